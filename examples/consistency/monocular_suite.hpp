#pragma once
// The `monocular` and `monocular-forests` suites of examples/consistency: the monocular
// tree-SLAM pipelines of examples/forest_slam (MonocularTreeSlam) on the forest simulator.
//
//   monocular          the default forest (forest_slam's seed 26), `draws` noise draws of it:
//                      draw i measures with the noise stream deriveSeed(26, 1000 + i);
//   monocular-forests  forests 1..30, each with its own noise (makeForestScenario(seed)),
//                      as scripts/forest_slam_seeds.py runs them.
//
// Recorded per run, every 10th frame: the camera-pose NEES (6 dof) and that of its position
// and orientation alone (3 each), from sylva::cameraPoseError in the filter's own frame (it
// starts at the true first pose, so no alignment is needed or allowed); the NIS of every
// observation of a mapped tree at the predicted state, by parametrization; the landmark and
// trajectory errors after similarity alignment and convergence (forest_run.hpp).

#include <array>
#include <vector>
#include <cstdint>
#include <string>

#include <sylva/consistency/monte_carlo.hpp>
#include <sylva/sim/forest_scenario.hpp>
#include <sylva/sim/random.hpp>

#include "forest_run.hpp"
#include "monocular_tree_slam.hpp"

namespace consistency {

constexpr int kNeesEvery = 10;  ///< frames between two NEES samples

/// The statistics of one ensemble of one pipeline and mode.
struct MonocularEnsemble {
  sylva::NeesEnsemble pose{6}, position{3}, orientation{3};
  /// NIS at the predicted state by parametrization: inverse depth and XYZ (2 dof), XYZ-R and
  /// IDR (3 dof).
  std::array<sylva::NisTally, 4> nis = forest_slam::FrameReport::emptyNisTallies();
  int runs = 0;
  int converged = 0;
  std::vector<bool> converged_by_run;  ///< each run's convergence, in run order (paired comparisons)
  double landmark_error_sum = 0.0;    ///< e_l (m^2) over converged runs
  double trajectory_error_sum = 0.0;  ///< e_t (m^2) over converged runs
};

/// The scenario of run `run` of a suite: a noise draw of the default forest, or forest run + 1.
inline sylva::sim::ForestScenario monocularScenario(bool many_forests, int run, double pixel_noise_px) {
  sylva::sim::ForestScenarioOptions options;
  options.observer.sigma_px = pixel_noise_px;
  options.observer.sigma_width_px = pixel_noise_px;
  if (many_forests) return sylva::sim::makeForestScenario(options, static_cast<std::uint64_t>(run) + 1);
  const std::uint64_t forest = forest_slam::kDefaultForestSeed;
  return sylva::sim::observeForest(options, sylva::sim::makeForestTrees(options, forest),
                                   sylva::sim::deriveSeed(forest, 1000 + static_cast<std::uint64_t>(run)));
}

/// Adds the statistics of one run (`forest_slam::runForestSlam` with NEES every kNeesEvery
/// frames) to `out` as run `run`.
inline void addMonocularRun(const forest_slam::RunResult& r, int run, MonocularEnsemble& out) {
  // A covariance that is no longer positive definite (infinite NEES) is a diverged run: kept
  // as +inf, which the median tolerates.
  for (std::size_t k = 0; k < r.pose_nees.size(); ++k) {
    out.pose.add(run, static_cast<int>(k), r.pose_nees[k]);
    out.position.add(run, static_cast<int>(k), r.position_nees[k]);
    out.orientation.add(run, static_cast<int>(k), r.orientation_nees[k]);
  }
  for (std::size_t t = 0; t < 4; ++t) out.nis[t].merge(r.nis[t]);
  ++out.runs;
  if (static_cast<int>(out.converged_by_run.size()) <= run) out.converged_by_run.resize(static_cast<std::size_t>(run) + 1, false);
  out.converged_by_run[static_cast<std::size_t>(run)] = r.converged;
  if (r.converged) {
    ++out.converged;
    out.landmark_error_sum += r.landmark_error;
    out.trajectory_error_sum += r.trajectory_error;
  }
}

}  // namespace consistency
