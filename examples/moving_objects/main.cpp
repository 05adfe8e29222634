// moving_objects: the laser moving-object detector of chapter 4 of D. Amarasinghe's thesis
// (multisensor SLAM, 2008, Sec. 4.3-4.4), on simulated and real scans, and its use as a
// preprocessing step of 2D range-bearing EKF-SLAM.
//
// Without flags the program runs four things and prints a report (--json: one JSON object):
//
//  1. The default dynamic scene (scenes.hpp; like Fig. 4.9/4.10): a robot driving slowly into
//     a room with three walking people and a rolling cart, 61 scans at 5 Hz (180 deg at
//     0.5 deg, 8 m, 1 cm noise). Each scan is compared with the previous one, both aligned
//     by the robot's (true) pose. Per scan: precision and recall of the readings reported
//     moving (evaluation.hpp) and the position error of the detected objects (hull centroid
//     and box centre against the true leg or cart centre). Picture: <prefix>_scene.svg.
//  2. The five cases of Sec. 4.3.4 (cases.hpp): whether the detector recovers each moving
//     object in full (every reading on the object reported, at least 95 % of the reported
//     readings on it). Picture: <prefix>_cases.svg.
//  3. A static check: the SLAM hall without people, scanned from the robot driving its loop
//     and aligned with the true poses: every detection is false.
//  4. SLAM (slam_run.hpp): Ekf<Unicycle2D, Point2> with RangeBearing on pole-like laser
//     features in a hall with walking people, over --slam-seeds worlds, without removal, with
//     removal of the features on detected moving objects, and with removal plus a memory of
//     recent detections. Landmark RMS error, spurious landmarks, robot NEES.
//     Picture: <prefix>_slam.svg (the first seed).
//
// With --real the program instead runs the detector on the leg_tracker recording (README of
// the data folder) and reports detections and tracks per scan, and how many detections fall
// on the static background (there is no ground truth). Picture: <prefix>_real.svg.
//
// Same flags, same output, bit for bit. `moving_objects --help` lists the flags.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <sylva/consistency/chi_square.hpp>
#include <sylva/core/error.hpp>
#include <sylva/datasets/leg_tracker.hpp>
#include <sylva/laser/moving_object_detector.hpp>
#include <sylva/laser/object_tracker.hpp>
#include <sylva/sim/laser_scanner_2d.hpp>

#include "../common/cli_checks.hpp"
#include "../common/report.hpp"
#include "../common/text.hpp"
#include "cases.hpp"
#include "evaluation.hpp"
#include "figures.hpp"
#include "scenes.hpp"
#include "slam_run.hpp"

#ifndef MOVING_OBJECTS_DEFAULT_DATA
#define MOVING_OBJECTS_DEFAULT_DATA "../shared/data/laser-people-leg-tracker"
#endif

namespace {

using sylva_examples::fixed;

using sylva::laser::Detection;
using sylva::laser::DetectorOptions;
using sylva::laser::MovingObjectDetector;
using sylva::LaserScanGeometry;
using nlohmann::json;
using sylva::Vec;

using sylva::kRadPerDeg;
constexpr int kSkipped = 77;  // ctest's SKIP_RETURN_CODE

struct Options {
  std::uint64_t seed = 1;
  bool json = false;
  std::string svg_prefix = "moving_objects";
  int scans = 61;
  // scanner
  double fov_deg = 180.0;
  double resolution_deg = 0.5;
  double max_range_m = 8.0;
  double sigma_range_m = 0.01;
  // detector
  double match_k = 3.0;
  double match_floor_m = 0.04;
  double segment_k = 5.0;
  double segment_floor_m = 0.10;
  int min_points = 3;
  int min_seed = 2;
  int replace_max_o = 1;
  bool no_free_space = false;
  double free_space_fraction = 0.8;
  // SLAM
  int slam_seeds = 10;
  int slam_people = 6;
  int slam_poles = 40;
  double slam_laps = 1.2;
  double memory_s = 1.0;
  bool no_slam = false;
  bool slam_oracle = false;
  // real data
  bool real = false;
  std::string data = MOVING_OBJECTS_DEFAULT_DATA;
  int real_step = 2;
  int real_max_scans = 0;
};

sylva::sim::LaserScanner2DOptions scannerOptions(const Options& o) {
  sylva::sim::LaserScanner2DOptions s;
  s.fov_rad = o.fov_deg * kRadPerDeg;
  s.resolution_rad = o.resolution_deg * kRadPerDeg;
  s.max_range_m = o.max_range_m;
  s.sigma_range_m = o.sigma_range_m;
  return s;
}

DetectorOptions detectorOptions(const Options& o) {
  DetectorOptions d;
  d.matching.match_k = o.match_k;
  d.matching.match_floor_m = o.match_floor_m;
  d.matching.free_space = !o.no_free_space;
  d.matching.free_space_max_range_fraction = o.free_space_fraction;
  d.segments.k = o.segment_k;
  d.segments.floor_m = o.segment_floor_m;
  d.min_segment_points = o.min_points;
  d.min_seed_points = o.min_seed;
  d.replace_max_o_segments = o.replace_max_o;
  d.validate();
  return d;
}

double rms(double sum_squares, long long n) { return n > 0 ? std::sqrt(sum_squares / static_cast<double>(n)) : 0.0; }

// ---------------------------------------------------------------------------------------
// 1. The default dynamic scene.

struct SceneRow {
  int scan;
  double time_s;
  int objects;
  moving_objects::PointScores scores;
  double hull_error_m;  // mean over this scan's objects on moving objects (NaN if none)
  double box_error_m;
};

struct SceneReport {
  std::vector<SceneRow> rows;
  moving_objects::PointScores pooled;
  double hull_sq = 0.0, box_sq = 0.0;
  long long located = 0;         // objects paired with a true moving object
  double leg_hull_sq = 0.0, leg_box_sq = 0.0;
  long long legs_located = 0;    // ... of which legs
  long long false_objects = 0;   // objects without a reading on a moving object
  long long objects = 0;
  double mean_precision = 0.0, mean_recall = 0.0;
  int torsos = 0;
  int confirmed_tracks = 0;
};

SceneReport runDefaultScene(const Options& o, const LaserScanGeometry& g, const sylva::sim::LaserScanner2D& scanner,
                            const MovingObjectDetector& detector, const std::string& svg_path) {
  using namespace moving_objects;
  const DefaultScene scene = makeDefaultScene(o.seed, o.scans);
  sylva::sim::Rng rng(sylva::sim::deriveSeed(o.seed, 1));
  sylva::sim::LaserScene2D snapshot;
  std::vector<sylva::sim::LaserScan2D> scans;
  for (std::size_t k = 0; k < scene.times.size(); ++k) {
    scene.world.snapshot(scene.times[k], snapshot);
    scans.push_back(scanner.scan(scene.robot_poses[k], snapshot, rng));
    scans.back().time_s = scene.times[k];
  }

  SceneReport report;
  svg::SceneFigure fig;
  NearestNeighborTracker tracker;
  for (std::size_t k = 1; k < scans.size(); ++k) {
    const AlignedScan previous = alignScan(g, scans[k - 1].ranges_m, scene.robot_poses[k - 1]);
    const AlignedScan current = alignScan(g, scans[k].ranges_m, scene.robot_poses[k]);
    const Detection d = detector.detect(previous, current, scene.times[k] - scene.times[k - 1]);
    const PointScores s = scorePoints(d, scans[k], scene.world, scene.times[k - 1], scene.times[k],
                                      current.origin(), g, detector.options().matching);
    const auto errors = objectErrors(d, scans[k], scene.world, scene.times[k]);
    SceneRow row{static_cast<int>(k), scene.times[k], static_cast<int>(d.objects.size()), s, std::nan(""), std::nan("")};
    double hull = 0.0, box = 0.0;
    int n = 0;
    for (const auto& e : errors) {
      ++report.objects;
      if (e.truth_id == sylva::sim::kNoObject) {
        ++report.false_objects;
        continue;
      }
      hull += e.hull_error_m;
      box += e.box_error_m;
      report.hull_sq += e.hull_error_m * e.hull_error_m;
      report.box_sq += e.box_error_m * e.box_error_m;
      ++report.located;
      if (isLegId(e.truth_id)) {
        report.leg_hull_sq += e.hull_error_m * e.hull_error_m;
        report.leg_box_sq += e.box_error_m * e.box_error_m;
        ++report.legs_located;
      }
      ++n;
    }
    if (n > 0) {
      row.hull_error_m = hull / n;
      row.box_error_m = box / n;
    }
    report.pooled += s;
    report.mean_precision += s.precision();
    report.mean_recall += s.recall();
    report.rows.push_back(row);

    for (int i = 0; i < current.size(); ++i) {
      if (!current.valid(i)) continue;
      (d.moving[static_cast<std::size_t>(i)] ? fig.moving_points : fig.scan_points).push_back(current.point(i));
    }
    for (const DetectedObject& object : d.objects) fig.boxes.push_back(object.box);
    const auto people = groupPeople(d.objects, 0.6);
    std::vector<Vec<2>> candidates;
    for (const auto& p : people) {
      candidates.push_back(p.position);
      if (p.legs >= 2) {
        fig.torsos.push_back(p.position);
        ++report.torsos;
      }
    }
    tracker.update(scene.times[k], candidates);
  }
  report.mean_precision /= static_cast<double>(report.rows.size());
  report.mean_recall /= static_cast<double>(report.rows.size());
  report.confirmed_tracks = tracker.confirmedCount();

  if (!svg_path.empty()) {
    fig.title = "Moving objects in the default scene (thesis Fig. 4.9): " + std::to_string(scans.size()) +
                " scans at 5 Hz from a moving robot";
    fig.subtitle = {"Three people walk (legs r = 6 cm with a gait), a cart rolls; scans aligned by the robot pose; seed " +
                        std::to_string(o.seed) + ".",
                    "Readings reported moving: precision " + fixed(report.pooled.precision(), 3) + ", recall " +
                        fixed(report.pooled.recall(), 3) + " (readings on objects that moved detectably); " +
                        std::to_string(report.objects) + " objects, " + std::to_string(report.false_objects) + " false."};
    fig.walls = scene.walls;
    for (const auto& c : scene.world.staticPart().circles()) fig.pillars.emplace_back(c.center, c.radius_m);
    for (const auto& person : scene.world.people()) {
      std::vector<Vec<2>> path;
      for (const double t : scene.times) path.push_back(person.bodyPosition(t));
      fig.true_paths.push_back(path);
    }
    for (const Vec<3>& p : scene.robot_poses) fig.robot_path.push_back(p.head<2>());
    for (const Track& t : tracker.tracks())
      if (tracker.confirmed(t)) fig.tracks.push_back(t.positions);
    fig.x0 = -1.7;
    fig.y0 = -5.2;
    fig.x1 = 11.2;
    fig.y1 = 5.2;
    svg::writeSceneSvg(svg_path, fig);
  }
  return report;
}

// ---------------------------------------------------------------------------------------
// 2. The five cases.

struct CaseReport {
  int number;
  std::string name;
  std::string what;
  int object_readings = 0;
  int objects = 0;
  moving_objects::PointScores scores;
  int initial_m_readings = 0;  // readings on the object in M_C^s before Algorithms 3-4
  int joined_a = 0, joined_o = 0;
  bool replaced = false;
  bool full = false;
};

std::vector<CaseReport> runCases(const Options& o, const LaserScanGeometry& g, const sylva::sim::LaserScanner2D& scanner,
                                 const MovingObjectDetector& detector, const std::string& svg_path) {
  using namespace moving_objects;
  std::vector<CaseReport> out;
  std::vector<svg::CasePanel> panels;
  for (ScriptedCase& c : fiveCases()) {
    sylva::sim::Rng rng(sylva::sim::deriveSeed(o.seed, 10 + static_cast<std::uint64_t>(c.number)));
    const auto before = scanner.scan(c.previous_pose, c.world.snapshot(0.0), rng);
    const auto after = scanner.scan(c.current_pose, c.world.snapshot(c.dt_s), rng);
    const AlignedScan previous = alignScan(g, before.ranges_m, c.previous_pose);
    const AlignedScan current = alignScan(g, after.ranges_m, c.current_pose);
    const Detection d = detector.detect(previous, current, c.dt_s);
    CaseReport r;
    r.number = c.number;
    r.name = c.name;
    r.what = c.what;
    r.scores = scorePoints(d, after, c.world, 0.0, c.dt_s, current.origin(), g, detector.options().matching);
    r.objects = static_cast<int>(d.objects.size());
    for (std::size_t i = 0; i < after.hit_object.size(); ++i) r.object_readings += after.hit_object[i] == c.moving_id;
    for (const Segment& s : d.m_segments)
      for (const int b : s.beams) r.initial_m_readings += after.hit_object[static_cast<std::size_t>(b)] == c.moving_id;
    for (const DetectedObject& object : d.objects) {
      r.joined_a += object.joined_from_a;
      r.joined_o += object.joined_from_o;
    }
    r.replaced = d.replaced_from_o;
    r.full = r.scores.on_moving > 0 && r.scores.on_moving_found == r.scores.on_moving && r.scores.precision() >= 0.95;
    out.push_back(r);

    svg::CasePanel panel;
    panel.title = "Case " + std::to_string(c.number) + ": " + c.name;
    std::ostringstream result;
    result << (r.full ? "recovered in full: " : "NOT in full: ") << r.scores.on_moving_found << "/" << r.scores.on_moving
           << " readings, precision " << fixed(r.scores.precision(), 2);
    panel.result = result.str();
    for (int i = 0; i < previous.size(); ++i)
      if (previous.valid(i)) panel.previous_points.push_back(previous.point(i));
    for (int i = 0; i < current.size(); ++i) {
      if (!current.valid(i)) continue;
      panel.current_points.push_back(current.point(i));
      if (d.moving[static_cast<std::size_t>(i)]) panel.detected_points.push_back(current.point(i));
    }
    for (const DetectedObject& object : d.objects) panel.boxes.push_back(object.box);
    panel.x0 = 1.6;
    panel.x1 = 4.4;
    panel.y0 = -1.4;
    panel.y1 = 1.4;
    panels.push_back(std::move(panel));
  }
  if (!svg_path.empty())
    svg::writeCasesSvg(svg_path, "The five cases of Sec. 4.3.4: two scans 0.2 s apart, one moving object", panels);
  return out;
}

// ---------------------------------------------------------------------------------------
// 3. Static scene from a moving robot.

struct StaticReport {
  int scans = 0;
  long long false_objects = 0;
  long long scans_with_false = 0;
  long long false_readings = 0;
  long long valid_readings = 0;
};

StaticReport runStaticCheck(const Options& o, const MovingObjectDetector& detector) {
  using namespace moving_objects;
  SlamRunOptions so;
  so.scanner = scannerOptions(o);
  so.scene.poles = o.slam_poles;
  so.scene.people = 0;
  so.scene.laps = o.slam_laps;
  const SlamData data = simulateSlam(so, sylva::sim::deriveSeed(o.seed, 50));
  const LaserScanGeometry& g = detector.geometry();
  StaticReport r;
  AlignedScan previous = alignScan(g, data.scans[0].ranges_m, data.scene.trajectory.startPose());
  for (std::size_t k = 0; k < data.truth.size(); ++k) {
    const AlignedScan current = alignScan(g, data.scans[k + 1].ranges_m, data.truth[k].true_pose);
    const Detection d = detector.detect(previous, current, data.scene.trajectory.dt());
    ++r.scans;
    r.false_objects += static_cast<long long>(d.objects.size());
    r.scans_with_false += d.objects.empty() ? 0 : 1;
    for (int i = 0; i < current.size(); ++i) {
      r.valid_readings += current.valid(i) ? 1 : 0;
      r.false_readings += d.moving[static_cast<std::size_t>(i)] ? 1 : 0;
    }
    previous = current;
  }
  return r;
}

// ---------------------------------------------------------------------------------------
// 4. SLAM with and without removal.

struct VariantStats {
  std::string name;
  double pole_sq = 0.0;       // squared errors of pole-born landmarks, all seeds
  long long poles = 0;
  long long spurious = 0;
  double nees_sum = 0.0;      // sum over seeds of the run's mean NEES
  long long nees_inside = 0;  // steps inside the single-run 95 % bounds
  long long nees_steps = 0;
  double position_sq = 0.0;
  long long removed = 0, removed_on_legs = 0, features_on_legs = 0, leg_used = 0;
  std::array<long long, 3> leg_by_motion{}, leg_removed_by_motion{}, leg_fused_by_motion{};
  long long pole_features_near_leg = 0, pole_features_clear = 0, duplicates = 0;
  double pole_near_leg_sq = 0.0, pole_clear_sq = 0.0;
  std::vector<double> per_seed_rmse;
};

struct SlamReport {
  std::vector<VariantStats> variants;  // without, with, with + memory
  int seeds = 0;
  int steps = 0;
  double path_length_m = 0.0;
};

SlamReport runSlamStudy(const Options& o, const std::string& svg_path) {
  using namespace moving_objects;
  SlamRunOptions so;
  so.scanner = scannerOptions(o);
  so.detector = detectorOptions(o);
  so.scene.poles = o.slam_poles;
  so.scene.people = o.slam_people;
  so.scene.laps = o.slam_laps;
  SlamReport report;
  for (const std::string& name : {std::string("without removal"), std::string("with removal"),
                                  "with removal + " + fixed(o.memory_s, 1) + " s memory", std::string("oracle removal (truth)")}) {
    if (name == "oracle removal (truth)" && !o.slam_oracle) break;
    report.variants.emplace_back();
    report.variants.back().name = name;
  }
  report.seeds = o.slam_seeds;
  const auto [lo, hi] = sylva::averageChiSquareBounds(3, 1, 0.95);
  svg::SlamFigure fig;
  for (int s = 0; s < o.slam_seeds; ++s) {
    const std::uint64_t seed = sylva::sim::deriveSeed(o.seed, 1000 + static_cast<std::uint64_t>(s));
    const SlamData data = simulateSlam(so, seed);
    report.steps = static_cast<int>(data.truth.size());
    report.path_length_m = data.scene.trajectory.speed() * data.scene.trajectory.dt() * report.steps;
    for (std::size_t v = 0; v < report.variants.size(); ++v) {
      SlamRunOptions run = so;
      run.memory_s = v == 2 ? o.memory_s : 0.0;
      run.oracle = v == 3;
      const SlamResult r = runSlam(data, run, v > 0);
      VariantStats& st = report.variants[v];
      st.pole_sq += r.landmark_rmse_m * r.landmark_rmse_m * r.pole_landmarks;
      st.poles += r.pole_landmarks;
      st.spurious += r.spurious_landmarks;
      st.nees_sum += r.nees.mean();
      for (const double a : r.nees.averages()) {
        ++st.nees_steps;
        st.nees_inside += (a >= lo && a <= hi) ? 1 : 0;
      }
      st.position_sq += r.position_rmse_m * r.position_rmse_m;
      st.removed += r.removed;
      st.removed_on_legs += r.removed_on_legs;
      st.features_on_legs += r.features_on_legs;
      st.leg_used += r.leg_observations_used;
      st.pole_features_near_leg += r.pole_features_near_leg;
      st.pole_features_clear += r.pole_features_clear;
      st.pole_near_leg_sq += r.pole_near_leg_sq;
      st.pole_clear_sq += r.pole_clear_sq;
      st.duplicates += r.duplicate_pole_landmarks;
      for (std::size_t c = 0; c < 3; ++c) {
        st.leg_by_motion[c] += r.leg_by_motion[c];
        st.leg_removed_by_motion[c] += r.leg_removed_by_motion[c];
        st.leg_fused_by_motion[c] += r.leg_fused_by_motion[c];
      }
      st.per_seed_rmse.push_back(r.landmark_rmse_m);
      if (s == 0 && v < 3) {
        svg::SlamPanel panel;
        panel.title = report.variants[v].name + ": RMSE " + fixed(r.landmark_rmse_m * 100, 2) + " cm, " +
                      std::to_string(r.spurious_landmarks) + " spurious";
        panel.estimated_path = r.estimated_path;
        for (const auto& [estimate, truth] : r.landmarks)
          (truth >= kFirstPoleId && truth < kFirstLegId ? panel.pole_landmarks : panel.spurious_landmarks)
              .push_back(estimate);
        fig.panels.push_back(panel);
      }
    }
    if (s == 0) {
      fig.walls = data.scene.walls;
      for (const auto& p : data.scene.poles) fig.poles.push_back(p.position);
      fig.true_path.push_back(data.scene.trajectory.startPose().head<2>());
      for (const auto& step : data.truth) fig.true_path.push_back(step.true_pose.head<2>());
      fig.routes = data.scene.person_routes;
      const auto& path = data.scene.trajectory.path();
      fig.x0 = -0.5 * path.length() - 7.0;
      fig.x1 = 0.5 * path.length() + 7.0;
      fig.y0 = -7.0;
      fig.y1 = path.width() + 7.0;
    }
  }
  if (!svg_path.empty()) {
    fig.title = "2D EKF-SLAM on laser point features among walking people, without and with moving-object removal";
    fig.subtitle = {"Ekf<Unicycle2D, Point2> + RangeBearing; " + std::to_string(o.slam_poles) + " poles, " +
                        std::to_string(o.slam_people) + " people whose legs look like poles; first of " +
                        std::to_string(o.slam_seeds) + " worlds (seed " + std::to_string(o.seed) + ").",
                    "RMSE: landmarks from poles against the true poles. Spurious: landmarks created from legs. Removal drops "
                    "features on objects found moving in the current scan pair; memory also drops features near objects "
                    "found moving in the last " + fixed(o.memory_s, 1) + " s."};
    svg::writeSlamSvg(svg_path, fig);
  }
  return report;
}

// ---------------------------------------------------------------------------------------
// Real data.

struct RealReport {
  std::string dir;
  int scans = 0;
  int pairs = 0;
  double dt_s = 0.0;
  long long detections = 0;
  int max_detections = 0;
  int scans_with_detections = 0;
  long long detected_readings = 0;
  long long background_readings = 0;
  long long detected_on_background = 0;
  long long objects_on_background = 0;
  int confirmed_tracks = 0;
  double mean_active_tracks = 0.0;
  int max_active_tracks = 0;
  long long invalid_readings = 0, no_return_readings = 0, readings = 0;
  std::vector<int> detections_per_scan;
  std::vector<int> active_tracks_per_scan;
};

/// Per beam: the static background range (75th percentile of the valid readings) when the
/// beam reads valid in at least half of the scans, else +infinity (open space).
std::vector<double> backgroundModel(const sylva::datasets::LegTrackerRecording& data) {
  const LaserScanGeometry& g = data.geometry;
  std::vector<double> background(static_cast<std::size_t>(g.beams), std::numeric_limits<double>::infinity());
  for (int b = 0; b < g.beams; ++b) {
    std::vector<double> valid;
    for (const auto& scan : data.ranges) {
      const double r = scan[static_cast<std::size_t>(b)];
      if (sylva::laser::classifyReading(r, g) == sylva::laser::Reading::kValid) valid.push_back(r);
    }
    if (2 * valid.size() < data.ranges.size()) continue;
    const std::size_t k = (3 * valid.size()) / 4;
    std::nth_element(valid.begin(), valid.begin() + static_cast<std::ptrdiff_t>(k), valid.end());
    background[static_cast<std::size_t>(b)] = valid[k];
  }
  return background;
}

constexpr double kBackgroundTolerance_m = 0.15;

int runReal(const Options& o, const DetectorOptions& detector_options, const std::string& svg_path, RealReport& r) {
  using namespace moving_objects;
  r.dir = o.data;
  const std::string name = "stationary_simple_environment";
  if (!std::filesystem::exists(o.data + "/" + name + "_scans.csv")) {
    std::cerr << "moving_objects: SKIPPED the real-data run: no " << name << "_scans.csv in '" << o.data
              << "'.\n  Get the leg_tracker demo recording (github.com/angusleigh/leg_tracker, "
                 "rosbags/demos/demo_stationary_simple_environment.bag, BSD 3-Clause), convert /scan to the CSV "
                 "format of docs/examples/moving-objects.md, and pass its folder with --data DIR.\n";
    return kSkipped;
  }
  sylva::datasets::LegTrackerRecording data = sylva::datasets::loadLegTrackerRecording(o.data, name);
  if (o.real_max_scans > 0 && static_cast<int>(data.ranges.size()) > o.real_max_scans) {
    data.ranges.resize(static_cast<std::size_t>(o.real_max_scans));
    data.stamps_s.resize(static_cast<std::size_t>(o.real_max_scans));
  }
  const LaserScanGeometry& g = data.geometry;
  const MovingObjectDetector detector(g, detector_options);
  const std::vector<double> background = backgroundModel(data);
  r.scans = static_cast<int>(data.ranges.size());
  const auto step = static_cast<std::size_t>(o.real_step);
  if (data.ranges.size() <= step) sylva::fail(sylva::ErrorCode::kInvalidArgument, "--real-step is not smaller than the number of scans");
  NearestNeighborTracker tracker;
  svg::BeamTimeFigure fig;
  fig.range_max = g.max_range_m;
  fig.beam_step = 2;
  const Vec<3> still = Vec<3>::Zero();  // the scanner stands still (data README)
  long long active_sum = 0;
  for (std::size_t k = step; k < data.ranges.size(); ++k) {
    const double dt = data.stamps_s[k] - data.stamps_s[k - step];
    const AlignedScan previous = alignScan(g, data.ranges[k - step], still);
    const AlignedScan current = alignScan(g, data.ranges[k], still);
    const Detection d = detector.detect(previous, current, dt);
    ++r.pairs;
    r.dt_s += dt;
    r.detections += static_cast<long long>(d.objects.size());
    r.max_detections = std::max(r.max_detections, static_cast<int>(d.objects.size()));
    r.scans_with_detections += d.objects.empty() ? 0 : 1;
    r.detections_per_scan.push_back(static_cast<int>(d.objects.size()));
    r.invalid_readings += current.invalid;
    r.no_return_readings += current.no_return;
    r.readings += current.size();
    for (int i = 0; i < current.size(); ++i) {
      if (!current.valid(i)) continue;
      const double bg = background[static_cast<std::size_t>(i)];
      const bool on_background = std::isfinite(bg) && current.range(i) >= bg - kBackgroundTolerance_m;
      const bool moving = d.moving[static_cast<std::size_t>(i)] != 0;
      r.background_readings += on_background ? 1 : 0;
      r.detected_readings += moving ? 1 : 0;
      r.detected_on_background += (moving && on_background) ? 1 : 0;
    }
    for (const DetectedObject& object : d.objects) {
      int on = 0;
      for (const int b : object.beams) {
        const double bg = background[static_cast<std::size_t>(b)];
        on += (std::isfinite(bg) && current.range(b) >= bg - kBackgroundTolerance_m) ? 1 : 0;
      }
      r.objects_on_background += 2 * on > static_cast<int>(object.beams.size()) ? 1 : 0;
    }
    std::vector<Vec<2>> candidates;
    for (const auto& p : groupPeople(d.objects, 0.6)) candidates.push_back(p.position);
    tracker.update(data.stamps_s[k], candidates);
    const int active = tracker.activeConfirmed();
    r.active_tracks_per_scan.push_back(active);
    active_sum += active;
    r.max_active_tracks = std::max(r.max_active_tracks, active);
    fig.times.push_back(data.stamps_s[k] - data.stamps_s.front());
    fig.ranges.push_back(data.ranges[k]);
    fig.detected.push_back(d.moving);
  }
  r.dt_s /= r.pairs;
  r.confirmed_tracks = tracker.confirmedCount();
  r.mean_active_tracks = static_cast<double>(active_sum) / r.pairs;
  if (!svg_path.empty()) {
    fig.title = "Real scans (leg_tracker demo, stationary scanner): range per beam over time, detections in red";
    fig.subtitle = {std::to_string(r.pairs) + " scans, each against the one " + std::to_string(o.real_step) +
                        " scans earlier (dt = " + fixed(r.dt_s, 2) + " s); " + std::to_string(r.detections) +
                        " detections, " + std::to_string(r.confirmed_tracks) + " confirmed tracks. No ground truth.",
                    "Beam 0 looks right (-90 deg), beam 511 left (+89.6 deg); walkers are the dark zig-zags in front of "
                    "the light background."};
    svg::writeBeamTimeSvg(svg_path, fig);
  }
  return 0;
}

// ---------------------------------------------------------------------------------------

json scoresJson(const moving_objects::PointScores& s) {
  return {{"precision", s.precision()}, {"recall", s.recall()}, {"recall_all", s.recallAll()},
          {"reported", s.reported}, {"reported_on_moving", s.reported_on_moving},
          {"detectable", s.detectable}, {"detectable_found", s.detectable_found}};
}

std::string pathWith(const std::string& prefix, const std::string& suffix) {
  return prefix.empty() ? std::string() : prefix + suffix;
}

int runReal(const Options& o) {
  RealReport r;
  const int status = runReal(o, detectorOptions(o), pathWith(o.svg_prefix, "_real.svg"), r);
  if (status != 0) return status;
  const double background_rate =
      r.background_readings ? static_cast<double>(r.detected_on_background) / r.background_readings : 0.0;
  const double detections_per_scan = static_cast<double>(r.detections) / r.pairs;
  json j;
  j["data"] = r.dir;
  j["ground_truth"] = false;
  j["note"] = "no ground truth in this recording: the figures are counts and a plausibility check";
  j["scans"] = r.scans;
  j["scan_pairs"] = r.pairs;
  j["dt_s"] = r.dt_s;
  j["no_return_fraction"] = static_cast<double>(r.no_return_readings) / r.readings;
  j["invalid_fraction"] = static_cast<double>(r.invalid_readings) / r.readings;
  j["detections"] = r.detections;
  j["detections_per_scan_mean"] = detections_per_scan;
  j["detections_per_scan_max"] = r.max_detections;
  j["scans_with_detections"] = r.scans_with_detections;
  j["confirmed_tracks"] = r.confirmed_tracks;
  j["active_tracks_per_scan_mean"] = r.mean_active_tracks;
  j["active_tracks_per_scan_max"] = r.max_active_tracks;
  j["detected_readings"] = r.detected_readings;
  j["background_readings"] = r.background_readings;
  j["background_tolerance_m"] = kBackgroundTolerance_m;
  j["detected_on_background"] = r.detected_on_background;
  j["background_false_detection_rate"] = background_rate;
  j["objects_on_background"] = r.objects_on_background;
  j["detections_per_scan"] = r.detections_per_scan;
  j["active_tracks_per_scan"] = r.active_tracks_per_scan;
  sylva_examples::writeResult(std::cout, o.json, "moving_objects --real: the leg_tracker recording", json{{"real", j}});
  return 0;
}

int runSimulation(const Options& o) {
  const sylva::sim::LaserScanner2D scanner(scannerOptions(o));
  const LaserScanGeometry g = scanner.geometry();
  const MovingObjectDetector detector(g, detectorOptions(o));
  const double dt = 0.2;

  const SceneReport scene = runDefaultScene(o, g, scanner, detector, pathWith(o.svg_prefix, "_scene.svg"));
  const std::vector<CaseReport> cases = runCases(o, g, scanner, detector, pathWith(o.svg_prefix, "_cases.svg"));
  int cases_detected = 0;
  for (const CaseReport& c : cases) cases_detected += c.full ? 1 : 0;
  const StaticReport still = runStaticCheck(o, detector);
  SlamReport slam;
  if (!o.no_slam) slam = runSlamStudy(o, pathWith(o.svg_prefix, "_slam.svg"));
  const auto [nees_lo, nees_hi] = sylva::averageChiSquareBounds(3, 1, 0.95);

  json j;
  j["seed"] = o.seed;
  json per_scan = json::array();
  for (const SceneRow& row : scene.rows) {
    json r = scoresJson(row.scores);
    r["scan"] = row.scan;
    r["time_s"] = row.time_s;
    r["objects"] = row.objects;
    r["hull_error_m"] = std::isnan(row.hull_error_m) ? json(nullptr) : json(row.hull_error_m);
    r["box_error_m"] = std::isnan(row.box_error_m) ? json(nullptr) : json(row.box_error_m);
    per_scan.push_back(r);
  }
  j["default_scene"] = {{"scans", scene.rows.size() + 1},
                        {"dt_s", dt},
                        {"points", scoresJson(scene.pooled)},
                        {"precision", scene.pooled.precision()},
                        {"recall", scene.pooled.recall()},
                        {"mean_per_scan_precision", scene.mean_precision},
                        {"mean_per_scan_recall", scene.mean_recall},
                        {"objects", scene.objects},
                        {"false_objects", scene.false_objects},
                        {"position_error_m",
                         {{"hull_centroid_rms", rms(scene.hull_sq, scene.located)},
                          {"box_centre_rms", rms(scene.box_sq, scene.located)},
                          {"objects", scene.located},
                          {"legs",
                           {{"hull_centroid_rms", rms(scene.leg_hull_sq, scene.legs_located)},
                            {"box_centre_rms", rms(scene.leg_box_sq, scene.legs_located)},
                            {"objects", scene.legs_located}}},
                          {"cart",
                           {{"hull_centroid_rms", rms(scene.hull_sq - scene.leg_hull_sq, scene.located - scene.legs_located)},
                            {"box_centre_rms", rms(scene.box_sq - scene.leg_box_sq, scene.located - scene.legs_located)},
                            {"objects", scene.located - scene.legs_located}}}}},
                        {"torso_estimates", scene.torsos},
                        {"confirmed_tracks", scene.confirmed_tracks},
                        {"per_scan", per_scan}};
  json vmin;
  for (const double r : {1.0, 2.0, 4.0, 8.0})
    vmin[fixed(r, 0) + "m"] = sylva::laser::minDetectableSpeed(g, detector.options().matching, r, dt);
  j["min_detectable_speed_mps"] = vmin;
  json jc = json::array();
  for (const CaseReport& c : cases)
    jc.push_back({{"case", c.number}, {"name", c.name}, {"recovered_in_full", c.full},
                  {"object_readings", c.object_readings}, {"found", c.scores.on_moving_found},
                  {"precision", c.scores.precision()}, {"initial_m_readings", c.initial_m_readings},
                  {"joined_from_a", c.joined_a}, {"joined_from_o", c.joined_o}, {"algorithm_4", c.replaced}});
  j["cases"] = jc;
  j["cases_detected"] = cases_detected;
  j["static_check"] = {{"scans", still.scans},
                       {"false_objects", still.false_objects},
                       {"false_objects_per_scan", static_cast<double>(still.false_objects) / still.scans},
                       {"scans_with_false_objects", still.scans_with_false},
                       {"false_readings", still.false_readings},
                       {"valid_readings", still.valid_readings}};
  if (!o.no_slam) {
    const auto rmse = [&](std::size_t v) { return rms(slam.variants[v].pole_sq, slam.variants[v].poles); };
    j["slam_landmark_rmse_m"] = {{"without_removal", rmse(0)}, {"with_removal", rmse(1)},
                                 {"with_removal_and_memory", rmse(2)}};
    json variants = json::array();
    for (const VariantStats& v : slam.variants) {
      variants.push_back({{"name", v.name},
                          {"landmark_rmse_m", rms(v.pole_sq, v.poles)},
                          {"pole_landmarks_per_run", static_cast<double>(v.poles) / slam.seeds},
                          {"duplicate_pole_landmarks_per_run", static_cast<double>(v.duplicates) / slam.seeds},
                          {"spurious_landmarks_per_run", static_cast<double>(v.spurious) / slam.seeds},
                          {"robot_nees_mean", v.nees_sum / slam.seeds},
                          {"robot_nees_fraction_inside_95", static_cast<double>(v.nees_inside) / v.nees_steps},
                          {"position_rmse_m", std::sqrt(v.position_sq / slam.seeds)},
                          {"features_on_legs", v.features_on_legs},
                          {"removed", v.removed},
                          {"removed_on_legs", v.removed_on_legs},
                          {"leg_features_used", v.leg_used},
                          {"leg_features_by_motion",
                           {{"classes", {"stance (not moving)", "slower than eq. 4.5", "detectable"}},
                            {"extracted", v.leg_by_motion},
                            {"removed", v.leg_removed_by_motion},
                            {"fused_into_landmarks", v.leg_fused_by_motion}}},
                          {"per_seed_landmark_rmse_m", v.per_seed_rmse}});
    }
    int wins = 0;
    for (int s = 0; s < slam.seeds; ++s) wins += slam.variants[1].per_seed_rmse[s] < slam.variants[0].per_seed_rmse[s];
    const VariantStats& v0 = slam.variants[0];
    j["slam_pole_features"] = {{"near_a_leg", v0.pole_features_near_leg},
                               {"near_a_leg_rms_error_m", rms(v0.pole_near_leg_sq, v0.pole_features_near_leg)},
                               {"clear", v0.pole_features_clear},
                               {"clear_rms_error_m", rms(v0.pole_clear_sq, v0.pole_features_clear)}};
    j["slam"] = {{"seeds", slam.seeds}, {"steps", slam.steps}, {"path_length_m", slam.path_length_m},
                 {"people", o.slam_people}, {"poles", o.slam_poles}, {"nees_bounds_95", {nees_lo, nees_hi}},
                 {"seeds_with_removal_better", wins}, {"variants", variants}};
  }
  sylva_examples::writeResult(std::cout, o.json,
                              "moving_objects: laser moving-object detection (Amarasinghe 2008, Sec. 4.3-4.4)", j);
  return 0;
}


}  // namespace

using sylva_examples::positive;

int main(int argc, char** argv) {
  Options o;
  CLI::App app{
      "Laser moving-object detection of Amarasinghe 2008, chapter 4 (closest points, Algorithms 2-4, Join, convex "
      "hull and bounding box, eq. 4.1-4.5) on simulated scans, the five cases of Sec. 4.3.4, a static check, and "
      "2D EKF-SLAM with and without removing detected moving objects. --real runs it on the leg_tracker recording."};
  app.option_defaults()->always_capture_default();  // every option shows its default in --help
  app.footer(
      "Same flags, same output, bit for bit. Pictures: <prefix>_scene.svg, _cases.svg, _slam.svg (or _real.svg\n"
      "with --real); --svg-prefix \"\" writes none. With --real and no data at --data, the program says where to get\n"
      "them and exits with status 77 (ctest reports the smoke test as skipped).");
  app.add_option("--seed", o.seed, "seed of the scenes and the noise");
  app.add_flag("--json", o.json, "print one JSON object instead of text");
  app.add_option("--svg-prefix", o.svg_prefix, "path prefix of the SVG pictures (\"\" for none)");
  app.add_option("--scans", o.scans, "scans of the default scene")->check(CLI::Range(2, 100000));
  app.add_option("--fov", o.fov_deg, "scanner field of view (deg)")->check(CLI::Range(1.0, 360.0));
  app.add_option("--resolution", o.resolution_deg, "angle between beams (deg)")->check(positive(false));
  app.add_option("--max-range", o.max_range_m, "scanner maximum range (m)")->check(positive(false));
  app.add_option("--sigma-range", o.sigma_range_m, "range noise (m)")->check(positive(true));
  app.add_option("--match-k", o.match_k, "k of eq. 4.4 (closest points)")->check(positive(true));
  app.add_option("--match-floor", o.match_floor_m, "floor of the closest-point threshold (m)")->check(positive(true));
  app.add_option("--segment-k", o.segment_k, "k of the segmentation and Join threshold")->check(positive(true));
  app.add_option("--segment-floor", o.segment_floor_m, "floor of the segmentation threshold (m)")->check(positive(true));
  app.add_option("--min-points", o.min_points, "minimum readings of a detected object (Sec. 4.4.1)")->check(CLI::Range(1, 10000));
  app.add_option("--min-seed", o.min_seed, "minimum readings of an M_C^s segment before the joins")->check(CLI::Range(1, 10000));
  app.add_option("--replace-max-o", o.replace_max_o, "Algorithm 4 only with at most this many O_C^s segments (0: never)")->check(CLI::Range(0, 100000));
  app.add_flag("--no-free-space", o.no_free_space, "the thesis' Algorithm 2 without the free-space extension");
  app.add_option("--free-space-fraction", o.free_space_fraction,
                 "trust 'no return' as free space only for readings within this share of the maximum range")
      ->check(CLI::Range(0.01, 1.0));
  app.add_option("--slam-seeds", o.slam_seeds, "worlds of the SLAM comparison")->check(CLI::Range(1, 100000));
  app.add_option("--slam-people", o.slam_people, "walking people in the SLAM hall")->check(CLI::Range(0, 1000));
  app.add_option("--slam-poles", o.slam_poles, "poles (landmarks) in the SLAM hall")->check(CLI::Range(1, 1000));
  app.add_option("--slam-laps", o.slam_laps, "laps of the SLAM loop")->check(CLI::Range(0.05, 100.0));
  app.add_option("--memory", o.memory_s, "third SLAM variant: also drop features near objects detected in the last S seconds")->check(positive(false));
  app.add_flag("--no-slam", o.no_slam, "skip the SLAM comparison");
  app.add_flag("--slam-oracle", o.slam_oracle, "diagnostic: a fourth SLAM variant that drops exactly the leg features (truth)");
  app.add_flag("--real", o.real, "run on the leg_tracker recording instead of the simulation");
  app.add_option("--data", o.data, "folder of the leg_tracker recording");
  app.add_option("--real-step", o.real_step, "compare each real scan with the one this many scans earlier")->check(CLI::Range(1, 1000));
  app.add_option("--real-max-scans", o.real_max_scans, "use only the first N real scans (0: all)")->check(CLI::Range(0, 100000000));
  CLI11_PARSE(app, argc, argv);

  try {
    return o.real ? runReal(o) : runSimulation(o);
  } catch (const sylva::Error& e) {
    std::cerr << "moving_objects: " << e.what() << "\n";
    return 1;
  }
}
