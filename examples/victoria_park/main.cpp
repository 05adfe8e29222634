// victoria_park: EKF-SLAM on the Victoria Park data set (ACFR; Guivant and Nebot 2001,
// Guivant, Nebot and Baiker 2000): a car with a laser among trees, unknown association.
//
// Two variants on the same data and the same declared configuration (config.hpp):
//   point  Ekf<Ackermann2D, Point2>   with RangeBearing         (range, bearing)
//   tree   Ekf<Ackermann2D, TreeXYR>  with RangeBearingDiameter (range, bearing, diameter)
// The run is described in slam_run.hpp, the GPS comparison in sylva/datasets/victoria_park_gps.hpp, and the whole
// example in docs/examples/victoria-park.md.
//
// Output: one result per variant as text (examples/common/report.hpp), or with --json as
// {"config": ..., "point": {...}, "tree": {...}},
// --svg-prefix for a map per variant, --robustness for the 81-setting noise study
// (each of the four noise values x1.5, x1, /1.5), run on --threads threads,
// --compare-compressed for each variant run plain and with the compressed EKF (times, and the
// difference of the final states).
// Without data at --data the program says where to get it and exits with status 77.

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "../common/cli_checks.hpp"
#include "../common/report.hpp"
#include "../common/run_pool.hpp"
#include "config.hpp"
#include "slam_run.hpp"
#include "svg.hpp"

#ifndef VICTORIA_PARK_DEFAULT_DATA
#define VICTORIA_PARK_DEFAULT_DATA "../shared/data/victoria-park"
#endif

namespace {

using namespace victoria_park;
constexpr int kSkipped = 77;  // ctest's SKIP_RETURN_CODE

nlohmann::json toJson(const RunResult& r) {
  nlohmann::json j = {{"gps_rmse_m", r.gps.rmse_valid_m},
          {"gps_median_m", r.gps.median_valid_m},
          {"gps_rmse_all_m", r.gps.rmse_all_m},
          {"gps_max_valid_m", r.gps.max_valid_m},
          {"gps_fixes_valid", r.gps.valid},
          {"gps_fixes_total", r.gps.total},
          {"landmarks", r.landmarks},
          {"scans", r.scans},
          {"predictions", r.predictions},
          {"readings", r.readings},
          {"readings_paired", r.paired},
          {"readings_ambiguous", r.ambiguous},
          {"readings_tentative", r.tentative_readings},
          {"readings_refused", r.refused_updates},
          {"runtime_s", r.runtime_s},
          {"step_ms_end", r.step_ms_end},
          {"step_ms_mean", r.step_ms_mean}};
  if (std::isfinite(r.steering_offset_rad))
    j["bias_estimates"] = {{"speed_scale", r.speed_scale},
                           {"speed_scale_sigma", r.speed_scale_sigma},
                           {"steering_offset_rad", r.steering_offset_rad},
                           {"steering_offset_sigma_rad", r.steering_offset_sigma_rad}};
  return j;
}

struct Study {
  std::vector<double> rmse;
  int diverged = 0;
  double median = 0.0;
  double worst = 0.0;
  nlohmann::json runs = nlohmann::json::array();
};

/// The 81 settings: noise value i scaled by 1.5^(e_i), e_i in {-1, 0, 1}.
template <class V>
Study robustness(const sylva::datasets::VictoriaParkData& data, const Config& base, const std::vector<char>& valid,
                 int threads) {
  std::vector<Config> settings;
  std::vector<std::array<int, 4>> exponents;
  for (int a = -1; a <= 1; ++a)
    for (int b = -1; b <= 1; ++b)
      for (int c = -1; c <= 1; ++c)
        for (int d = -1; d <= 1; ++d) {
          Config cfg = base;
          cfg.noise.speed_mps *= std::pow(1.5, a);
          cfg.noise.steering_rad *= std::pow(1.5, b);
          cfg.noise.range_m *= std::pow(1.5, c);
          cfg.noise.bearing_rad *= std::pow(1.5, d);
          settings.push_back(cfg);
          exponents.push_back({a, b, c, d});
        }
  const std::vector<RunResult> results = sylva_examples::runAll<RunResult>(
      static_cast<int>(settings.size()), threads,
      [&](int i) { return runSlam<V>(data, settings[static_cast<std::size_t>(i)], valid); }, false);
  Study s;
  for (std::size_t i = 0; i < results.size(); ++i) {
    const double e = results[i].gps.rmse_valid_m;
    s.rmse.push_back(e);
    if (!(e <= 5.0)) ++s.diverged;
    s.runs.push_back({{"scale_exponents", exponents[i]}, {"gps_rmse_m", e}, {"landmarks", results[i].landmarks}});
  }
  std::vector<double> sorted = s.rmse;
  std::sort(sorted.begin(), sorted.end());
  s.median = sorted[sorted.size() / 2];
  s.worst = sorted.back();
  return s;
}

/// The largest entry of |a - b| over the largest of |b| (0 for empty states).
double relativeDifference(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  if (b.size() == 0) return 0.0;
  return (a - b).cwiseAbs().maxCoeff() / std::max(b.cwiseAbs().maxCoeff(), 1e-300);
}

/// Variant V plain and compressed on the same data: both times, and how far apart the final
/// states are (they are the same filter up to round-off, unless an association decision
/// flipped on a round-off difference). Returns whether they agree to 1e-9.
template <class V>
bool compareCompressed(const sylva::datasets::VictoriaParkData& data, const Config& cfg, const std::vector<char>& valid,
                       const char* name, nlohmann::json& out) {
  Config plain_cfg = cfg;
  plain_cfg.compress_radius_m = 0.0;
  FinalState plain_state, compressed_state;
  const RunResult plain = runSlam<V>(data, plain_cfg, valid, &plain_state);
  const RunResult compressed = runSlam<V>(data, cfg, valid, &compressed_state);
  const bool same_landmarks = plain_state.ids == compressed_state.ids;
  const double mean_difference = same_landmarks ? relativeDifference(compressed_state.mean, plain_state.mean) : INFINITY;
  const double covariance_difference =
      same_landmarks ? relativeDifference(compressed_state.covariance, plain_state.covariance) : INFINITY;
  const bool agree = same_landmarks && mean_difference <= 1e-9 && covariance_difference <= 1e-9;
  out[name] = {{"plain", toJson(plain)},
               {"compressed", toJson(compressed)},
               {"global_updates", compressed.global_updates},
               {"time_ratio", compressed.runtime_s / plain.runtime_s},
               {"same_landmarks", same_landmarks},
               {"mean_difference", mean_difference},
               {"covariance_difference", covariance_difference},
               {"agree", agree}};
  return agree;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"EKF-SLAM on the Victoria Park data set (point and tree landmarks, unknown association)"};
  app.option_defaults()->always_capture_default();  // every option shows its default in --help
  Config cfg;
  std::string data_dir = VICTORIA_PARK_DEFAULT_DATA;
  bool json = false, study = false;
  std::string svg_prefix, variants = "both";
  int threads = 2;
  std::string errors_csv;
  app.add_option("--data", data_dir, "folder with measurements.dat, odometry.txt, gps.txt");
  app.add_flag("--json", json, "print the results as JSON");
  app.add_option("--svg-prefix", svg_prefix, "write <prefix>_point.svg and <prefix>_tree.svg");
  app.add_option("--variant", variants, "point, tree or both")->check(CLI::IsMember({"point", "tree", "both"}));
  app.add_option("--duration", cfg.duration_s, "seconds of data to run (0: all)")->check(sylva_examples::positive(true));
  app.add_option("--association", cfg.association, "jcbb or nn")->check(CLI::IsMember({"jcbb", "nn"}));
  app.add_option("--linearization", cfg.linearization,
                 "first-estimates (FEJ), invariant (the right-invariant EKF) or current (the textbook EKF)")
      ->check(CLI::IsMember({"first-estimates", "invariant", "current"}));
  app.add_option("--bias-states", cfg.bias_states,
                 "biases estimated online (Ackermann2DWithBias): none, speed (encoder scale error), steering "
                 "(steering offset) or both")
      ->check(CLI::IsMember({"none", "speed", "steering", "both"}));
  app.add_option("--speed-scale-prior", cfg.speed_scale_prior, "prior sigma of the speed scale error")
      ->check(sylva_examples::positive(false));
  app.add_option("--steering-offset-prior", cfg.steering_offset_prior_rad, "prior sigma of the steering offset (rad)")
      ->check(sylva_examples::positive(false));
  app.add_option("--speed-scale-walk", cfg.speed_scale_walk, "random walk of the speed scale error (1/sqrt(s))")
      ->check(sylva_examples::positive(false));
  app.add_option("--steering-offset-walk", cfg.steering_offset_walk_rad, "random walk of the steering offset (rad/sqrt(s))")
      ->check(sylva_examples::positive(false));
  app.add_option("--gate", cfg.gate_probability, "probability of the association's chi-square gates")
      ->check(CLI::Range(0.5, 0.999999));
  app.add_option("--predict", cfg.predict, "scan (integrate odometry between scans) or odometry (predict per sample)")
      ->check(CLI::IsMember({"scan", "odometry"}));
  app.add_option("--laser-left", cfg.laser_left_m, "laser lateral offset b (m, + = left)")->check(sylva_examples::finite(false));
  app.add_option("--max-range", cfg.max_range_m, "detections farther away are ignored (m)")->check(sylva_examples::positive(false));
  app.add_option("--sigma-speed", cfg.noise.speed_mps, "encoder speed noise per 40 Hz sample (m/s)")->check(sylva_examples::positive(false));
  app.add_option("--sigma-steering", cfg.noise.steering_rad, "steering noise per 40 Hz sample (rad)")->check(sylva_examples::positive(false));
  app.add_option("--sigma-range", cfg.noise.range_m, "range noise (m)")->check(sylva_examples::positive(false));
  app.add_option("--sigma-bearing", cfg.noise.bearing_rad, "bearing noise (rad)")->check(sylva_examples::positive(false));
  app.add_option("--sigma-diameter", cfg.diameter_sigma_m, "diameter noise (m)")->check(sylva_examples::positive(false));
  app.add_option("--confirm", cfg.confirm_sightings, "sightings that confirm a new landmark")->check(CLI::Range(1, 100));
  app.add_option("--errors-csv", errors_csv, "write <prefix>_<variant>.csv: time, aligned GPS error, valid flag per fix");
  app.add_flag("--robustness", study, "run the 81-setting noise study (every noise value x1.5, x1, /1.5)");
  app.add_option("--threads", threads, "threads for the robustness study")->check(CLI::Range(1, 64));
  app.add_option("--compress-radius", cfg.compress_radius_m,
                 "the compressed EKF's region radius (m; 0: the plain filter; needs --linearization current)")
      ->check(sylva_examples::positive(true));
  app.add_option("--compress-ahead", cfg.compress_ahead_m, "the region's centre ahead of the car (m)")
      ->check(sylva_examples::finite(false));
  bool compare_compressed = false;
  app.add_flag("--compare-compressed", compare_compressed,
               "run each variant plain and compressed (--compress-radius, default 2 x --max-range, centred "
               "--max-range ahead), report both times and the largest difference of the final states, and exit 1 "
               "if they differ by more than 1e-9 of their largest entry");
  CLI11_PARSE(app, argc, argv);
  if (compare_compressed && cfg.compress_radius_m == 0.0) {
    cfg.compress_radius_m = 2.0 * cfg.max_range_m;
    cfg.compress_ahead_m = cfg.max_range_m;
  }
  if (cfg.compress_radius_m > 0.0 && cfg.linearization == "invariant") {
    std::cerr << "victoria_park: the compressed EKF (--compress-radius, --compare-compressed) needs --linearization "
                 "current (or first-estimates with --bias-states none): the invariant update, the default, transforms "
                 "the whole covariance at every update\n";
    return 2;
  }
  if (cfg.bias_states != "none" && cfg.linearization == "first-estimates") {
    std::cerr << "victoria_park: --linearization first-estimates needs --bias-states none (the default is '"
              << Config().bias_states << "'): the car with bias states has no first-estimates Jacobian (its biases "
                                         "couple the heading to the estimate); or use --linearization invariant or current\n";
    return 2;
  }

  if (!std::filesystem::exists(data_dir + "/measurements.dat")) {
    std::cerr << "victoria_park: SKIPPED: no measurements.dat in '" << data_dir
              << "'. The Victoria Park data set (ACFR, J. Guivant and E. Nebot) is not part of sylva: get "
                 "measurements.dat (kykleung/RFS-SLAM, data/VictoriaPark), and odometry.txt and gps.txt converted "
                 "from aa3_dr.mat and aa3_gpsx.mat (see docs/examples/victoria-park.md), then pass the folder "
                 "with --data DIR.\n";
    return kSkipped;
  }
  try {
    const auto data = sylva::datasets::loadVictoriaPark(data_dir);
    const std::vector<char> valid = sylva::datasets::validVictoriaParkGpsFixes(data.gps, data.odometry, cfg.wheelbase_m, cfg.encoder_offset_m);
    nlohmann::json out;
    out["config"] = toJson(cfg);
    out["data"] = data_dir;
    bool agree = true;
    const auto report = [&](auto variant, const char* name, const char* title) {
      using V = decltype(variant);
      if (compare_compressed) {
        agree = compareCompressed<V>(data, cfg, valid, name, out) && agree;
        return;
      }
      const RunResult r = runSlam<V>(data, cfg, valid);
      out[name] = toJson(r);
      if (!svg_prefix.empty()) writeSvg(svg_prefix + "_" + name + ".svg", r, data.gps, valid, title);
      if (!errors_csv.empty()) {
        std::ofstream f(errors_csv + "_" + name + ".csv");
        f << "t_s,error_m,valid\n";
        for (std::size_t i = 0; i < r.gps.fix_t_s.size(); ++i)
          f << r.gps.fix_t_s[i] << "," << r.gps.fix_error_m[i] << "," << int(r.gps.fix_valid[i]) << "\n";
      }
      if (study) {
        const Study s = robustness<V>(data, cfg, valid, threads);
        out[name]["robustness"] = {{"settings", s.rmse.size()}, {"diverged_over_5m", s.diverged},
                                   {"median_gps_rmse_m", s.median}, {"worst_gps_rmse_m", s.worst}, {"runs", s.runs}};
      }
    };
    if (variants != "tree") report(PointVariant{}, "point", "Victoria Park, EKF-SLAM with point landmarks (range, bearing)");
    if (variants != "point") report(TreeVariant{}, "tree", "Victoria Park, EKF-SLAM with tree landmarks (range, bearing, diameter)");
    sylva_examples::writeResult(std::cout, json, "victoria_park: EKF-SLAM on the Victoria Park recording", out);
    if (!agree) return 1;
  } catch (const sylva::Error& e) {
    std::cerr << "victoria_park: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
