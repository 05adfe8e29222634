// consistency: does the filter's covariance tell the truth? Monte Carlo NEES and NIS of
// sylva's filters on named suites, for each linearization mode that applies.
//
// Suites (--suite, comma-separated; default planar,monocular,monocular-forests):
//   planar             the range_bearing_slam world, two laps, known association, the true
//                      noise given to the filter; --ensembles ensembles (seeds 1..10) of
//                      --runs runs (50). Modes: textbook, first_estimates, invariant,
//                      iterated, ideal.
//   monocular          the default forest of forest_slam, 1 px noise, --runs noise draws (50),
//                      for each tree pipeline (none, thesis, first_sight) and mode (textbook,
//                      first_estimates, iterated, ideal); and the textbook and ideal filters
//                      with the camera's velocity in its own frame (<pipeline>/camera_velocity/
//                      <mode>). The filter's noise is the pipelines' default (TreeSlamOptions).
//   monocular-forests  forests 1..30, one run each, the same pipelines and modes.
//   monocular-factors  the experiment behind docs/consistency.md: every combination of
//                      linearization (textbook, ideal), the filter's pixel noise (the true 1 px
//                      or the default 1.5 px), the NIS gate (on, off), the point models'
//                      (u, v) (the base ellipse's centre, or the projection of the base centre:
//                      without the model's bias) and the linear acceleration noise of the
//                      motion model (the default or --raised-accel), for each pipeline, --runs
//                      noise draws of the default forest.
//   monocular-tuning   the study that chooses the motion model's acceleration noise, on forests
//                      101..100 + --forests, which no other suite scores: each pipeline, the
//                      textbook and first-estimates filters, each of --tuning-accels.
//   monocular-motion   the motion-model study, on the same forests: the frame of the camera's
//                      linear velocity (world, camera) and each of --motion-accels, for each
//                      pipeline, the textbook and the ideal filter.
//   monocular-gauge    on the same forests, the observability-constrained update with the
//                      camera-frame velocity and each left inverse of its transport
//                      (GaugeInverse: robot, whole_state), each pipeline.
//   monocular-manifold on the same forests, the camera's state on its manifold
//                      (OnManifold<ConstantVelocity3D>, covariance on the 12-dimensional
//                      tangent) against its quaternion's four entries (<pipeline>/<mode>/
//                      manifold, .../quaternion), the camera-frame velocity, the textbook and
//                      the observability-constrained filter; each entry lists run_nees and
//                      run_converged for the paired comparison.
//
// Modes: textbook = every Jacobian at the latest estimate; first_estimates = FEJ (Huang,
// Mourikis and Roumeliotis 2010); invariant = the right-invariant EKF (Barrau and Bonnabel
// 2015; planar robots only: the camera declares no planar frame); iterated = Gauss-Newton
// iterations of each update (the filter's default stopping rule); ideal = predict and update
// linearized about the true state, a diagnostic that separates linearization error from model
// error.
//
// Every entry: nees_mean (mean over steps of the ensemble-average NEES), nees_median_run (the
// median over runs of each run's time-average NEES), nees_bounds (two-sided 95% bounds of the
// ensemble average of `runs` runs), fraction_inside (share of steps whose ensemble average
// lies inside them; over several ensembles the smallest, and fraction_inside_by_seed lists
// each), runs, dof; the same for the parts of the pose (position, heading or orientation);
// the NIS per measurement type at the predicted state; the monocular suites add
// convergence_ratio and the errors of the converged runs. --json prints one object
// {"<suite>": {"<mode>": {...}}}; infinite values (a diverged run) print as null.
//
// Reproducible bit for bit from the flags; --threads only changes the speed.

#include <cmath>
#include <cstdio>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "../common/run_pool.hpp"
#include "monocular_suite.hpp"
#include "planar_suite.hpp"

namespace {

using nlohmann::json;
using sylva::LinearizationPoint;

json number(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

json summaryJson(const sylva::NeesEnsemble& ensemble) {
  const auto s = ensemble.summary();
  return {{"nees_mean", number(s.mean)},
          {"nees_median_run", number(s.median_run)},
          {"nees_bounds", {s.lower, s.upper}},
          {"fraction_inside", s.fraction_inside},
          {"runs", s.runs},
          {"dof", s.dof}};
}

json nisJson(const sylva::NisTally& t) {
  if (t.count() == 0) return {{"count", 0}};
  const auto [lo, hi] = t.bounds();
  return {{"mean", t.mean()},
          {"bounds", {lo, hi}},
          {"fraction_above_95", t.fractionAbove()},
          {"count", t.count()},
          {"dof", t.dof()}};
}

struct Mode {
  const char* name;
  LinearizationPoint point;
};
constexpr Mode kPlanarModes[] = {{"textbook", LinearizationPoint::kCurrentEstimate},
                                 {"first_estimates", LinearizationPoint::kFirstEstimates},
                                 {"invariant", LinearizationPoint::kInvariant},
                                 {"iterated", LinearizationPoint::kIterated},
                                 {"ideal", LinearizationPoint::kIdeal}};
constexpr Mode kMonocularModes[] = {{"textbook", LinearizationPoint::kCurrentEstimate},
                                    {"first_estimates", LinearizationPoint::kFirstEstimates},
                                    {"iterated", LinearizationPoint::kIterated},
                                    {"observability_constrained", LinearizationPoint::kObservabilityConstrained},
                                    {"ideal", LinearizationPoint::kIdeal}};

struct Pipeline {
  const char* name;
  forest_slam::WidthPipeline pipeline;
};
constexpr Pipeline kPipelines[] = {{"none", forest_slam::WidthPipeline::kNone},
                                   {"thesis", forest_slam::WidthPipeline::kAfterXyz},
                                   {"first_sight", forest_slam::WidthPipeline::kFromFirstSight}};

struct Settings {
  int runs = 50;
  int ensembles = 10;
  int forests = 30;
  int threads = 2;
  bool progress = true;
};

// ---------------------------------------------------------------------------- planar

json planarSuite(const Settings& settings) {
  struct Job {
    int mode, ensemble;
  };
  std::vector<Job> jobs;
  for (int m = 0; m < static_cast<int>(std::size(kPlanarModes)); ++m)
    for (int e = 0; e < settings.ensembles; ++e) jobs.push_back({m, e});
  const auto results = sylva_examples::runAll<consistency::PlanarEnsemble>(
      static_cast<int>(jobs.size()), settings.threads,
      [&](int i) {
        const Job& job = jobs[static_cast<std::size_t>(i)];
        const std::uint64_t seed = static_cast<std::uint64_t>(job.ensemble) + 1;
        const consistency::PlanarWorld world = consistency::makePlanarWorld(seed);
        consistency::PlanarEnsemble out;
        for (int run = 0; run < settings.runs; ++run)
          consistency::runPlanar(world, kPlanarModes[job.mode].point, seed, run, out);
        return out;
      },
      settings.progress);

  json suite;
  for (int m = 0; m < static_cast<int>(std::size(kPlanarModes)); ++m) {
    // Over the ensembles: fraction_inside is the smallest, nees_mean the mean of the
    // ensembles' means, nees_median_run the median over every run of every ensemble.
    json entry;
    sylva::NisTally nis(2);
    double final_error = 0.0, landmark_sq = 0.0;
    long long landmarks = 0, runs = 0;
    json parts = json::object();
    for (const auto& [part, pick] : std::vector<std::pair<const char*, int>>{{"pose", 0}, {"position", 1}, {"heading", 2}}) {
      std::vector<double> part_fractions, part_runs;
      double part_mean = 0.0;
      json first;
      for (int e = 0; e < settings.ensembles; ++e) {
        const auto& r = results[static_cast<std::size_t>(m * settings.ensembles + e)];
        const sylva::NeesEnsemble& series = pick == 0 ? r.pose : pick == 1 ? r.position : r.heading;
        const auto s = series.summary();
        part_fractions.push_back(s.fraction_inside);
        part_mean += s.mean / settings.ensembles;
        for (double v : series.runAverages()) part_runs.push_back(v);
        if (e == 0) first = summaryJson(series);
      }
      std::sort(part_runs.begin(), part_runs.end());
      const std::size_t n = part_runs.size();
      const double median = n % 2 ? part_runs[n / 2] : 0.5 * (part_runs[n / 2 - 1] + part_runs[n / 2]);
      json j = first;
      j["nees_mean"] = number(part_mean);
      j["nees_median_run"] = number(median);
      j["fraction_inside"] = *std::min_element(part_fractions.begin(), part_fractions.end());
      j["fraction_inside_by_seed"] = part_fractions;
      j["ensembles"] = settings.ensembles;
      if (pick == 0) {
        entry = j;
      } else {
        parts[part] = j;
      }
    }
    for (int e = 0; e < settings.ensembles; ++e) {
      const auto& r = results[static_cast<std::size_t>(m * settings.ensembles + e)];
      nis.merge(r.range_bearing_nis);
      final_error += r.final_position_error_sum_m;
      landmark_sq += r.landmark_squared_error_sum;
      landmarks += r.landmarks_mapped;
      runs += r.runs;
    }
    entry["parts"] = parts;
    entry["nis"] = {{"range_bearing", nisJson(nis)}};
    entry["final_position_error_m"] = final_error / static_cast<double>(runs);
    entry["landmark_rmse_m"] = std::sqrt(landmark_sq / static_cast<double>(landmarks));
    entry["seeds"] = {1, settings.ensembles};
    suite[kPlanarModes[m].name] = entry;
  }
  return suite;
}

// ---------------------------------------------------------------------------- monocular

/// One configuration of the monocular pipeline.
struct MonocularConfig {
  std::string key;
  forest_slam::TreeSlamOptions options;
};

json monocularEntry(const consistency::MonocularEnsemble& e) {
  json j = summaryJson(e.pose);
  j["parts"] = {{"position", summaryJson(e.position)}, {"orientation", summaryJson(e.orientation)}};
  const char* names[] = {"inverse_depth", "xyz", "xyzr", "idr"};
  json nis = json::object();
  for (std::size_t t = 0; t < 4; ++t)
    if (e.nis[t].count() > 0) nis[names[t]] = nisJson(e.nis[t]);
  j["nis"] = nis;
  j["convergence_ratio"] = static_cast<double>(e.converged) / e.runs;
  j["landmark_error_converged_m2"] = e.converged > 0 ? number(e.landmark_error_sum / e.converged) : json(nullptr);
  j["trajectory_error_converged_m2"] = e.converged > 0 ? number(e.trajectory_error_sum / e.converged) : json(nullptr);
  // Each run's time-averaged pose NEES and its convergence, in run order: the suites run the
  // same scenarios for every mode, so two modes compare run by run (paired).
  json run_nees = json::array();
  for (const double v : e.pose.runAverages()) run_nees.push_back(number(v));
  j["run_nees"] = run_nees;
  j["run_converged"] = e.converged_by_run;
  return j;
}

/// Which scenarios a monocular suite runs.
enum class Scenarios { kDefaultForestDraws, kForests, kTuningForests };

json monocularSuite(const std::vector<MonocularConfig>& configs, Scenarios scenarios, int runs, const Settings& settings) {
  const double pixel_noise_px = 1.0;
  const int jobs = static_cast<int>(configs.size()) * runs;
  const auto results = sylva_examples::runAll<forest_slam::RunResult>(
      jobs, settings.threads,
      [&](int i) {
        const MonocularConfig& config = configs[static_cast<std::size_t>(i / runs)];
        const int run = i % runs;
        const sylva::sim::ForestScenario scenario =
            scenarios == Scenarios::kDefaultForestDraws ? consistency::monocularScenario(false, run, pixel_noise_px)
            : scenarios == Scenarios::kForests          ? consistency::monocularScenario(true, run, pixel_noise_px)
                                                        : consistency::monocularScenario(true, 100 + run, pixel_noise_px);
        forest_slam::TreeSlamOptions options = config.options;
        options.camera = scenario.options.camera;
        return forest_slam::runForestSlam(scenario, options, 0, consistency::kNeesEvery);
      },
      settings.progress);
  json suite;
  for (std::size_t c = 0; c < configs.size(); ++c) {
    consistency::MonocularEnsemble ensemble;
    for (int r = 0; r < runs; ++r) consistency::addMonocularRun(results[c * static_cast<std::size_t>(runs) + static_cast<std::size_t>(r)], r, ensemble);
    suite[configs[c].key] = monocularEntry(ensemble);
  }
  return suite;
}

/// The pipeline's default options with linearization `point`. The observability-constrained
/// filter keeps the map's position and scale uncertain, so its life cycle judges landmarks
/// given the camera (TreeSlamOptions::conversion_given_camera).
forest_slam::TreeSlamOptions pipelineOptions(const Pipeline& p, LinearizationPoint point) {
  forest_slam::TreeSlamOptions o;
  o.pipeline = p.pipeline;
  o.linearization = point;
  o.conversion_given_camera = point == LinearizationPoint::kObservabilityConstrained;
  return o;
}

/// pipeline/mode for every pipeline and monocular mode, the filter's noise at its default; and
/// pipeline/camera_velocity/mode, the same filter with the velocity in the camera frame
/// (ConstantVelocity3D::VelocityFrame::kCamera) at the same noise, for the textbook and the
/// ideal filter (first estimates diverge with either motion model: docs/consistency.md).
std::vector<MonocularConfig> monocularModes() {
  std::vector<MonocularConfig> out;
  for (const Pipeline& p : kPipelines) {
    for (const Mode& m : kMonocularModes) {
      out.push_back({std::string(p.name) + "/" + m.name, pipelineOptions(p, m.point)});
    }
    for (const Mode& m : kMonocularModes) {
      if (m.point != LinearizationPoint::kCurrentEstimate && m.point != LinearizationPoint::kObservabilityConstrained &&
          m.point != LinearizationPoint::kIdeal)
        continue;
      forest_slam::TreeSlamOptions o = pipelineOptions(p, m.point);
      o.velocity_frame = sylva::ConstantVelocity3D::VelocityFrame::kCamera;
      out.push_back({std::string(p.name) + "/camera_velocity/" + m.name, o});
    }
  }
  return out;
}

/// The factorial experiment: pipeline/linearization/pixel noise/gate/points/process noise,
/// every combination (textbook and ideal linearization only: the cause, not the cure).
std::vector<MonocularConfig> monocularFactors(double raised_accel) {
  std::vector<MonocularConfig> out;
  const forest_slam::TreeSlamOptions defaults;
  for (const Pipeline& p : kPipelines)
    for (const LinearizationPoint point : {LinearizationPoint::kCurrentEstimate, LinearizationPoint::kIdeal})
      for (const bool true_noise : {false, true})
        for (const bool gate : {true, false})
          for (const bool unbiased : {false, true})
            for (const bool raised : {false, true}) {
              forest_slam::TreeSlamOptions o = pipelineOptions(p, point);
              o.pixel_sigma_px = true_noise ? 1.0 : defaults.pixel_sigma_px;
              o.gate_probability = gate ? defaults.gate_probability : 0.0;
              o.unbiased_point_uv = unbiased;
              o.linear_accel_sigma = raised ? raised_accel : defaults.linear_accel_sigma;
              std::ostringstream key;
              key << p.name << "/" << (point == LinearizationPoint::kIdeal ? "ideal" : "textbook") << "/"
                  << (true_noise ? "true_pixel_noise" : "default_pixel_noise") << "/" << (gate ? "gate" : "no_gate") << "/"
                  << (unbiased ? "unbiased_points" : "ellipse_centre_points") << "/"
                  << (raised ? "raised_accel" : "default_accel");
              out.push_back({key.str(), o});
            }
  return out;
}

/// The motion-model study on the tuning forests (seeds 101..100 + N): the frame of the
/// constant-velocity model's linear velocity (world or camera) and its linear acceleration
/// noise, for every pipeline, the textbook filter and the ideal one (which shows what the
/// motion model alone does, without linearization error).
std::vector<MonocularConfig> monocularMotion(const std::vector<double>& accels) {
  using Frame = sylva::ConstantVelocity3D::VelocityFrame;
  std::vector<MonocularConfig> out;
  for (const Pipeline& p : kPipelines)
    for (const LinearizationPoint point : {LinearizationPoint::kCurrentEstimate, LinearizationPoint::kIdeal})
      for (const Frame frame : {Frame::kWorld, Frame::kCamera})
        for (const double accel : accels) {
          forest_slam::TreeSlamOptions o = pipelineOptions(p, point);
          o.velocity_frame = frame;
          o.linear_accel_sigma = accel;
          std::ostringstream key;
          key << p.name << "/"
              << (point == LinearizationPoint::kIdeal ? "ideal" : "textbook")
              << "/" << (frame == Frame::kCamera ? "camera_velocity" : "world_velocity") << "/accel_" << accel;
          out.push_back({key.str(), o});
        }
  return out;
}

/// The left inverse of the observability-constrained update (GaugeInverse) on the tuning
/// forests: the camera-frame velocity, the default noise, each pipeline, both inverses.
std::vector<MonocularConfig> monocularGauge() {
  std::vector<MonocularConfig> out;
  for (const Pipeline& p : kPipelines)
    for (const sylva::GaugeInverse inverse : {sylva::GaugeInverse::kRobot, sylva::GaugeInverse::kWholeState}) {
      forest_slam::TreeSlamOptions o = pipelineOptions(p, LinearizationPoint::kObservabilityConstrained);
      o.velocity_frame = sylva::ConstantVelocity3D::VelocityFrame::kCamera;
      o.gauge_inverse = inverse;
      out.push_back({std::string(p.name) + (inverse == sylva::GaugeInverse::kRobot ? "/robot" : "/whole_state"), o});
    }
  return out;
}

/// The camera's state on its manifold (OnManifold<ConstantVelocity3D>: covariance on the
/// 12-dimensional tangent, updates through plus) against its quaternion's four entries, on the
/// tuning forests: each pipeline, the camera-frame velocity, the textbook and the
/// observability-constrained filter.
std::vector<MonocularConfig> monocularManifold() {
  std::vector<MonocularConfig> out;
  for (const Pipeline& p : kPipelines)
    for (const LinearizationPoint point : {LinearizationPoint::kCurrentEstimate, LinearizationPoint::kObservabilityConstrained})
      for (const bool manifold : {false, true}) {
        forest_slam::TreeSlamOptions o = pipelineOptions(p, point);
        o.velocity_frame = sylva::ConstantVelocity3D::VelocityFrame::kCamera;
        o.camera_on_manifold = manifold;
        out.push_back({std::string(p.name) + "/" +
                           (point == LinearizationPoint::kCurrentEstimate ? "textbook" : "observability_constrained") +
                           (manifold ? "/manifold" : "/quaternion"),
                       o});
      }
  return out;
}

/// The process-noise study on forests no other suite scores (seeds 101..100 + N): every
/// pipeline and the textbook and first-estimates filters, for each linear-acceleration sigma.
std::vector<MonocularConfig> monocularTuning(const std::vector<double>& accels) {
  std::vector<MonocularConfig> out;
  for (const Pipeline& p : kPipelines)
    for (const LinearizationPoint point : {LinearizationPoint::kCurrentEstimate, LinearizationPoint::kFirstEstimates})
      for (const double accel : accels) {
        forest_slam::TreeSlamOptions o = pipelineOptions(p, point);
        o.linear_accel_sigma = accel;
        std::ostringstream key;
        key << p.name << "/" << (point == LinearizationPoint::kFirstEstimates ? "first_estimates" : "textbook")
            << "/accel_" << accel;
        out.push_back({key.str(), o});
      }
  return out;
}

// ---------------------------------------------------------------------------- table

void printTable(const json& all) {
  std::printf("%-18s %-62s %5s %4s %11s %11s %17s %7s %6s\n", "suite", "mode", "runs", "dof", "NEES mean", "median run",
              "95% bounds", "inside", "conv.");
  for (const auto& [suite, modes] : all.items()) {
    for (const auto& [mode, e] : modes.items()) {
      const auto fmt = [](const json& v) {
        char buf[32];
        if (v.is_null()) return std::string("inf");
        std::snprintf(buf, sizeof buf, "%.2f", v.get<double>());
        return std::string(buf);
      };
      char bounds[48];
      std::snprintf(bounds, sizeof bounds, "[%.2f, %.2f]", e["nees_bounds"][0].get<double>(), e["nees_bounds"][1].get<double>());
      std::printf("%-18s %-62s %5d %4d %11s %11s %17s %7.3f %6s\n", suite.c_str(), mode.c_str(), e["runs"].get<int>(),
                  e["dof"].get<int>(), fmt(e["nees_mean"]).c_str(), fmt(e["nees_median_run"]).c_str(), bounds,
                  e["fraction_inside"].get<double>(),
                  e.contains("convergence_ratio") ? fmt(e["convergence_ratio"]).c_str() : "-");
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"consistency: Monte Carlo NEES and NIS of sylva's filters on named suites"};
  app.option_defaults()->always_capture_default();  // every option shows its default in --help
  std::string suites = "planar,monocular,monocular-forests";
  Settings settings;
  bool json_output = false;
  app.add_option("--suite", suites,
                 "comma-separated: planar, monocular, monocular-forests, monocular-factors, monocular-tuning, "
                 "monocular-motion, monocular-gauge, monocular-manifold");
  app.add_option("--runs", settings.runs, "runs per ensemble (planar) or noise draws (monocular)")
      ->check(CLI::Range(2, 100000));
  app.add_option("--ensembles", settings.ensembles, "planar: ensembles, seeds 1..N")->check(CLI::Range(1, 1000));
  app.add_option("--forests", settings.forests, "monocular-forests: forests, seeds 1..N")->check(CLI::Range(2, 1000));
  app.add_option("--threads", settings.threads, "worker threads (results do not depend on it)")
      ->check(CLI::Range(1, 256));
  app.add_flag("--json", json_output, "print one JSON object {suite: {mode: {...}}}");
  double raised_accel = 1.0;
  app.add_option("--raised-accel", raised_accel, "monocular-factors: the raised linear acceleration sigma (m/s^2)")
      ->check(CLI::PositiveNumber);
  std::vector<double> tuning_accels{0.3, 0.5, 0.75, 1.0, 1.5, 2.0};
  app.add_option("--tuning-accels", tuning_accels, "monocular-tuning: the linear acceleration sigmas (m/s^2)");
  std::vector<double> motion_accels{0.1, 0.3, 1.0};
  app.add_option("--motion-accels", motion_accels, "monocular-motion: the linear acceleration sigmas (m/s^2)");
  bool quiet = false;
  app.add_flag("--quiet", quiet, "no progress on stderr");
  CLI11_PARSE(app, argc, argv);
  settings.progress = !quiet;

  std::vector<std::string> wanted;
  {
    std::stringstream ss(suites);
    for (std::string s; std::getline(ss, s, ',');)
      if (!s.empty()) wanted.push_back(s);
  }
  json all = json::object();
  try {
    for (const std::string& suite : wanted) {
      if (settings.progress) std::cerr << "consistency: suite " << suite << "\n";
      if (suite == "planar") {
        all[suite] = planarSuite(settings);
      } else if (suite == "monocular") {
        all[suite] = monocularSuite(monocularModes(), Scenarios::kDefaultForestDraws, settings.runs, settings);
      } else if (suite == "monocular-forests") {
        all[suite] = monocularSuite(monocularModes(), Scenarios::kForests, settings.forests, settings);
      } else if (suite == "monocular-factors") {
        all[suite] = monocularSuite(monocularFactors(raised_accel), Scenarios::kDefaultForestDraws, settings.runs, settings);
      } else if (suite == "monocular-tuning") {
        all[suite] = monocularSuite(monocularTuning(tuning_accels), Scenarios::kTuningForests, settings.forests, settings);
      } else if (suite == "monocular-gauge") {
        all[suite] = monocularSuite(monocularGauge(), Scenarios::kTuningForests, settings.forests, settings);
      } else if (suite == "monocular-manifold") {
        all[suite] = monocularSuite(monocularManifold(), Scenarios::kTuningForests, settings.forests, settings);
      } else if (suite == "monocular-motion") {
        all[suite] = monocularSuite(monocularMotion(motion_accels), Scenarios::kTuningForests, settings.forests, settings);
      } else {
        std::cerr << "consistency: unknown suite '" << suite
                  << "' (planar, monocular, monocular-forests, monocular-factors, monocular-tuning, "
                     "monocular-motion, monocular-gauge, monocular-manifold)\n";
        return 2;
      }
    }
  } catch (const sylva::Error& e) {
    std::cerr << "consistency: " << e.what() << "\n";
    return 1;
  }
  if (json_output)
    std::cout << all.dump(2) << "\n";
  else
    printTable(all);
  return 0;
}
