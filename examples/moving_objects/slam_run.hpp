#pragma once
// 2D range-bearing EKF-SLAM (sylva::Ekf<Unicycle2D, Point2> with RangeBearing) on point
// features extracted from simulated laser scans, with and without removing the features
// that fall on detected moving objects.
//
// One simulation (true path, odometry, scans; scenes.hpp) feeds both variants, so they
// differ only in the removal. Per scan k (taken after odometry step k):
//   1. predict with the odometry;
//   2. place the scan in the world at the predicted pose, the previous scan at the previous
//      estimate (the alignment the detector needs comes from the filter);
//   3. extract point features (sylva/laser/pole_features.hpp);
//   4. with removal: run the detector on the two scans and drop every feature that shares
//      a reading with a detected moving object; with `memory_s` > 0 also drop features
//      within `memory_radius_m` of an object detected moving in the last memory_s seconds
//      (a leg at rest between two swings does not move and is not detected; its other leg,
//      swinging beside it a moment earlier, was); `oracle` (a diagnostic) drops exactly the
//      features the simulator says are legs, the best any removal could do;
//   5. sylva::slam::FrontEnd: individual-compatibility nearest neighbour (chi-square gate) pairs features with the
//      map; paired features are fused in one batched update; a feature whose NIS to every
//      candidate exceeds a wider gate becomes a new landmark (InverseRangeBearing); the rest
//      are dropped as ambiguous.
// The filter never sees the simulator's ids. For evaluation each feature takes the id of the
// object most of its readings hit, and each landmark the id of the feature that created it:
// landmarks born on poles are compared with their pole's centre (landmark RMS error),
// landmarks born on legs are counted as spurious.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <optional>
#include <unordered_map>
#include <vector>

#include <sylva/consistency/monte_carlo.hpp>
#include <sylva/consistency/nees.hpp>
#include <sylva/filter/ekf.hpp>
#include <sylva/landmarks/point2.hpp>
#include <sylva/laser/moving_object_detector.hpp>
#include <sylva/laser/pole_features.hpp>
#include <sylva/measurements/range_bearing.hpp>
#include <sylva/motion/unicycle_2d.hpp>
#include <sylva/sim/laser_scanner_2d.hpp>
#include <sylva/sim/loop_trajectory_2d.hpp>
#include <sylva/slam/front_end.hpp>
#include <sylva/slam/reach.hpp>

#include "scenes.hpp"

namespace moving_objects {

using namespace sylva::laser;  // the detector and its scans (include/sylva/laser)
using sylva::LaserScanGeometry;

using SlamFilter = sylva::Ekf<sylva::Unicycle2D, sylva::Point2>;

struct SlamRunOptions {
  SlamSceneOptions scene;
  sylva::sim::LaserScanner2DOptions scanner;
  DetectorOptions detector;
  FeatureOptions features;
  // Told to the filter. The features' centres lie 1.8 cm RMS from the true pole centres
  // (printed by the program); measured over 5 worlds their range error is +0.6 cm bias and
  // 1.5 cm sd, their bearing error 0.11 deg sd. Errors of one pole in consecutive scans are
  // correlated (the radius estimate), so the bearing sigma is inflated: without people the
  // robot NEES is then 3.3 (3 expected; `moving_objects --slam-people 0 --slam-seeds 30`).
  double sigma_feature_range_m = 0.02;
  double sigma_feature_bearing_rad = 0.25 * sylva::kRadPerDeg;
  double gate_probability = 0.99;
  double new_landmark_probability = 0.9999;
  double memory_s = 0.0;
  double memory_radius_m = 0.5;
  bool oracle = false;  ///< diagnostic: with removal, drop exactly the leg features (truth), no detector
};

/// The simulation both variants share.
struct SlamData {
  SlamScene scene;
  std::vector<sylva::sim::TrajectoryStep2D> truth;  ///< step k ends at truth[k].true_pose
  std::vector<sylva::sim::LaserScan2D> scans;       ///< scans[0] at the start, scans[k + 1] after step k
  LaserScanGeometry geometry;
};

inline SlamData simulateSlam(const SlamRunOptions& o, std::uint64_t seed) {
  SlamData data{makeSlamScene(o.scene, seed), {}, {}, {}};
  const sylva::sim::LaserScanner2D scanner(o.scanner);
  data.geometry = scanner.geometry();
  sylva::sim::Rng rng(sylva::sim::deriveSeed(seed, 300));
  data.truth = data.scene.trajectory.simulate(data.scene.steps, rng);
  sylva::sim::LaserScene2D snapshot;
  data.scene.world.snapshot(0.0, snapshot);
  data.scans.push_back(scanner.scan(data.scene.trajectory.startPose(), snapshot, rng));
  for (const auto& step : data.truth) {
    data.scene.world.snapshot(step.time_s, snapshot);
    data.scans.push_back(scanner.scan(step.true_pose, snapshot, rng));
    data.scans.back().time_s = step.time_s;
  }
  return data;
}

struct SlamResult {
  double landmark_rmse_m = 0.0;       ///< over landmarks born on poles
  int pole_landmarks = 0;
  int spurious_landmarks = 0;         ///< born on legs (or walls)
  double final_position_error_m = 0.0;
  double position_rmse_m = 0.0;       ///< over all steps
  sylva::NeesSeries nees{3};          ///< robot pose, per step (one run)
  long long features = 0;             ///< features extracted
  long long features_on_legs = 0;     ///< ... of which on a leg (truth)
  long long removed = 0;              ///< dropped as moving
  long long removed_on_legs = 0;      ///< ... of which on a leg (truth)
  long long leg_observations_used = 0;  ///< leg features fused or added
  long long leg_into_pole = 0;        ///< leg features fused into a pole-born landmark
  /// Leg features by how far the leg moved in the scan interval before (truth): [0] not at
  /// all (stance), [1] less than the closest-point threshold dd_c (too slow to detect,
  /// eq. 4.5), [2] more. Per class: extracted, removed, fused into an existing landmark.
  std::array<long long, 3> leg_by_motion{}, leg_removed_by_motion{}, leg_fused_by_motion{};
  /// Pole features (truth) whose pole has a leg within 0.3 m, and the rest: count and sum of
  /// squared errors of the feature's centre against the pole's (before any removal).
  long long pole_features_near_leg = 0, pole_features_clear = 0;
  double pole_near_leg_sq = 0.0, pole_clear_sq = 0.0;
  int duplicate_pole_landmarks = 0;  ///< pole-born landmarks beyond the first of their pole
  std::vector<Vec<2>> estimated_path;
  std::vector<std::pair<Vec<2>, Id>> landmarks;  ///< final estimate and true id
};

inline Id majorityObject(const sylva::sim::LaserScan2D& scan, const std::vector<int>& beams) {
  std::map<Id, int> votes;
  for (const int b : beams) ++votes[scan.hit_object[static_cast<std::size_t>(b)]];
  Id best = sylva::sim::kNoObject;
  int count = 0;
  for (const auto& [id, n] : votes)
    if (n > count) {
      count = n;
      best = id;
    }
  return best;
}

inline SlamResult runSlam(const SlamData& data, const SlamRunOptions& o, bool remove_moving) {
  using sylva::Gaussian;
  const LaserScanGeometry& g = data.geometry;
  const MovingObjectDetector detector(g, o.detector);
  const auto R = Gaussian<2>::sigmas(Vec<2>(o.sigma_feature_range_m, o.sigma_feature_bearing_rad));
  const auto& topt = data.scene.trajectory.options();
  const auto Q = Gaussian<2>::sigmas(Vec<2>(topt.sigma_v_mps, topt.sigma_omega_radps));
  const double dt = data.scene.trajectory.dt();
  SlamFilter ekf(data.scene.trajectory.startPose(), sylva::Mat<3, 3>::Zero());
  // Association with the map landmarks in reach (range + 1 m, field of view + 10 deg), by
  // nearest neighbour; a feature that pairs with nothing and is far from every candidate
  // starts a landmark at once.
  sylva::slam::FrontEndOptions front_end_options;
  front_end_options.association = sylva::slam::Association::kNearestNeighbor;
  front_end_options.gate_probability = o.gate_probability;
  front_end_options.new_landmark_probability = o.new_landmark_probability;
  const sylva::slam::RangeBearingReach reach{
      g.max_range_m + 1.0, 0.5 * (g.beams - 1) * g.angle_increment_rad + 10.0 * sylva::kRadPerDeg, 1e-6};
  sylva::slam::FrontEnd<SlamFilter, sylva::RangeBearing, sylva::InverseRangeBearing> front_end(
      sylva::RangeBearing{}, sylva::InverseRangeBearing{}, front_end_options,
      sylva::slam::candidatesInReach<sylva::Point2>(sylva::RangeBearing{}, reach));
  std::vector<sylva::slam::Reading<2>> readings;
  const auto slamStep = [&](const std::vector<PointFeature>& features, double time_s) -> const sylva::slam::StepReport& {
    readings.clear();
    for (const PointFeature& f : features) readings.push_back({f.z, R});
    return front_end.update(ekf, readings, time_s);
  };
  std::unordered_map<Id, Id> true_id_of;
  SlamResult result;
  struct Remembered {
    Vec<2> position;
    double time;
  };
  std::vector<Remembered> memory;

  AlignedScan previous = alignScan(g, data.scans[0].ranges_m, ekf.robotMean());
  {  // The first scan maps every feature.
    const std::vector<PointFeature> features = extractPointFeatures(g, previous, o.features);
    const sylva::slam::StepReport& report = slamStep(features, data.scans[0].time_s);
    for (std::size_t i = 0; i < features.size(); ++i)
      if (report.readings[i].outcome == sylva::slam::Outcome::kAdded)
        true_id_of[*report.readings[i].landmark] = majorityObject(data.scans[0], features[i].beams);
  }
  result.estimated_path.push_back(ekf.robotMean().head<2>());

  double squared_position_error = 0.0;
  for (std::size_t k = 0; k < data.truth.size(); ++k) {
    const auto& step = data.truth[k];
    const sylva::sim::LaserScan2D& scan = data.scans[k + 1];
    ekf.predict(step.odometry, dt, Q);
    const AlignedScan current = alignScan(g, scan.ranges_m, ekf.robotMean());
    std::vector<PointFeature> features = extractPointFeatures(g, current, o.features);
    std::vector<Id> feature_truth;
    std::vector<int> motion_class;  // of leg features (evaluation only), -1 otherwise
    for (const PointFeature& f : features) {
      feature_truth.push_back(majorityObject(scan, f.beams));
      ++result.features;
      motion_class.push_back(-1);
      const Id truth = feature_truth.back();
      if (truth >= kFirstPoleId && truth < kFirstLegId) {
        const Vec<2>& pole = data.scene.poles[static_cast<std::size_t>(truth - kFirstPoleId)].position;
        double nearest_leg = std::numeric_limits<double>::infinity();
        for (const auto& [id, position] : data.scene.world.dynamicObjectPositions(step.time_s))
          if (isLegId(id)) nearest_leg = std::min(nearest_leg, (position - pole).norm());
        // The feature's centre from the true pose, so that only the extraction is judged.
        const double a = step.true_pose[2] + f.z[1];
        const Vec<2> centre = step.true_pose.head<2>() + f.z[0] * Vec<2>(std::cos(a), std::sin(a));
        const double squared = (centre - pole).squaredNorm();
        if (nearest_leg < 0.3) {
          ++result.pole_features_near_leg;
          result.pole_near_leg_sq += squared;
        } else {
          ++result.pole_features_clear;
          result.pole_clear_sq += squared;
        }
      }
      if (!isLegId(truth)) continue;
      ++result.features_on_legs;
      const Vec<2> now = *data.scene.world.objectPosition(feature_truth.back(), step.time_s);
      const double moved = (now - *data.scene.world.objectPosition(feature_truth.back(), step.time_s - dt)).norm();
      const double threshold = rangeThreshold(o.detector.matching.match_k, o.detector.matching.match_floor_m,
                                              g.angle_increment_rad, f.z[0]);
      motion_class.back() = moved < 1e-6 ? 0 : (moved < threshold ? 1 : 2);
      ++result.leg_by_motion[static_cast<std::size_t>(motion_class.back())];
    }

    if (remove_moving) {
      const Detection d = detector.detect(previous, current, dt);
      for (const DetectedObject& object : d.objects) memory.push_back({object.hull_centroid, step.time_s});
      memory.erase(std::remove_if(memory.begin(), memory.end(),
                                  [&](const Remembered& m) { return step.time_s - m.time > o.memory_s + 1e-9; }),
                   memory.end());
      std::vector<PointFeature> kept;
      std::vector<Id> kept_truth;
      std::vector<int> kept_class;
      for (std::size_t i = 0; i < features.size(); ++i) {
        bool moving = false;
        for (const int b : features[i].beams) moving = moving || d.moving[static_cast<std::size_t>(b)] != 0;
        if (o.oracle) moving = isLegId(feature_truth[i]);
        if (o.memory_s > 0.0 && !o.oracle)
          for (const Remembered& m : memory)
            moving = moving || (m.position - features[i].world).norm() <= o.memory_radius_m;
        if (moving) {
          ++result.removed;
          if (isLegId(feature_truth[i])) ++result.removed_on_legs;
          if (motion_class[i] >= 0) ++result.leg_removed_by_motion[static_cast<std::size_t>(motion_class[i])];
        } else {
          kept.push_back(std::move(features[i]));
          kept_truth.push_back(feature_truth[i]);
          kept_class.push_back(motion_class[i]);
        }
      }
      features = std::move(kept);
      feature_truth = std::move(kept_truth);
      motion_class = std::move(kept_class);
    }

    const sylva::slam::StepReport& report = slamStep(features, scan.time_s);
    for (std::size_t i = 0; i < features.size(); ++i) {
      const sylva::slam::ReadingResult& r = report.readings[i];
      if (r.outcome == sylva::slam::Outcome::kAdded) {
        true_id_of[*r.landmark] = feature_truth[i];
        if (isLegId(feature_truth[i])) ++result.leg_observations_used;
      } else if (r.outcome == sylva::slam::Outcome::kPaired && isLegId(feature_truth[i])) {
        ++result.leg_observations_used;
        ++result.leg_fused_by_motion[static_cast<std::size_t>(motion_class[i])];
        const Id landmark_truth = true_id_of.at(*r.landmark);
        if (landmark_truth >= kFirstPoleId && landmark_truth < kFirstLegId) ++result.leg_into_pole;
      }
    }

    const Vec<3> estimate = ekf.robotMean();
    const Vec<3> error = sylva::Unicycle2D::difference(step.true_pose, estimate);
    if (k > 0) result.nees.add(static_cast<int>(k) - 1, sylva::nees(error, ekf.robotCovariance()));
    squared_position_error += error.head<2>().squaredNorm();
    result.estimated_path.push_back(estimate.head<2>());
    previous = alignScan(g, scan.ranges_m, estimate);
  }

  result.final_position_error_m =
      (ekf.robotMean().head<2>() - data.truth.back().true_pose.head<2>()).norm();
  result.position_rmse_m = std::sqrt(squared_position_error / static_cast<double>(data.truth.size()));
  double squared = 0.0;
  std::map<Id, int> per_pole;
  for (const sylva::LandmarkSlot& slot : ekf.slots()) {
    const Id truth = true_id_of.at(slot.id);
    const Vec<2> estimate = ekf.landmarkMean<sylva::Point2>(slot.id);
    result.landmarks.emplace_back(estimate, truth);
    if (truth >= kFirstPoleId && truth < kFirstLegId) {
      const Vec<2>& pole = data.scene.poles[static_cast<std::size_t>(truth - kFirstPoleId)].position;
      squared += (estimate - pole).squaredNorm();
      ++result.pole_landmarks;
      if (++per_pole[truth] > 1) ++result.duplicate_pole_landmarks;
    } else {
      ++result.spurious_landmarks;
    }
  }
  result.landmark_rmse_m = result.pole_landmarks > 0 ? std::sqrt(squared / result.pole_landmarks) : 0.0;
  return result;
}

}  // namespace moving_objects
