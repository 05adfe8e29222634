#pragma once
/// @file
/// `sim::makeForestScenario`: everything the monocular tree-SLAM experiments need, from one
/// options struct and a seed (tree-width thesis, Sec. 4.1.1): the forest (`generateForest`,
/// trees kept clear of the path), the camera driving a Bezier loop through the waypoints
/// `laps` times (`forestTrajectory`; default: two laps, as in the thesis), and the noisy
/// tree measurements of every frame (`TreeObserver`, ids as data association).
///
/// Random streams: the forest uses deriveSeed(seed, 1), the measurement noise
/// deriveSeed(seed, 2); the same seed and options give the same scenario bit for bit, and the
/// noise can change (another seed) only together with the forest.

#include <cmath>
#include <cstdint>
#include <vector>

#include "sylva/core/types.hpp"
#include "sylva/measurements/pinhole_camera.hpp"
#include "sylva/sim/bezier_loop_2d.hpp"
#include "sylva/sim/forest_trajectory.hpp"
#include "sylva/sim/random.hpp"
#include "sylva/sim/tree_forest.hpp"
#include "sylva/sim/tree_observer.hpp"

namespace sylva::sim {

/// Eight waypoints on a slightly irregular loop of about 9 m radius about the origin.
inline std::vector<Vec<2>> defaultForestWaypoints() {
  std::vector<Vec<2>> points;
  for (int k = 0; k < 8; ++k) {
    const double a = k * 3.14159265358979323846 / 4.0;
    const double radius = k % 2 == 0 ? 9.5 : 8.0;
    points.emplace_back(radius * std::cos(a), radius * std::sin(a));
  }
  return points;
}

struct ForestScenarioOptions {
  PinholeCamera camera{500.0, 500.0, 320.0, 240.0, 640, 480};
  ForestOptions forest;
  TrajectoryOptions trajectory;
  ObserverOptions observer;
  std::vector<Vec<2>> waypoints = defaultForestWaypoints();
};

struct ForestScenario {
  ForestScenarioOptions options;
  std::vector<Tree> trees;
  std::vector<CameraFrame> frames;
  std::vector<std::vector<TreeObservation>> observations;  ///< one list per frame

  /// The true tree with id `id` (ids are 0..N-1, in order).
  const Tree& tree(Id id) const { return trees.at(static_cast<std::size_t>(id)); }
};

inline ForestScenario makeForestScenario(const ForestScenarioOptions& options, std::uint64_t seed) {
  options.camera.validate();
  ForestScenario scenario;
  scenario.options = options;
  const BezierLoop2D path(options.waypoints);
  std::vector<Vec<2>> keep_clear;
  for (double s = 0.0; s < path.length(); s += 0.25) keep_clear.push_back(path.position(s));
  Rng forest_rng(deriveSeed(seed, 1));
  scenario.trees = generateForest(options.forest, forest_rng, keep_clear);
  const ForestOptions& forest = options.forest;
  scenario.frames = forestTrajectory(path, options.trajectory,
                                     [&forest](double x, double y) { return forest.groundElevation(x, y); });
  const TreeObserver observer(options.camera, options.observer);
  Rng noise_rng(deriveSeed(seed, 2));
  scenario.observations.reserve(scenario.frames.size());
  for (const CameraFrame& frame : scenario.frames)
    scenario.observations.push_back(observer.observe(frame.state, scenario.trees, noise_rng));
  return scenario;
}

}  // namespace sylva::sim
