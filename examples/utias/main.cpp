// utias: 2D EKF-SLAM on the UTIAS MRCLAM Dataset 7 (real data), one run per robot with
// known correspondences (barcodes) and one with unknown correspondences (JCBB).
//
// Data: K. Y. K. Leung, Y. Halpern, T. D. Barfoot, H. H. T. Liu, "The UTIAS Multi-Robot
// Cooperative Localization and Mapping Dataset", IJRR 30(8):969-974, 2011. Five robots
// drive among 15 barcoded landmarks for 900 s; each logs velocity commands (~67 Hz) and
// range-bearing observations from a camera; Vicon gives the ground truth of robots and
// landmarks. The data are not part of sylva (see docs/examples/utias.md for where to get
// them); the default folder is ../shared/data/utias-mrclam/MRCLAM_Dataset7 beside the
// repository.
//
// The filter: sylva::Ekf<Unicycle2D, Point2> with RangeBearing and InverseRangeBearing,
// stepped from event to event (slam_run.hpp), with the one declared noise configuration of
// noise_model.hpp for every robot. Scores against the Vicon ground truth (evaluation.hpp):
// trajectory RMS in the Vicon frame and after the rigid alignment of the map, landmark RMS
// after that alignment, mean pose NEES, and the association statistics of JCBB.
//
// --noise-study prints the statistics the noise configuration is read off (residuals.hpp);
// --study the grid of noise settings (selection.hpp); --leave-one-out fits the delay, the
// command calibration and the setting on four robots and scores the fifth (fit.hpp). Every
// output is labelled with the recording's name (the folder of --data), and a robot is scored
// only where its ground truth exists (evaluation.hpp).
// Run `utias --help` for the flags.

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <sylva/datasets/utias_mrclam.hpp>

#include "../common/cli_checks.hpp"
#include "../common/report.hpp"
#include "../common/text.hpp"
#include "../common/planar_map_svg.hpp"
#include "evaluation.hpp"
#include "fit.hpp"
#include "residuals.hpp"
#include "selection.hpp"
#include "slam_run.hpp"

#ifndef UTIAS_DEFAULT_DATA
#define UTIAS_DEFAULT_DATA "../shared/data/utias-mrclam/MRCLAM_Dataset7"
#endif

namespace {

using sylva_examples::fixed;

using nlohmann::json;
using sylva::Vec;

struct Options {
  std::string data = UTIAS_DEFAULT_DATA;
  bool data_given = false;  // --data was passed: a missing recording is then an error, not a skip
  int robot = 0;  // 0: all five
  double max_time_s = 0.0;
  bool json = false;
  bool noise_study = false;
  bool study = false;
  bool leave_one_out = false;
  std::string svg_prefix;
  utias::NoiseConfig noise;
};

struct RobotReport {
  int robot = 0;
  utias::RunResult known, jcbb;
  utias::Scores known_scores, jcbb_scores;
  long unknown_barcodes = 0;
  long robot_observations = 0;
  double duration_s = 0.0;
};

/// The recording's name: the last component of the --data folder (e.g. "MRCLAM_Dataset7").
std::string recordingName(const std::string& folder) {
  std::filesystem::path p = std::filesystem::path(folder).lexically_normal();
  if (p.filename().empty()) p = p.parent_path();  // "dir/" -> "dir"
  const std::string name = p.filename().string();
  return name.empty() || name == "." || name == ".." ? std::filesystem::absolute(p).lexically_normal().filename().string()
                                                     : name;
}

/// Round to 4 significant decimals for the JSON (the figures are not more precise than that).
double r4(double v) { return std::round(v * 1e4) / 1e4; }

json configJson(const utias::NoiseConfig& c) {
  return json{{"command_delay_s", c.command_delay_s},
              {"command_jitter_s", c.command_jitter_s},
              {"v_gain", c.v_gain},
              {"v_turn_loss_m_per_rad", c.v_turn_loss},
              {"omega_gain", c.omega_gain},
              {"omega_bias_radps", c.omega_bias},
              {"v_scale_per_sqrt_s", c.v_scale},
              {"v_floor_m_per_sqrt_s", c.v_floor},
              {"omega_scale_per_sqrt_s", c.omega_scale},
              {"omega_floor_rad_per_sqrt_s", c.omega_floor},
              {"sigma_range_m", c.sigma_range_m},
              {"sigma_range_per_m", c.sigma_range_per_m},
              {"sigma_bearing_rad", c.sigma_bearing_rad},
              {"landmark_interval_s", c.landmark_interval_s},
              {"initial_sigma", {c.initial_sigma[0], c.initial_sigma[1], c.initial_sigma[2]}},
              {"outlier_gate_probability", c.outlier_gate_probability},
              {"jcbb_gate_probability", c.jcbb_gate_probability},
              {"jcbb_noise_scale", c.jcbb_noise_scale},
              {"new_landmark_probability", c.new_landmark_probability},
              {"candidate_range_m", c.candidate_range_m},
              {"candidate_half_fov_rad", c.candidate_half_fov_rad},
              {"online_gains", c.online_gains},
              {"gain_sigma", {c.gain_sigma[0], c.gain_sigma[1], c.gain_sigma[2]}},
              {"gain_walk", {c.gain_walk[0], c.gain_walk[1], c.gain_walk[2]}}};
}

json robotJson(const RobotReport& r) {
  const auto& k = r.known_scores;
  const auto& j = r.jcbb_scores;
  const auto& a = r.jcbb.counts;
  json out{{"robot", r.robot},
              {"known_rmse_m", r4(k.rmse_m)},
              {"known_aligned_rmse_m", r4(k.aligned_rmse_m)},
              {"jcbb_aligned_rmse_m", r4(j.aligned_rmse_m)},
              {"landmark_aligned_rmse_m", r4(k.landmark_aligned_rmse_m)},
              {"nees_mean", r4(k.nees_mean)},
              {"known_final_error_m", r4(k.final_error_m)},
              {"known_landmark_rmse_m", r4(k.landmark_rmse_m)},
              {"known_landmarks", k.landmarks_mapped},
              {"known_gated_out", r.known.counts.gated_out},
              {"jcbb_rmse_m", r4(j.rmse_m)},
              {"jcbb_landmark_aligned_rmse_m", r4(j.landmark_aligned_rmse_m)},
              {"jcbb_nees_mean", r4(j.nees_mean)},
              {"jcbb_landmarks", j.landmarks_mapped},
              {"jcbb_landmark_subjects", j.subjects_mapped},
              {"jcbb_association",
               {{"observations", a.observations},
                {"paired", a.paired},
                {"correct", a.correct},
                {"wrong", a.wrong},
                {"wrong_same_cluster", a.wrong_same_cluster},
                {"new", a.added},
                {"duplicates", a.duplicates},
                {"ambiguous", a.ambiguous}}},
              {"dead_reckoning_rmse_m", r4(k.dead_reckoning_rmse_m)},
              {"landmark_observations", r.known.counts.observations},
              {"skipped", {{"unknown_barcode", r.unknown_barcodes}, {"robot_observations", r.robot_observations}}},
              {"duration_s", r4(r.duration_s)},
              {"samples", k.samples},
              {"samples_scored", k.samples_scored},
              {"truth_end_s", r4(k.truth_end_s)},
              {"scored_until_s", r4(k.last_scored_s)},
              {"truth_ends_early", k.truthEndsEarly()},
              {"runtime_known_s", r4(r.known.runtime_s)},
              {"runtime_jcbb_s", r4(r.jcbb.runtime_s)}};
  if (r.known.online_gains) {
    // The known-correspondence filter's online gains [k_v, k_w, b_w] at the end, and sigmas.
    out["online_gains"] = {{"k_v", r4(r.known.gains[0])}, {"k_w", r4(r.known.gains[1])}, {"b_w_radps", r4(r.known.gains[2])},
                           {"sigmas", {r4(r.known.gain_sigmas[0]), r4(r.known.gain_sigmas[1]), r4(r.known.gain_sigmas[2])}}};
  }
  return out;
}

/// Every `stride`-th point of a path (and its last one).
template <typename Get>
std::vector<Vec<2>> thinned(std::size_t n, std::size_t stride, Get get) {
  std::vector<Vec<2>> out;
  for (std::size_t k = 0; k < n; k += stride) out.push_back(get(k));
  if (n > 0) out.push_back(get(n - 1));
  return out;
}

void writeSvg(const std::string& file,
              const std::string& recording,
              const RobotReport& r,
              const utias::GroundTruth& gt,
              const std::vector<sylva::datasets::UtiasLandmark>& truth) {
  sylva_examples::SvgMapData m;
  const auto& run = r.known;
  const std::size_t n = run.samples.size();
  const std::size_t stride = std::max<std::size_t>(1, n / 2000);
  m.true_path = thinned(n, stride, [&](std::size_t k) { return Vec<2>(gt.at(run.samples[k].time_s).head<2>()); });
  m.estimated_path = thinned(n, stride, [&](std::size_t k) { return Vec<2>(run.samples[k].pose.head<2>()); });
  m.odometry_path = thinned(n, stride, [&](std::size_t k) { return Vec<2>(run.dead_reckoning[k].head<2>()); });
  for (const auto& l : truth) {
    m.true_landmarks.push_back(l.position_m);
    bool mapped = false;
    for (const auto& e : run.landmarks) mapped = mapped || e.subject == l.subject;
    m.true_landmark_mapped.push_back(mapped);
  }
  for (const auto& e : run.landmarks) m.estimated_landmarks.push_back({e.mean, e.covariance});
  m.start_pose = gt.at(run.samples.front().time_s);
  m.true_final_pose = gt.at(run.samples.back().time_s);
  m.estimated_final_pose = run.samples.back().pose;
  m.final_position_covariance = run.samples.back().covariance.topLeftCorner<2, 2>();
  m.sensor_range_fov = Vec<2>(8.4, 0.6);
  m.title = "UTIAS " + recording + ", robot " + std::to_string(r.robot) + ": EKF-SLAM with known correspondences";
  const auto& k = r.known_scores;
  const auto& j = r.jcbb_scores;
  m.subtitle_lines = {
      fixed(r.duration_s, 0) + " s, Vicon frame: trajectory RMS " + fixed(k.rmse_m, 3) + " m (dead reckoning " +
          fixed(k.dead_reckoning_rmse_m, 2) + " m), mean pose NEES " + fixed(k.nees_mean, 2),
      "after aligning the map: trajectory RMS " + fixed(k.aligned_rmse_m, 3) + " m, landmark RMS " +
          fixed(k.landmark_aligned_rmse_m, 3) + " m; with JCBB instead of barcodes: trajectory " +
          fixed(j.aligned_rmse_m, 3) + " m, " + std::to_string(j.landmarks_mapped) + " landmarks"};
  sylva_examples::writeSvgMap(file, m);
}

int noiseStudy(const Options& o, const sylva::datasets::UtiasDataset& data) {
  json robots = json::array();
  auto spreadJson = [](const utias::Spread& s) {
    return json{{"count", s.count},       {"mean", r4(s.mean)},       {"sigma", r4(s.sigma)},
                {"robust_sigma", r4(s.robust_sigma)}, {"beyond_3_robust_sigma", r4(s.beyond3)},
                {"beyond_5_robust_sigma", r4(s.beyond5)}};
  };
  utias::MeasurementResiduals pooled;
  std::vector<double> along[3], heading[3];
  for (const auto& r : data.robots) {
    const auto m = utias::measurementResiduals(data, r);
    pooled.range_m.insert(pooled.range_m.end(), m.range_m.begin(), m.range_m.end());
    pooled.bearing_rad.insert(pooled.bearing_rad.end(), m.bearing_rad.begin(), m.bearing_rad.end());
    robots.push_back({{"robot", r.robot},
                      {"range_m", spreadJson(utias::spreadOf(m.range_m))},
                      {"bearing_rad", spreadJson(utias::spreadOf(m.bearing_rad))}});
    const auto c = utias::commandResiduals(r, 1.0, o.noise.command_delay_s);
    for (std::size_t k = 0; k < c.along_m.size(); ++k) {
      const double v = c.mean_speed_mps[k], w = c.mean_turn_radps[k];
      along[v < 0.005 ? 0 : v < 0.06 ? 1 : 2].push_back(c.along_m[k]);
      heading[w < 0.02 ? 0 : w < 0.2 ? 1 : 2].push_back(c.heading_rad[k]);
    }
  }
  json lag = json::array();
  for (int ms = 0; ms <= 400; ms += 50) {
    json row{{"lag_s", ms / 1000.0}};
    for (const auto& r : data.robots) row["robot" + std::to_string(r.robot)] = r4(utias::turnRateLagRms(r, ms / 1000.0));
    lag.push_back(row);
  }
  utias::CommandCalibration pooled_calibration;
  utias::ResidualCorrelation correlation;
  json calibration = json::array();
  const double window = 1.0;
  for (const auto& r : data.robots) {
    const auto cal = utias::commandCalibration(r, window, o.noise.command_delay_s);
    pooled_calibration.add(cal);
    correlation.add(data, r);
    const Eigen::Vector2d w = cal.turn(window), d = cal.distance();
    calibration.push_back({{"robot", r.robot}, {"omega_gain", r4(w[0])}, {"omega_bias_radps", r4(w[1])},
                           {"v_gain", r4(d[0])}, {"v_turn_loss_m_per_rad", r4(d[1])}});
  }
  {
    const Eigen::Vector2d w = pooled_calibration.turn(window), d = pooled_calibration.distance();
    calibration.push_back({{"robot", "pooled"}, {"omega_gain", r4(w[0])}, {"omega_bias_radps", r4(w[1])},
                           {"v_gain", r4(d[0])}, {"v_turn_loss_m_per_rad", r4(d[1])}});
  }
  json corr = json::array();
  for (std::size_t b = 0; b < correlation.pairs.size(); ++b)
    corr.push_back({{"lag_up_to_s", correlation.lag_edges_s[b]}, {"pairs", correlation.pairs[b]},
                    {"range", r4(correlation.correlation(b, 0))}, {"bearing", r4(correlation.correlation(b, 1))}});
  json j{{"turn_rate_rms_by_command_lag_radps", lag},
         {"command_calibration_1s_windows", calibration},
         {"residual_correlation_same_landmark", corr},
         {"measurements", robots},
         {"measurements_pooled",
          {{"range_m", spreadJson(utias::spreadOf(pooled.range_m))},
           {"bearing_rad", spreadJson(utias::spreadOf(pooled.bearing_rad))}}},
         {"commands_1s",
          {{"along_m_by_speed", {{"below_0.005_mps", spreadJson(utias::spreadOf(along[0]))},
                                 {"0.005_to_0.06_mps", spreadJson(utias::spreadOf(along[1]))},
                                 {"above_0.06_mps", spreadJson(utias::spreadOf(along[2]))}}},
           {"heading_rad_by_turn_rate", {{"below_0.02_radps", spreadJson(utias::spreadOf(heading[0]))},
                                         {"0.02_to_0.2_radps", spreadJson(utias::spreadOf(heading[1]))},
                                         {"above_0.2_radps", spreadJson(utias::spreadOf(heading[2]))}}}}}};
  sylva_examples::writeResult(std::cout, o.json, "utias --noise-study: residuals of the measurements and commands against the ground truth", j);
  return 0;
}

/// The note printed when a robot's ground truth does not cover its whole run (empty if it does).
std::string coverageNote(int robot, const utias::Scores& s) {
  std::string note;
  if (s.truthEndsEarly())
    note = "robot " + std::to_string(robot) + ": ground truth ends at t = " + fixed(s.truth_end_s, 1) +
           " s, scored until then (" + std::to_string(s.samples_after_truth) + " of " + std::to_string(s.samples) +
           " samples after it not scored; the run ends at t = " + fixed(s.run_end_s, 1) + " s)";
  if (s.samplesInGaps() > 0)
    note += (note.empty() ? "robot " + std::to_string(robot) + ": " : "; ") + std::to_string(s.samplesInGaps()) +
            " samples in gaps of the ground truth longer than " + fixed(utias::GroundTruth::kDefaultMaxGapS, 1) +
            " s not scored";
  return note;
}

json summaryJson(const utias::TargetSummary& t) {
  return json{{"robots", t.robots},
              {"aligned_rmse_mean_m", r4(t.aligned_mean_m)},
              {"aligned_rmse_worst_m", r4(t.aligned_worst_m)},
              {"vicon_rmse_mean_m", r4(t.vicon_mean_m)},
              {"vicon_rmse_worst_m", r4(t.vicon_worst_m)},
              {"landmark_aligned_rmse_worst_m", r4(t.landmark_worst_m)},
              {"nees_min", r4(t.nees_min)},
              {"nees_max", r4(t.nees_max)},
              {"targets_met", t.met()},
              {"targets_met_each",
               {{"aligned_mean", t.alignedMeanMet()},
                {"aligned_worst", t.alignedWorstMet()},
                {"vicon_mean", t.viconMeanMet()},
                {"vicon_worst", t.viconWorstMet()},
                {"landmark_worst", t.landmarkMet()},
                {"nees_band", t.neesMet()}}},
              {"smallest_margin", r4(t.smallestMargin())}};
}

json settingJson(const utias::GridSetting& g) {
  return json{{"process", g.process}, {"range", g.range}, {"bearing_rad", g.bearing_rad}};
}

json commandFitJson(const utias::CommandFit& c) {
  return json{{"command_delay_s", c.delay_s},   {"v_gain", c.v_gain},         {"v_turn_loss_m_per_rad", c.v_turn_loss},
              {"omega_gain", c.omega_gain},     {"omega_bias_radps", c.omega_bias}, {"windows", c.windows},
              {"spread", {c.spread[0], c.spread[1], c.spread[2]}}};
}

utias::RobotSet allRobots(const sylva::datasets::UtiasDataset& data) {
  utias::RobotSet out;
  for (const auto& r : data.robots) out.push_back(&r);
  return out;
}

/// The study behind the noise settings: the known-correspondence run of every robot for each
/// setting of the grid of selection.hpp (the same setting for all robots; delay, calibration
/// and everything else as given), one row per setting with the figures, how many of
/// its targets it meets, the smallest margin, and the setting the declared rule picks (`chosen`).
int configurationStudy(const Options& o, const sylva::datasets::UtiasDataset& data) {
  const auto grid = utias::studyGrid();
  const auto summaries = utias::gridSummaries(allRobots(data), data.landmarks, o.noise, o.max_time_s);
  const std::size_t chosen = utias::selectSetting(summaries);
  json settings = json::array();
  for (std::size_t k = 0; k < grid.size(); ++k)
    settings.push_back({{"setting", settingJson(grid[k])}, {"summary", summaryJson(summaries[k])}, {"chosen", k == chosen}});
  sylva_examples::writeResult(
      std::cout, o.json, "utias --study: the noise settings of the grid on every robot (chosen: the declared rule's pick)",
      json{{"recording", recordingName(o.data)},
           {"robots", data.robots.size()},
           {"base_config", configJson(o.noise)},
           {"settings", settings}});
  return 0;
}

/// Leave-one-robot-out (fit.hpp): for each robot, the fitting procedure on the others and the
/// robot scored with its result; then the procedure on all robots (the default's rule).
int leaveOneOut(const Options& o, const sylva::datasets::UtiasDataset& data) {
  if (data.robots.size() < 2)
    sylva::fail(sylva::ErrorCode::kInvalidArgument, "--leave-one-out needs at least two robots (do not pass --robot)");
  const std::string recording = recordingName(o.data);
  const auto grid = utias::studyGrid();
  json rotations = json::array();
  std::vector<utias::RobotFigures> held_out;
  std::vector<std::string> notes;
  for (const auto& robot : data.robots) {
    utias::RobotSet training;
    for (const auto& r : data.robots)
      if (r.robot != robot.robot) training.push_back(&r);
    const utias::ConfigurationFit fit = utias::fitConfiguration(training, data.landmarks, o.noise, o.max_time_s);
    const utias::Scores s = utias::scoreKnown(robot, data.landmarks, fit.config, o.max_time_s);
    held_out.push_back(utias::figuresOf(s));
    const std::string note = coverageNote(robot.robot, s);
    if (!note.empty()) notes.push_back(note);
    json training_robots = json::array();
    for (const auto* r : training) training_robots.push_back(r->robot);
    const auto& c = fit.commands;
    rotations.push_back({{"held_out_robot", robot.robot},
                         {"training_robots", training_robots},
                         {"commands", commandFitJson(c)},
                         {"setting", settingJson(fit.setting)},
                         {"training", summaryJson(fit.grid[fit.chosen])},
                         {"held_out",
                          {{"aligned_rmse_m", r4(s.aligned_rmse_m)},
                           {"vicon_rmse_m", r4(s.rmse_m)},
                           {"landmark_aligned_rmse_m", r4(s.landmark_aligned_rmse_m)},
                           {"nees_mean", r4(s.nees_mean)},
                           {"samples", s.samples},
                           {"samples_scored", s.samples_scored},
                           {"truth_ends_early", s.truthEndsEarly()},
                           {"scored_until_s", r4(s.last_scored_s)}}}});
  }
  const utias::TargetSummary summary = utias::summarize(held_out);
  // The default's rule: the same procedure on every robot.
  const utias::ConfigurationFit all = utias::fitConfiguration(allRobots(data), data.landmarks, o.noise, o.max_time_s);
  const utias::NoiseConfig compiled;
  const bool default_matches = utias::hasCommandFit(compiled, all.commands) && utias::hasSetting(compiled, all.setting);
  json all_grid = json::array();
  for (std::size_t k = 0; k < grid.size(); ++k)
    all_grid.push_back({{"setting", settingJson(grid[k])}, {"summary", summaryJson(all.grid[k])}});
  json all_robots{{"commands", commandFitJson(all.commands)},
                  {"setting", settingJson(all.setting)},
                  {"summary", summaryJson(all.grid[all.chosen])},
                  {"compiled_default_matches", default_matches},
                  {"grid", all_grid}};
  sylva_examples::writeResult(std::cout, o.json,
                              "utias --leave-one-out: fit on the other robots, score the held-out one",
                              json{{"recording", recording},
                                   {"mode", "leave_one_robot_out"},
                                   {"rotations", rotations},
                                   {"held_out_summary", summaryJson(summary)},
                                   {"all_robots", all_robots},
                                   {"notes", notes},
                                   {"max_time_s", o.max_time_s},
                                   {"base_config", configJson(o.noise)}});
  return 0;
}

int run(const Options& o) {
  if (o.data_given && !std::filesystem::exists(std::filesystem::path(o.data) / "Barcodes.dat")) {
    // Only the default location may be absent (a user's fresh machine); a folder the user
    // named must hold a recording.
    std::cerr << "utias: --data '" << o.data << "': "
              << (std::filesystem::is_directory(o.data) ? "no Barcodes.dat in this folder (not a MRCLAM recording)"
                                                        : "no such folder")
              << "\n";
    return 2;
  }
  if (!std::filesystem::exists(std::filesystem::path(o.data) / "Barcodes.dat")) {
    std::cerr << "utias: SKIPPED: no UTIAS MRCLAM dataset in '" << o.data << "'.\n"
              << "  Get MRCLAM_Dataset7 (17 .dat files) from the UTIAS MRCLAM page,\n"
              << "  http://asrl.utias.utoronto.ca/datasets/mrclam/ (Leung et al., IJRR 30(8) 2011),\n"
              << "  unpack it and pass its folder with --data DIR (default: ../shared/data/utias-mrclam/"
                 "MRCLAM_Dataset7 beside the repository).\n";
    return 77;
  }
  sylva::datasets::UtiasLoadOptions lo;
  if (o.robot > 0) lo.robots = {o.robot};
  const sylva::datasets::UtiasDataset data = sylva::datasets::loadUtiasMrclam(o.data, lo);
  if (o.noise_study) return noiseStudy(o, data);
  if (o.study) return configurationStudy(o, data);
  if (o.leave_one_out) return leaveOneOut(o, data);
  const std::string recording = recordingName(o.data);

  // Clusters of landmarks for the association statistics only: true positions closer than
  // 0.5 m, joined transitively (the data's landmarks stand in groups of two or three).
  std::map<int, int> cluster_of;
  for (const auto& l : data.landmarks) cluster_of[l.subject] = l.subject;
  for (bool changed = true; changed;) {
    changed = false;
    for (const auto& a : data.landmarks)
      for (const auto& b : data.landmarks)
        if ((a.position_m - b.position_m).norm() < 0.5 && cluster_of[a.subject] > cluster_of[b.subject]) {
          cluster_of[a.subject] = cluster_of[b.subject];
          changed = true;
        }
  }
  std::vector<RobotReport> reports;
  for (const auto& robot : data.robots) {
    RobotReport r;
    r.robot = robot.robot;
    r.unknown_barcodes = static_cast<long>(robot.unknown_barcode_rows.size());
    r.robot_observations = static_cast<long>(robot.robot_observations.size());
    const utias::GroundTruth gt(robot.groundtruth);
    r.known = utias::runSlam(robot, o.noise, utias::Association::kKnown, o.max_time_s);
    r.jcbb = utias::runSlam(robot, o.noise, utias::Association::kJcbb, o.max_time_s, &cluster_of);
    r.known_scores = utias::score(r.known, gt, data.landmarks);
    r.jcbb_scores = utias::score(r.jcbb, gt, data.landmarks);
    r.duration_s = r.known.samples.empty() ? 0.0 : r.known.samples.back().time_s - robot.groundtruth.front().time_s;
    if (!o.svg_prefix.empty()) writeSvg(o.svg_prefix + "_robot" + std::to_string(r.robot) + ".svg", recording, r, gt, data.landmarks);
    reports.push_back(std::move(r));
  }

  json robots = json::array();
  for (const auto& r : reports) robots.push_back(robotJson(r));
  json notes = json::array();
  for (const auto& r : reports)
    if (const std::string n = coverageNote(r.robot, r.known_scores); !n.empty()) notes.push_back(n);
  sylva_examples::writeResult(std::cout, o.json,
                              "utias: EKF-SLAM on " + recording + " (UTIAS MRCLAM, Leung et al. IJRR 2011); known: "
                              "barcodes give the landmark; jcbb: associateJcbb, barcodes only to score",
                              json{{"recording", recording}, {"robots", robots}, {"notes", notes}, {"config", configJson(o.noise)}});
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  using sylva_examples::positive;
  Options o;
  CLI::App app{
      "EKF-SLAM (sylva::Ekf<Unicycle2D, Point2>, RangeBearing) on a UTIAS MRCLAM recording (Leung et al., "
      "IJRR 30(8) 2011), each robot with known (barcodes) and unknown (JCBB) correspondences; scores "
      "against the Vicon ground truth."};
  app.option_defaults()->always_capture_default();  // every option shows its default in --help
  app.footer(
      "One noise configuration for all robots (examples/utias/noise_model.hpp, docs/examples/utias.md).\n"
      "Get the data from http://asrl.utias.utoronto.ca/datasets/mrclam/ and pass the folder with --data.");
  CLI::Option* data_option =
      app.add_option("--data", o.data, "folder of one MRCLAM recording (Barcodes.dat, Robot1_Odometry.dat, ...); its name labels the output");
  app.add_option("--robot", o.robot, "robot 1-5 (0: all five)")->check(CLI::Range(0, 5));
  app.add_option("--max-time", o.max_time_s, "stop after this many seconds of data (0: all)")
      ->check(positive(true));
  app.add_flag("--json", o.json, "print one JSON object instead of text");
  app.add_option("--svg-prefix", o.svg_prefix, "write <prefix>_robot<N>.svg for each robot");
  app.add_flag("--noise-study", o.noise_study,
               "print the residual statistics of measurements and commands against the ground truth");
  app.add_flag("--study", o.study,
               "run the known-correspondence filter of every robot over the 36 noise settings of the grid "
               "(examples/utias/selection.hpp; they replace the command and measurement noise flags) with the "
               "delay and calibration given, one row per setting, and mark the one the declared rule picks");
  app.add_flag("--leave-one-out", o.leave_one_out,
               "leave-one-robot-out: for each robot, fit the command delay, calibration and noise setting on "
               "the other robots (examples/utias/fit.hpp) and score it; then the same fit on all robots (the "
               "default's rule)");
  auto& c = o.noise;
  app.add_option("--command-delay", c.command_delay_s, "a command logged at t acts from t + this (s)")
      ->check(positive(true));
  app.add_option("--command-jitter", c.command_jitter_s,
                 "timing uncertainty of a command change (s): adds |delta u| x this to the pose")
      ->check(positive(true));
  app.add_option("--v-gain", c.v_gain, "the robot drives this x the commanded speed")
      ->check(positive(false));
  app.add_option("--omega-gain", c.omega_gain, "the robot turns this x the commanded turn rate")
      ->check(positive(false));
  app.add_option("--v-turn-loss", c.v_turn_loss, "speed lost per rad/s of turn rate while driving (m/rad)")
      ->check(positive(true));
  app.add_option("--omega-bias", c.omega_bias, "added to the commanded turn rate (rad/s)");
  app.add_option("--sigma-range", c.sigma_range_m, "range noise at zero range (m)")->check(positive(false));
  app.add_option("--sigma-range-per-m", c.sigma_range_per_m, "range noise added per metre of range (m/m)")
      ->check(positive(true));
  app.add_option("--sigma-bearing", c.sigma_bearing_rad, "bearing noise (rad)")
      ->check(positive(false));
  app.add_option("--v-scale", c.v_scale, "speed noise density per m/s of speed (1/sqrt(s))")
      ->check(positive(true));
  app.add_option("--v-floor", c.v_floor, "speed noise density floor (m/sqrt(s))")
      ->check(positive(false));
  app.add_option("--omega-scale", c.omega_scale, "turn-rate noise density per rad/s of turn rate (1/sqrt(s))")
      ->check(positive(true));
  app.add_option("--omega-floor", c.omega_floor, "turn-rate noise density floor (rad/sqrt(s))")
      ->check(positive(false));
  app.add_option("--landmark-interval", c.landmark_interval_s,
                 "fuse each landmark at most once per this many seconds (0: every reading)")
      ->check(positive(true));
  app.add_option("--outlier-gate", c.outlier_gate_probability,
                 "known ids: chi-square probability above which an observation is rejected")
      ->check(CLI::Range(0.5, 0.99999999));
  app.add_option("--jcbb-noise-scale", c.jcbb_noise_scale,
                 "JCBB associates with this x the measurement sigmas (and fuses with the sigmas themselves)")
      ->check(positive(false));
  app.add_option("--jcbb-gate", c.jcbb_gate_probability, "chi-square gate probability of JCBB")
      ->check(CLI::Range(0.5, 0.999999));
  std::string gains = c.online_gains ? "online" : "fixed";
  app.add_option("--gains", gains,
                 "online: the speed gain, turn-rate gain and turn-rate bias are states of the filter "
                 "(Unicycle2DWithBias) with prior means --v-gain - 1, --omega-gain - 1, --omega-bias and sigmas "
                 "--gain-sigma; fixed: they are applied as a fixed calibration")
      ->check(CLI::IsMember({"online", "fixed"}));
  std::vector<double> gain_sigma{c.gain_sigma[0], c.gain_sigma[1], c.gain_sigma[2]};
  std::vector<double> gain_walk{c.gain_walk[0], c.gain_walk[1], c.gain_walk[2]};
  app.add_option("--gain-sigma", gain_sigma, "online gains: prior sigmas of [k_v, k_w, b_w] (-, -, rad/s)")
      ->expected(3)
      ->check(CLI::NonNegativeNumber);
  app.add_option("--gain-walk", gain_walk,
                 "online gains: random-walk densities of [k_v, k_w, b_w] (1/sqrt(s), 1/sqrt(s), rad/s/sqrt(s))")
      ->expected(3)
      ->check(CLI::NonNegativeNumber);
  CLI11_PARSE(app, argc, argv);
  c.online_gains = gains == "online";
  c.gain_sigma = Vec<3>(gain_sigma[0], gain_sigma[1], gain_sigma[2]);
  c.gain_walk = Vec<3>(gain_walk[0], gain_walk[1], gain_walk[2]);
  o.data_given = data_option->count() > 0;
  try {
    return run(o);
  } catch (const sylva::Error& e) {
    std::cerr << "utias: " << e.what() << "\n";
    return 1;
  }
}
