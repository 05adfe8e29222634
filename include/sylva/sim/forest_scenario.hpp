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
/// noise can change (another seed) only together with the forest. For experiments that keep
/// the forest and change the noise or thin the forest (the thesis' sweeps), build the parts
/// apart: `makeForestTrees`, `thinForest`, `observeForest`.

#include <cmath>
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "sylva/core/angles.hpp"
#include "sylva/core/error.hpp"
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
    const double a = k * kPi / 4.0;
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

/// The trees of the scenario `options` and `seed` describe (stream deriveSeed(seed, 1)),
/// kept clear of the camera's path.
inline std::vector<Tree> makeForestTrees(const ForestScenarioOptions& options, std::uint64_t seed) {
  options.camera.validate();
  const BezierLoop2D path(options.waypoints);
  std::vector<Vec<2>> keep_clear;
  for (double s = 0.0; s < path.length(); s += 0.25) keep_clear.push_back(path.position(s));
  Rng forest_rng(deriveSeed(seed, 1));
  return generateForest(options.forest, forest_rng, keep_clear);
}

/// A random `fraction` (in [0, 1]) of `trees`, round(fraction * N) of them chosen without
/// replacement, in their original order and renumbered 0..M-1 (the thesis' density sweep,
/// Sec. 4.3.2: "we randomly remove individual trees from each map").
inline std::vector<Tree> thinForest(const std::vector<Tree>& trees, double fraction, Rng& rng) {
  if (!(fraction >= 0.0 && fraction <= 1.0)) {
    std::ostringstream os;
    os << "thinForest: the fraction of trees to keep must be in [0, 1], got " << fraction;
    fail(ErrorCode::kInvalidArgument, os.str());
  }
  const std::size_t n = trees.size();
  const auto keep = static_cast<std::size_t>(std::llround(fraction * static_cast<double>(n)));
  // Partial Fisher-Yates on the indices: the first `keep` entries are a uniform sample.
  std::vector<std::size_t> index(n);
  for (std::size_t i = 0; i < n; ++i) index[i] = i;
  for (std::size_t i = 0; i < keep; ++i) {
    const std::size_t j = i + static_cast<std::size_t>(rng.uniform01() * static_cast<double>(n - i));
    std::swap(index[i], index[std::min(j, n - 1)]);
  }
  std::sort(index.begin(), index.begin() + static_cast<std::ptrdiff_t>(keep));
  std::vector<Tree> kept;
  kept.reserve(keep);
  for (std::size_t i = 0; i < keep; ++i) {
    Tree t = trees[index[i]];
    t.id = static_cast<Id>(kept.size());
    kept.push_back(t);
  }
  return kept;
}

/// The camera's frames over `options`' loop and the noisy measurements of `trees` in each
/// (noise stream `noise_seed`). Tree ids must be 0..N-1 in order.
inline ForestScenario observeForest(const ForestScenarioOptions& options, std::vector<Tree> trees, std::uint64_t noise_seed) {
  options.camera.validate();
  for (std::size_t i = 0; i < trees.size(); ++i) {
    if (trees[i].id != static_cast<Id>(i))
      fail(ErrorCode::kInvalidArgument, "observeForest: tree ids must be 0..N-1 in order (tree " + std::to_string(i) +
                                            " has id " + std::to_string(trees[i].id) + ")");
  }
  ForestScenario scenario;
  scenario.options = options;
  scenario.trees = std::move(trees);
  const BezierLoop2D path(options.waypoints);
  const ForestOptions& forest = options.forest;
  scenario.frames = forestTrajectory(path, options.trajectory,
                                     [&forest](double x, double y) { return forest.groundElevation(x, y); });
  const TreeObserver observer(options.camera, options.observer);
  Rng noise_rng(noise_seed);
  scenario.observations.reserve(scenario.frames.size());
  for (const CameraFrame& frame : scenario.frames)
    scenario.observations.push_back(observer.observe(frame.state, scenario.trees, noise_rng));
  return scenario;
}

inline ForestScenario makeForestScenario(const ForestScenarioOptions& options, std::uint64_t seed) {
  return observeForest(options, makeForestTrees(options, seed), deriveSeed(seed, 2));
}

}  // namespace sylva::sim
