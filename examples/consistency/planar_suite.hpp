#pragma once
// The `planar` suite of examples/consistency: the world of examples/range_bearing_slam (a
// unicycle robot driving a 120 m loop among 120 point landmarks, range-bearing sensor of the
// multisensor thesis' Table 3.1, odometry noise 5 cm/s and 1 deg/s) driven for two laps,
// with known data association and the simulator's true noise given to the filter.
//
// Ensemble seed s builds the world from deriveSeed(s, 0) and run i's noise from
// deriveSeed(s, 1 + i), exactly as `range_bearing_slam --seed s --runs N` does, so either
// program can check the other. One step: predict with the odometry, one batched update of
// every reading of a mapped landmark, then add the new ones through InverseRangeBearing.
//
// Recorded per run and step (from step 1: one prediction from P0 = 0 leaves a covariance of
// rank 2): the robot-pose NEES (3 dof) and that of its position (2) and heading (1) alone,
// the error e = Unicycle2D::difference(truth, estimate); and the NIS of every reading at the
// predicted state (2 dof), pooled.

#include <cstdint>
#include <string>
#include <vector>

#include <sylva/consistency/monte_carlo.hpp>
#include <sylva/consistency/nees.hpp>
#include <sylva/core/angles.hpp>
#include <sylva/filter/ekf.hpp>
#include <sylva/landmarks/point2.hpp>
#include <sylva/measurements/range_bearing.hpp>
#include <sylva/motion/unicycle_2d.hpp>
#include <sylva/sim/landmarks_2d.hpp>
#include <sylva/sim/loop_trajectory_2d.hpp>
#include <sylva/sim/random.hpp>
#include <sylva/sim/range_bearing_sensor.hpp>

namespace consistency {

using sylva::Gaussian;
using sylva::Id;
using sylva::Mat;
using sylva::Vec;

/// The range_bearing_slam defaults (its Options), driven for `laps` laps.
struct PlanarWorldOptions {
  int landmarks = 120;
  double min_separation_m = 1.5;
  double perimeter_m = 120.0;
  double speed_mps = 1.0;
  double dt_s = 0.1;
  double laps = 2.0;
  double max_range_m = 10.0;
  double fov_half_angle_rad = 90.0 * sylva::kRadPerDeg;
  double sigma_range_m = 0.05;
  double sigma_bearing_rad = 1.0 * sylva::kRadPerDeg;
  double sigma_v_mps = 0.05;
  double sigma_omega_radps = 1.0 * sylva::kRadPerDeg;
};

struct PlanarWorld {
  sylva::sim::LoopTrajectory2D trajectory;
  sylva::sim::RangeBearingSensor2D sensor;
  std::vector<sylva::sim::TrueLandmark2D> landmarks;
  int steps;
  Gaussian<2> odometry_noise;
  Gaussian<2> sensor_noise;
};

inline PlanarWorld makePlanarWorld(const PlanarWorldOptions& o, std::uint64_t seed) {
  sylva::sim::LoopTrajectory2DOptions t;
  t.perimeter_m = o.perimeter_m;
  t.speed_mps = o.speed_mps;
  t.dt_s = o.dt_s;
  t.sigma_v_mps = o.sigma_v_mps;
  t.sigma_omega_radps = o.sigma_omega_radps;
  sylva::sim::LoopTrajectory2D trajectory(t);
  sylva::sim::RangeBearingSensor2DOptions s;
  s.max_range_m = o.max_range_m;
  s.fov_half_angle_rad = o.fov_half_angle_rad;
  s.sigma_range_m = o.sigma_range_m;
  s.sigma_bearing_rad = o.sigma_bearing_rad;
  sylva::sim::Rng world_rng(sylva::sim::deriveSeed(seed, 0));
  sylva::sim::LandmarkField2DOptions field;
  field.count = o.landmarks;
  field.min_separation_m = o.min_separation_m;
  auto landmarks = sylva::sim::landmarksAlongPath(trajectory.path(), field, world_rng);
  const int steps = static_cast<int>(o.laps * trajectory.stepsPerLap() + 0.5);
  return PlanarWorld{trajectory,
                     sylva::sim::RangeBearingSensor2D(s),
                     std::move(landmarks),
                     steps,
                     Gaussian<2>::sigmas(Vec<2>(o.sigma_v_mps, o.sigma_omega_radps)),
                     Gaussian<2>::sigmas(Vec<2>(o.sigma_range_m, o.sigma_bearing_rad))};
}

/// The statistics of one ensemble of one mode.
struct PlanarEnsemble {
  sylva::NeesEnsemble pose{3}, position{2}, heading{1};
  sylva::NisTally range_bearing_nis{2};
  double final_position_error_sum_m = 0.0;  ///< |p_est - p_true| at the last step, summed over runs
  double landmark_squared_error_sum = 0.0;   ///< over every mapped landmark of every run
  int landmarks_mapped = 0;
  int runs = 0;
};

/// One run of `world` with the filter's linearization `point`; adds its statistics to `out`.
inline void runPlanar(const PlanarWorld& world,
                      sylva::LinearizationPoint point,
                      std::uint64_t seed,
                      int run,
                      PlanarEnsemble& out) {
  using Filter = sylva::Ekf<sylva::Unicycle2D, sylva::Point2>;
  sylva::sim::Rng rng(sylva::sim::deriveSeed(seed, 1 + static_cast<std::uint64_t>(run)));
  const auto truth = world.trajectory.simulate(world.steps, rng);
  const double dt = world.trajectory.dt();
  const bool ideal = point == sylva::LinearizationPoint::kIdeal;
  Filter ekf(world.trajectory.startPose(), Mat<3, 3>::Zero());
  ekf.setLinearizationPoint(point);
  ekf.reserve(2 * static_cast<int>(world.landmarks.size()));
  const sylva::RangeBearing model;
  const sylva::InverseRangeBearing inverse;
  std::vector<sylva::Observation<sylva::RangeBearing>> paired;
  Vec<3> previous_truth = world.trajectory.startPose();
  for (int k = 0; k < world.steps; ++k) {
    const auto& step = truth[static_cast<std::size_t>(k)];
    if (ideal) ekf.setIdealRobot(previous_truth);
    ekf.predict(step.odometry, dt, world.odometry_noise);
    if (ideal) ekf.setIdealRobot(step.true_pose);
    previous_truth = step.true_pose;
    const auto readings = world.sensor.observe(step.true_pose, world.landmarks, rng);
    paired.clear();
    for (const auto& reading : readings) {
      if (!ekf.contains(reading.id)) continue;
      paired.push_back({reading.id, reading.z, world.sensor_noise});
      out.range_bearing_nis.add(ekf.innovation(model, reading.id, reading.z, world.sensor_noise).nis());
    }
    if (!paired.empty()) ekf.update(model, paired);
    for (const auto& reading : readings) {
      if (ekf.contains(reading.id)) continue;
      ekf.add(reading.id, inverse, reading.z, world.sensor_noise);
      if (ideal)
        ekf.setIdealLandmark<sylva::Point2>(reading.id, world.landmarks[static_cast<std::size_t>(reading.id)].position);
    }
    if (k == 0) continue;
    const Vec<3> e = sylva::Unicycle2D::difference(step.true_pose, ekf.robotMean());
    const Mat<3, 3> P = ekf.robotCovariance();
    out.pose.add(run, k - 1, sylva::nees(e, P));
    out.position.add(run, k - 1, sylva::nees(Vec<2>(e.head<2>()), Mat<2, 2>(P.topLeftCorner<2, 2>())));
    out.heading.add(run, k - 1, e[2] * e[2] / P(2, 2));
  }
  out.final_position_error_sum_m += sylva::Unicycle2D::difference(truth.back().true_pose, ekf.robotMean()).head<2>().norm();
  for (const auto& slot : ekf.slots()) {
    out.landmark_squared_error_sum +=
        (ekf.landmarkMean<sylva::Point2>(slot.id) - world.landmarks[static_cast<std::size_t>(slot.id)].position)
            .squaredNorm();
    ++out.landmarks_mapped;
  }
  ++out.runs;
}

}  // namespace consistency
