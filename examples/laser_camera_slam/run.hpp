#pragma once
// The simulation and the three SLAM variants of the laser_camera_slam example (see main.cpp
// for the description). `simulate` produces every step's true pose, odometry, laser corners
// and laser-camera measurements once; `runVariant` runs one EKF-SLAM over them, so the three
// variants see exactly the same data.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <unordered_map>
#include <vector>

#include <sylva/consistency.hpp>
#include <sylva/laser/corner_features.hpp>
#include <sylva/laser_camera.hpp>
#include <sylva/sim.hpp>
#include <sylva/sylva.hpp>
#include <sylva/slam/front_end.hpp>
#include <sylva/slam/reach.hpp>

#include "indoor_world.hpp"

namespace laser_camera_slam {

using sylva::Gaussian;
using sylva::Id;
using sylva::kPi;
using sylva::Mat;
using sylva::Vec;
using Filter = sylva::Ekf<sylva::Unicycle2D, sylva::Point2>;

using sylva::kRadPerDeg;

struct Options {
  double perimeter_m = 40.0;
  double laps = 1.75;
  double speed_mps = 0.5;
  double dt_s = 0.4;  // 20 cm between scans, as the thesis logged (Sec. 3.5)
  double sigma_v_mps = 0.05;
  double sigma_omega_degps = 1.0;
  double laser_height_m = 0.40;
  double camera_above_laser_m = 0.19;  // b of Fig. 3.5
  double sigma_px = 1.0;
  bool calibrate = true;
  int calibration_pairs = 40;
  int calibration_degree = 3;
  bool near_side_at_jumps = true;
  double gate_probability = 0.99;
  double new_landmark_probability = 0.999999;
  std::uint64_t seed = 1;
};

enum class Variant { kLaserCorners = 0, kLaserCamera = 1, kFused = 2 };
inline const char* variantName(Variant v) {
  return v == Variant::kLaserCorners ? "laser_corners" : v == Variant::kLaserCamera ? "laser_camera" : "fused";
}

/// One point feature as [range, bearing] in the robot (= laser) frame.
struct PointFeature {
  Vec<2> z;
  Mat<2, 2> covariance;
  Id true_edge;  ///< evaluation only: nearest true edge within 0.25 m, -1 if none
};

struct StepData {
  Vec<3> true_pose;
  Vec<2> odometry;
  std::vector<PointFeature> corners;
  std::vector<PointFeature> laser_camera;
  int lines_detected = 0;
};

struct Simulation {
  IndoorWorld world;
  sylva::sim::LoopPath2D path{20.0, 10.0, 1.5};
  std::vector<StepData> steps;
  sylva::LaserCameraCalibration calibration;
  std::array<long long, 6> status_counts{};  ///< per LaserCameraStatus
  double uncalibrated_bearing_rms_rad = 0.0;  ///< systematic camera error over the field of view
  double calibrated_bearing_rms_rad = 0.0;
  double dt_s = 0.0;
};

inline sylva::sim::VerticalEdgeCameraOptions cameraOptions(const Options& o) {
  sylva::sim::VerticalEdgeCameraOptions c;
  c.height_m = o.laser_height_m + o.camera_above_laser_m;
  c.sigma_px = o.sigma_px;
  // Systematic error left by the camera calibration and the mounting: 0.5 deg yaw, 2 %
  // scale, a cubic lens term; about 1.9 deg at the image edge.
  c.distortion[0] = 0.5 * kRadPerDeg;
  c.distortion[1] = 0.02;
  c.distortion[3] = 0.06;
  return c;
}

/// Sec. 3.3.2: a 'v' target placed across the camera's view; the camera reads its tip with
/// its systematic error and pixel noise, the laser with 0.05 deg noise.
inline std::vector<sylva::CalibrationPair> calibrationPairs(const sylva::sim::VerticalEdgeCamera& camera,
                                                            int count,
                                                            sylva::sim::Rng& rng) {
  std::vector<sylva::CalibrationPair> pairs;
  const double half = camera.halfFov() - 2.0 * kRadPerDeg;
  for (int i = 0; i < count; ++i) {
    const double beta = -half + 2.0 * half * i / std::max(1, count - 1);
    const double c = camera.reportedBearing(beta, rng);
    pairs.push_back({c, beta + 0.05 * kRadPerDeg * rng.normal()});
  }
  return pairs;
}

inline Id nearestEdge(const IndoorWorld& world, const Vec<2>& p) {
  Id best = -1;
  double best_d = 0.25;
  for (const auto& e : world.edges) {
    const double d = (e.position - p).norm();
    if (d < best_d) {
      best_d = d;
      best = e.id;
    }
  }
  return best;
}

inline Vec<2> toWorld(const Vec<3>& pose, const Vec<2>& z) {
  return pose.head<2>() + z[0] * Vec<2>(std::cos(pose[2] + z[1]), std::sin(pose[2] + z[1]));
}

inline Simulation simulate(const Options& o) {
  using namespace sylva::sim;
  Simulation sim;
  LoopTrajectory2DOptions t;
  t.perimeter_m = o.perimeter_m;
  t.corner_radius_m = 1.5;
  t.speed_mps = o.speed_mps;
  t.dt_s = o.dt_s;
  t.sigma_v_mps = o.sigma_v_mps;
  t.sigma_omega_radps = o.sigma_omega_degps * kRadPerDeg;
  const LoopTrajectory2D trajectory(t);
  sim.path = trajectory.path();
  sim.dt_s = trajectory.dt();
  sim.world = makeIndoorWorld(trajectory.path());
  const LaserScanner2D scanner;  // SICK class: 180 deg at 0.5 deg, 8 m, 1 cm
  const sylva::LaserScanGeometry geometry = scanner.geometry();
  const VerticalEdgeCamera camera(cameraOptions(o));

  Rng calibration_rng(deriveSeed(o.seed, 1));
  if (o.calibrate)
    sim.calibration = sylva::LaserCameraCalibration::fit(calibrationPairs(camera, o.calibration_pairs, calibration_rng),
                                                         o.calibration_degree);
  {
    // Systematic bearing error before and after calibration over the field of view.
    double before = 0.0, after = 0.0;
    const int n = 101;
    const double half = camera.halfFov() - 2.0 * kRadPerDeg;
    for (int i = 0; i < n; ++i) {
      const double beta = -half + 2.0 * half * i / (n - 1);
      const double c = std::atan(std::tan(beta + camera.distortion(beta)));
      before += (c - beta) * (c - beta);
      after += (sim.calibration.toLaser(c) - beta) * (sim.calibration.toLaser(c) - beta);
    }
    sim.uncalibrated_bearing_rms_rad = std::sqrt(before / n);
    sim.calibrated_bearing_rms_rad = std::sqrt(after / n);
  }
  sylva::LaserCameraOptions so;
  so.camera_above_laser_m = o.camera_above_laser_m;
  so.sigma_bearing_rad = o.sigma_px / camera.options().focal_px;
  so.sigma_reading_m = scanner.options().sigma_range_m;
  so.near_side_at_jumps = o.near_side_at_jumps;
  const sylva::LaserCameraSensor sensor(geometry, sim.calibration, so);

  Rng rng(deriveSeed(o.seed, 2));
  const int steps = static_cast<int>(std::lround(o.laps * trajectory.stepsPerLap()));
  const auto truth = trajectory.simulate(steps, rng);
  LaserScan2D scan;
  std::vector<EdgeDetection> detections;
  sim.steps.reserve(truth.size());
  for (const auto& step : truth) {
    StepData d;
    d.true_pose = step.true_pose;
    d.odometry = step.odometry;
    scanner.scan(step.true_pose, sim.world.walls, rng, scan);
    camera.observe(step.true_pose, sim.world.edges, sim.world.walls, rng, detections);
    d.lines_detected = static_cast<int>(detections.size());
    for (const sylva::laser::CornerFeature& c : sylva::laser::extractCornerFeatures(scan.ranges_m, geometry))
      d.corners.push_back({c.z, c.covariance, nearestEdge(sim.world, toWorld(step.true_pose, c.z))});
    for (const auto& det : detections) {
      const sylva::LaserCameraMeasurement m = sensor.measure(det.line, scan.ranges_m);
      ++sim.status_counts[static_cast<std::size_t>(m.status)];
      if (m.ok()) d.laser_camera.push_back({m.z, m.covariance, nearestEdge(sim.world, toWorld(step.true_pose, m.z))});
    }
    sim.steps.push_back(std::move(d));
  }
  return sim;
}

/// Per-step record of one variant.
struct StepRecord {
  Vec<3> error;   ///< difference(true, estimate)
  Vec<3> sigma;   ///< square roots of the pose covariance's diagonal
  double nees;
  int map_size;
  int observed;
};

struct VariantResult {
  Variant variant;
  std::vector<StepRecord> records;
  int landmarks = 0;
  int spurious = 0;  ///< landmarks whose first feature matched no true edge
  double landmark_rmse_m = 0.0;
  double final_position_error_m = 0.0;
  double final_heading_error_rad = 0.0;
  double nees_mean = 0.0;
  double nees_fraction_inside = 0.0;  ///< steps with NEES inside the 95% chi-square(3) interval
  long long paired = 0, wrong = 0, added = 0, ambiguous = 0;
  std::vector<std::pair<Vec<2>, Mat<2, 2>>> map;  ///< final landmark means and covariances
  std::vector<Vec<2>> path;
};

/// The features a variant observes at one step. Fused: all corners, plus the laser-camera
/// points farther than 0.3 m from every corner of the same scan (a corner is also a
/// vertical edge; one landmark, one measurement).
inline std::vector<PointFeature> featuresOf(const StepData& d, Variant v) {
  if (v == Variant::kLaserCorners) return d.corners;
  if (v == Variant::kLaserCamera) return d.laser_camera;
  std::vector<PointFeature> out = d.corners;
  for (const auto& f : d.laser_camera) {
    const Vec<2> p = f.z[0] * Vec<2>(std::cos(f.z[1]), std::sin(f.z[1]));
    bool duplicate = false;
    for (const auto& c : d.corners)
      if ((c.z[0] * Vec<2>(std::cos(c.z[1]), std::sin(c.z[1])) - p).norm() < 0.3) duplicate = true;
    if (!duplicate) out.push_back(f);
  }
  return out;
}

inline VariantResult runVariant(const Simulation& sim, const Options& o, Variant variant) {
  const auto Q = Gaussian<2>::sigmas(Vec<2>(o.sigma_v_mps, o.sigma_omega_degps * kRadPerDeg));
  // JCBB gates with one noise for every measurement: Table 3.1's 5 cm and 1 deg, wider
  // than every feature's own covariance, which the update uses.
  const auto R_gate = Gaussian<2>::sigmas(Vec<2>(0.05, 1.0 * kRadPerDeg));
  // Candidates: landmarks predicted within 8.5 m and 100 deg of the heading.
  sylva::slam::FrontEndOptions options;
  options.association = sylva::slam::Association::kJcbb;
  options.gate_probability = o.gate_probability;
  options.new_landmark_probability = o.new_landmark_probability;
  sylva::slam::FrontEnd<Filter, sylva::RangeBearing, sylva::InverseRangeBearing> front_end(
      sylva::RangeBearing{}, sylva::InverseRangeBearing{}, options,
      sylva::slam::candidatesInReach<sylva::Point2>(sylva::RangeBearing{}, {8.5, 100.0 * kRadPerDeg}));
  std::vector<sylva::slam::Reading<2>> readings;
  const auto [nees_lo, nees_hi] = sylva::averageChiSquareBounds(3, 1, 0.95);

  VariantResult result;
  result.variant = variant;
  Filter ekf(Vec<3>::Zero(), Mat<3, 3>::Zero());
  ekf.reserve(256);
  std::unordered_map<Id, Id> truth_of;
  std::unordered_map<Id, Vec<2>> true_position;
  for (const auto& e : sim.world.edges) true_position[e.id] = e.position;
  double nees_sum = 0.0;
  int nees_count = 0, inside = 0;
  result.path.push_back(Vec<2>::Zero());
  for (std::size_t k = 0; k < sim.steps.size(); ++k) {
    const StepData& d = sim.steps[k];
    ekf.predict(d.odometry, sim.dt_s, Q);
    const std::vector<PointFeature> features = featuresOf(d, variant);
    readings.clear();
    for (const auto& f : features) readings.push_back({f.z, Gaussian<2>::covariance(f.covariance), R_gate});
    const sylva::slam::StepReport& report = front_end.update(ekf, readings, sim.dt_s * static_cast<double>(k + 1));
    for (std::size_t i = 0; i < features.size(); ++i) {
      const sylva::slam::ReadingResult& r = report.readings[i];
      if (r.outcome == sylva::slam::Outcome::kPaired) {
        ++result.paired;
        if (truth_of.at(*r.landmark) != features[i].true_edge) ++result.wrong;
      } else if (r.outcome == sylva::slam::Outcome::kAdded) {
        truth_of[*r.landmark] = features[i].true_edge;
        ++result.added;
      } else if (r.outcome == sylva::slam::Outcome::kAmbiguous) {
        ++result.ambiguous;
      }
    }
    StepRecord rec;
    rec.error = sylva::Unicycle2D::difference(d.true_pose, ekf.robotMean());
    const Mat<3, 3> P = ekf.robotCovariance();
    rec.sigma = P.diagonal().cwiseMax(0.0).cwiseSqrt();
    rec.nees = k > 0 ? sylva::nees(rec.error, P) : 0.0;
    rec.map_size = static_cast<int>(ekf.slots().size());
    rec.observed = static_cast<int>(features.size());
    if (k > 0) {
      nees_sum += rec.nees;
      ++nees_count;
      if (rec.nees >= nees_lo && rec.nees <= nees_hi) ++inside;
    }
    result.records.push_back(rec);
    result.path.push_back(ekf.robotMean().head<2>());
  }
  const StepRecord& last = result.records.back();
  result.final_position_error_m = last.error.head<2>().norm();
  result.final_heading_error_rad = std::abs(last.error[2]);
  result.nees_mean = nees_count > 0 ? nees_sum / nees_count : 0.0;
  result.nees_fraction_inside = nees_count > 0 ? static_cast<double>(inside) / nees_count : 0.0;
  double se = 0.0;
  int matched = 0;
  for (const sylva::LandmarkSlot& slot : ekf.slots()) {
    const Vec<2> m = ekf.landmarkMean<sylva::Point2>(slot.id);
    result.map.push_back({m, ekf.landmarkCovariance<sylva::Point2>(slot.id)});
    ++result.landmarks;
    const Id t = truth_of.at(slot.id);
    if (t < 0) {
      ++result.spurious;
      continue;
    }
    se += (m - true_position.at(t)).squaredNorm();
    ++matched;
  }
  result.landmark_rmse_m = matched > 0 ? std::sqrt(se / matched) : 0.0;
  return result;
}

}  // namespace laser_camera_slam
