#pragma once
// The tree-width study's runs: which ones (the sweeps of the thesis' Ch. 4 and the third
// pipeline beyond it), and one run as a JSON line.
//
// A run is a pure function of its `Job`: the forest, the tree removal, the measurement noise
// and the filter's settings all come from the job's fields and the study seed, so a run gives
// the same bits in any process, thread or shard. Jobs are numbered in a fixed order
// (`enumerateJobs`); `--shard K/N` takes those with index % N == K - 1.
//
// Seeds (sylva::sim::deriveSeed, SplitMix64): map m of the study seed S has forest seed
// F = deriveSeed(S, 1000 + m) (trees from makeForestTrees(options, F)); removal r at density
// fraction f draws from deriveSeed(F, 5000 + 1000 r + round(1000 f)); noise draw d uses the
// noise stream deriveSeed(F, 10000 + d). The same map and draw give the same noise sequence at
// every noise level (common random numbers: the noise sweep's curves are not jagged by
// draws), and the three pipelines always see the same measurements (paired comparison).

#include <cmath>
#include <cstdint>
#include <functional>
#include <map>
#include <utility>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include <sylva/sim/forest_scenario.hpp>

#include "forest_run.hpp"
#include "monocular_tree_slam.hpp"

namespace tree_width_study {

using forest_slam::WidthPipeline;

constexpr WidthPipeline kAllPipelines[] = {
    WidthPipeline::kNone, WidthPipeline::kAfterXyz, WidthPipeline::kFromFirstSight};

/// One run.
struct Job {
  int index = 0;
  std::string sweep;  ///< "gain", "noise" or "density"
  WidthPipeline pipeline = WidthPipeline::kNone;
  bool occlusion = false;  ///< true: only non-occluded trees are measured (thesis Sec. 4.4)
  int map = 0;
  int draw = 0;                 ///< noise draw
  int removal = -1;             ///< tree removal (density sweep), -1: none
  double density = 1.0;         ///< fraction of the map's trees kept
  double pixel_sigma_px = 1.0;  ///< simulated noise on u, v and w
  double pixel_scale = 1.5;     ///< the filter's sigma on u, v = pixel_scale * pixel_sigma_px
  double width_scale = 1.0;     ///< the filter's sigma on w = width_scale * pixel_sigma_px
  /// XYZ -> XYZ-R once the tree position's largest sigma is below this (TreeSlamOptions).
  double tree_position_sigma_m = forest_slam::TreeSlamOptions{}.tree_position_sigma_m;
  /// "default": the filter settings every pipeline shares; "tuned": the pipeline's own best
  /// setting, chosen by `tree_width_study tune` on maps the sweeps never score (tuning.hpp).
  std::string setting = "default";
};

/// A pipeline's filter settings in the noise and density sweeps.
struct FilterSetting {
  double pixel_scale = 1.5;
  double width_scale = 1.0;
  double tree_position_sigma_m = forest_slam::TreeSlamOptions{}.tree_position_sigma_m;
  bool operator==(const FilterSetting& o) const {
    return pixel_scale == o.pixel_scale && width_scale == o.width_scale &&
           tree_position_sigma_m == o.tree_position_sigma_m;
  }
  bool operator!=(const FilterSetting& o) const { return !(*this == o); }
};

/// (pipeline name, occlusion key) -> the best setting found by the tuning sweep.
using TunedSettings = std::map<std::pair<std::string, std::string>, FilterSetting>;

inline const char* occlusionKey(bool occlusion) {
  return occlusion ? "non_occluded_only" : "ignored";
}

/// The sizes of the three sweeps.
struct StudyPlan {
  std::uint64_t seed = 1;
  int maps = 10;  ///< thesis: 10 maps
  // Gain selection (Sec. 4.2): measurement-noise scalings at 1 px simulated noise.
  std::vector<double> gain_pixel_scales_no_width{0.5, 1.0, 1.5, 2.0, 3.0, 4.0};
  std::vector<double> gain_pixel_scales{1.0, 1.5, 2.0, 3.0};
  std::vector<double> gain_width_scales{0.5, 1.0, 2.0, 4.0};
  // Noise sweep (Sec. 4.3.1, 4.4.1): sigma = 1..10 px, 10 maps x 10 draws.
  std::vector<double> noise_levels_px{1, 2, 3, 4, 5, 6, 7, 8, 9, 10};
  int noise_draws = 10;
  // Density sweep (Sec. 4.3.2, 4.4.2): 3 removals x 3 draws per map and fraction.
  std::vector<double> densities{1.0, 0.9, 0.8, 0.7, 0.6, 0.5};
  int removals = 3;
  int density_draws = 3;
  double density_noise_px = 1.0;
  // The filter's noise scales in the noise and density sweeps (TreeSlamOptions' defaults).
  double pixel_scale = 1.5;
  double width_scale = 1.0;
  // The reruns at each pipeline's tuned setting: the same maps, levels and densities with the
  // first of the noise draws and removals (half the noise sweep's runs, a third of the
  // density sweep's), every pipeline on the same measurements as before.
  int tuned_noise_draws = 5;
  int tuned_removals = 3;
  int tuned_density_draws = 1;

  /// The reduced sweep of --quick: every noise level and density of the full study, on 5
  /// maps with fewer draws, and a smaller gain grid (1050 runs at the shared setting, about 4
  /// minutes on 2 cores, and one noise draw per map for the reruns at the tuned settings).
  static StudyPlan quick() {
    StudyPlan p;
    p.maps = 5;
    p.gain_pixel_scales_no_width = {1.0, 1.5, 3.0};
    p.gain_pixel_scales = {1.5};
    p.gain_width_scales = {0.5, 1.0, 2.0};
    p.noise_draws = 2;
    p.removals = 1;
    p.density_draws = 2;
    p.tuned_noise_draws = 1;
    p.tuned_removals = 1;
    p.tuned_density_draws = 1;
    return p;
  }
};

/// All runs of `plan`, in their fixed order. With `tuned`, the noise and density sweeps are
/// run a second time (with the plan's tuned_* draws) for every pipeline and occlusion mode
/// whose tuned setting differs from the shared default; those runs come last (setting
/// "tuned"), so the default runs keep their indices whether or not a tuning exists.
inline std::vector<Job> enumerateJobs(const StudyPlan& plan, const TunedSettings* tuned = nullptr) {
  std::vector<Job> jobs;
  const auto push = [&jobs](Job j) {
    j.index = static_cast<int>(jobs.size());
    jobs.push_back(j);
  };
  for (bool occlusion : {false, true}) {
    for (WidthPipeline pipeline : kAllPipelines) {
      const bool width = pipeline != WidthPipeline::kNone;
      const std::vector<double>& pixel_scales =
          width ? plan.gain_pixel_scales : plan.gain_pixel_scales_no_width;
      const std::vector<double> width_scales =
          width ? plan.gain_width_scales : std::vector<double>{plan.width_scale};
      for (double ps : pixel_scales)
        for (double ws : width_scales)
          for (int m = 0; m < plan.maps; ++m) {
            Job j;
            j.sweep = "gain";
            j.pipeline = pipeline;
            j.occlusion = occlusion;
            j.map = m;
            j.pixel_scale = ps;
            j.width_scale = ws;
            push(j);
          }
    }
  }
  const FilterSetting shared{plan.pixel_scale, plan.width_scale, Job{}.tree_position_sigma_m};
  const auto sweeps = [&](const std::string& setting_name, int noise_draws, int removals, int density_draws,
                          const std::function<const FilterSetting*(WidthPipeline, bool)>& setting_of) {
    // One run of this setting: its sweep, pipeline, map and noise draw, and the filter setting.
    const auto job = [&](const char* sweep, WidthPipeline pipeline, bool occlusion, int map, int draw) {
      Job j;
      j.sweep = sweep;
      j.pipeline = pipeline;
      j.occlusion = occlusion;
      j.map = map;
      j.draw = draw;
      const FilterSetting* f = setting_of(pipeline, occlusion);
      j.pixel_scale = f->pixel_scale;
      j.width_scale = f->width_scale;
      j.tree_position_sigma_m = f->tree_position_sigma_m;
      j.setting = setting_name;
      return j;
    };
    for (bool occlusion : {false, true})
      for (WidthPipeline pipeline : kAllPipelines) {
        if (!setting_of(pipeline, occlusion)) continue;
        for (double sigma : plan.noise_levels_px)
          for (int m = 0; m < plan.maps; ++m)
            for (int d = 0; d < noise_draws; ++d) {
              Job j = job("noise", pipeline, occlusion, m, d);
              j.pixel_sigma_px = sigma;
              push(j);
            }
      }
    for (bool occlusion : {false, true})
      for (WidthPipeline pipeline : kAllPipelines) {
        if (!setting_of(pipeline, occlusion)) continue;
        for (double f : plan.densities)
          for (int m = 0; m < plan.maps; ++m)
            for (int r = 0; r < (f < 1.0 ? removals : 1); ++r)
              for (int d = 0; d < density_draws; ++d) {
                Job j = job("density", pipeline, occlusion, m, d);
                j.removal = f < 1.0 ? r : -1;
                j.density = f;
                j.pixel_sigma_px = plan.density_noise_px;
                push(j);
              }
      }
  };
  sweeps("default", plan.noise_draws, plan.removals, plan.density_draws,
         [&](WidthPipeline, bool) { return &shared; });
  if (tuned)
    sweeps("tuned", plan.tuned_noise_draws, plan.tuned_removals, plan.tuned_density_draws,
           [&](WidthPipeline pipeline, bool occlusion) -> const FilterSetting* {
      const auto it = tuned->find({forest_slam::pipelineName(pipeline), occlusionKey(occlusion)});
      return it == tuned->end() || it->second == shared ? nullptr : &it->second;
    });
  return jobs;
}

inline std::uint64_t forestSeed(std::uint64_t study_seed, int map) {
  return sylva::sim::deriveSeed(study_seed, 1000 + static_cast<std::uint64_t>(map));
}

/// The scenario of `job`: map, removal and noise draw.
inline sylva::sim::ForestScenario makeScenario(const Job& job, std::uint64_t study_seed) {
  sylva::sim::ForestScenarioOptions options;
  options.observer.sigma_px = job.pixel_sigma_px;
  options.observer.sigma_width_px = job.pixel_sigma_px;
  options.observer.occlusion = job.occlusion;
  const std::uint64_t forest = forestSeed(study_seed, job.map);
  std::vector<sylva::sim::Tree> trees = sylva::sim::makeForestTrees(options, forest);
  if (job.removal >= 0) {
    sylva::sim::Rng rng(
        sylva::sim::deriveSeed(forest,
                               5000 + 1000 * static_cast<std::uint64_t>(job.removal) +
                                   static_cast<std::uint64_t>(std::llround(1000 * job.density))));
    trees = sylva::sim::thinForest(trees, job.density, rng);
  }
  return sylva::sim::observeForest(
      options,
      std::move(trees),
      sylva::sim::deriveSeed(forest, 10000 + static_cast<std::uint64_t>(job.draw)));
}

inline nlohmann::json finiteOrNull(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}

/// Runs `job` and returns its JSON line: the configuration, the seeds and the metrics (no
/// timings, so that lines are identical wherever they were computed). `nees_every`: camera
/// pose NEES every this many frames (0: none); `max_frames` > 0 cuts the run short.
inline nlohmann::json runJob(const Job& job,
                             std::uint64_t study_seed,
                             int nees_every,
                             int max_frames = 0) {
  const sylva::sim::ForestScenario scenario = makeScenario(job, study_seed);
  forest_slam::TreeSlamOptions options;
  options.camera = scenario.options.camera;
  options.pipeline = job.pipeline;
  options.pixel_sigma_px = job.pixel_scale * job.pixel_sigma_px;
  options.width_sigma_px = job.width_scale * job.pixel_sigma_px;
  options.tree_position_sigma_m = job.tree_position_sigma_m;
  nlohmann::json out;
  out["job"] = job.index;
  out["sweep"] = job.sweep;
  out["pipeline"] = forest_slam::pipelineName(job.pipeline);
  out["occlusion"] = occlusionKey(job.occlusion);
  out["map"] = job.map;
  out["draw"] = job.draw;
  out["removal"] = job.removal;
  out["density"] = job.density;
  out["pixel_sigma_px"] = job.pixel_sigma_px;
  out["pixel_scale"] = job.pixel_scale;
  out["width_scale"] = job.width_scale;
  out["tree_position_sigma_m"] = job.tree_position_sigma_m;
  out["setting"] = job.setting;
  out["study_seed"] = study_seed;
  out["forest_seed"] = forestSeed(study_seed, job.map);
  out["trees"] = scenario.trees.size();
  const forest_slam::RunResult r =
      forest_slam::runForestSlam(scenario, options, max_frames, nees_every);
  out["landmark_error"] = finiteOrNull(r.landmark_error);
  out["trajectory_error"] = finiteOrNull(r.trajectory_error);
  out["converged"] = r.converged;
  out["radius_rmse_m"] = finiteOrNull(r.radius_rmse_m);
  out["trees_by_parametrization"] = {{"inverse_depth", r.by_type[0]},
                                     {"xyz", r.by_type[1]},
                                     {"xyzr", r.by_type[2]},
                                     {"idr", r.by_type[3]}};
  out["rejected_observations"] = r.rejected;
  nlohmann::json nees = nlohmann::json::array();
  for (double v : r.pose_nees) nees.push_back(finiteOrNull(v));
  out["pose_nees_every"] = nees_every;
  out["pose_nees"] = nees;
  if (!r.failure.empty()) out["failure"] = r.failure;
  return out;
}

}  // namespace tree_width_study
