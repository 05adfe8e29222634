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
#include <optional>
#include <string>
#include <vector>

#include <sylva/consistency/monte_carlo.hpp>
#include <sylva/consistency/nees.hpp>
#include <sylva/filter/ekf.hpp>
#include <sylva/landmarks/point2.hpp>
#include <sylva/measurements/range_bearing.hpp>
#include <sylva/motion/unicycle_2d.hpp>
#include <sylva/sim/planar_loop_world.hpp>
#include <sylva/sim/random.hpp>
#include <sylva/slam/front_end.hpp>

namespace consistency {

using sylva::Gaussian;
using sylva::Id;
using sylva::Mat;
using sylva::Vec;

/// The range_bearing_slam world (sylva::sim::PlanarLoopWorld with its defaults), driven for
/// `laps` laps, and the noise the filter is told (the simulator's own).
struct PlanarWorld {
  sylva::sim::PlanarLoopWorld sim;
  int steps;
  Gaussian<2> odometry_noise;
  Gaussian<2> sensor_noise;
};

inline PlanarWorld makePlanarWorld(std::uint64_t seed, double laps = 2.0) {
  const sylva::sim::PlanarLoopWorldOptions o;
  sylva::sim::PlanarLoopWorld sim = sylva::sim::makePlanarLoopWorld(o, seed);
  const int steps = static_cast<int>(laps * sim.trajectory.stepsPerLap() + 0.5);
  return PlanarWorld{std::move(sim), steps,
                     Gaussian<2>::sigmas(Vec<2>(o.trajectory.sigma_v_mps, o.trajectory.sigma_omega_radps)),
                     Gaussian<2>::sigmas(Vec<2>(o.sensor.sigma_range_m, o.sensor.sigma_bearing_rad))};
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
  const auto truth = world.sim.trajectory.simulate(world.steps, rng);
  const double dt = world.sim.trajectory.dt();
  const bool ideal = point == sylva::LinearizationPoint::kIdeal;
  Filter ekf(world.sim.trajectory.startPose(), Mat<3, 3>::Zero());
  ekf.setLinearizationPoint(point);
  ekf.reserve(2 * static_cast<int>(world.sim.landmarks.size()));
  sylva::slam::FrontEndOptions options;
  options.association = sylva::slam::Association::kKnownIds;
  options.report_nis = true;
  sylva::slam::FrontEnd<Filter, sylva::RangeBearing, sylva::InverseRangeBearing> front_end(
      sylva::RangeBearing{}, sylva::InverseRangeBearing{}, options);
  std::vector<sylva::slam::Reading<2>> told;
  Vec<3> previous_truth = world.sim.trajectory.startPose();
  for (int k = 0; k < world.steps; ++k) {
    const auto& step = truth[static_cast<std::size_t>(k)];
    if (ideal) ekf.setIdealRobot(previous_truth);
    ekf.predict(step.odometry, dt, world.odometry_noise);
    if (ideal) ekf.setIdealRobot(step.true_pose);
    previous_truth = step.true_pose;
    const auto readings = world.sim.sensor.observe(step.true_pose, world.sim.landmarks, rng);
    told.clear();
    for (const auto& reading : readings) told.push_back({reading.z, world.sensor_noise, std::nullopt, reading.id});
    const sylva::slam::StepReport& report = front_end.update(ekf, told, k * dt);
    for (std::size_t i = 0; i < readings.size(); ++i) {
      const sylva::slam::ReadingResult& r = report.readings[i];
      if (r.outcome == sylva::slam::Outcome::kPaired) out.range_bearing_nis.add(r.nis);
      if (r.outcome == sylva::slam::Outcome::kAdded && ideal)
        ekf.setIdealLandmark<sylva::Point2>(
            readings[i].id, world.sim.landmarks[static_cast<std::size_t>(readings[i].id)].position);
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
        (ekf.landmarkMean<sylva::Point2>(slot.id) - world.sim.landmarks[static_cast<std::size_t>(slot.id)].position)
            .squaredNorm();
    ++out.landmarks_mapped;
  }
  ++out.runs;
}

}  // namespace consistency
