// Whole-filter behaviour on simulated 2D SLAM runs: the covariance stays symmetric positive
// semi-definite over 10,000 steps, and the robot-pose NEES over 50 Monte Carlo runs lies in its
// 95% bounds with the true noise models but not when the filter is told 10x smaller noise.

#include <Eigen/Eigenvalues>

#include <sylva/consistency.hpp>
#include <sylva/sim.hpp>
#include <sylva/sylva.hpp>

#include "sylva_catch.hpp"

// Own namespace: the tests of a folder are compiled as one unity translation unit.
namespace unity_filter_slam_run {

using namespace sylva;

namespace {

struct Scenario {
  sim::LoopTrajectory2DOptions trajectory;
  sim::RangeBearingSensor2DOptions sensor;
  int landmarks = 60;
  Scenario() {
    trajectory.perimeter_m = 100.0;
    trajectory.sigma_v_mps = 0.05;                    // 5 cm/s
    trajectory.sigma_omega_radps = 1.0 * kPi / 180.0;  // 1 deg/s
    sensor.max_range_m = 8.0;
  }
};

/// Runs known-id EKF-SLAM for `steps` steps; `told_scale` multiplies the sigmas the filter is
/// told. `on_step(k, ekf, true_pose)` is called after every step.
template <typename Filter, typename OnStep>
void runSlam(const Scenario& scenario, int steps, std::uint64_t seed, double told_scale, OnStep&& on_step) {
  sim::Rng rng(seed);
  const sim::LoopTrajectory2D trajectory(scenario.trajectory);
  sim::LandmarkField2DOptions field;
  field.count = scenario.landmarks;
  const auto landmarks = sim::landmarksAlongPath(trajectory.path(), field, rng);
  const sim::RangeBearingSensor2D sensor(scenario.sensor);
  const auto truth = trajectory.simulate(steps, rng);

  const auto q = Gaussian<2>::sigmas(told_scale * Vec<2>(scenario.trajectory.sigma_v_mps,
                                                         scenario.trajectory.sigma_omega_radps));
  const auto r = Gaussian<2>::sigmas(told_scale * Vec<2>(scenario.sensor.sigma_range_m,
                                                         scenario.sensor.sigma_bearing_rad));
  Filter ekf(trajectory.startPose(), Mat<3, 3>::Zero());
  ekf.reserve(2 * scenario.landmarks);
  for (int k = 0; k < steps; ++k) {
    ekf.predict(truth[k].odometry, trajectory.dt(), q);
    for (const sim::RangeBearingReading& reading : sensor.observe(truth[k].true_pose, landmarks, rng)) {
      if (ekf.contains(reading.id)) {
        ekf.update(RangeBearing{}, reading.id, reading.z, r);
      } else {
        ekf.add(reading.id, InverseRangeBearing{}, reading.z, r);
      }
    }
    on_step(k, ekf, truth[k].true_pose);
  }
}

double poseNees(const Vec<3>& truth, const Vec<3>& estimate, const Mat<3, 3>& P) {
  return nees(Unicycle2D::difference(truth, estimate), P);
}

}  // namespace

TEMPLATE_TEST_CASE("a 10,000-step run keeps P symmetric positive semi-definite", "[filter][slow]",
                   (Ekf<Unicycle2D, Point2>), (JosephEkf<Unicycle2D, Point2>)) {
  Scenario scenario;
  scenario.landmarks = 50;
  int checks = 0;
  double worst = 0.0;
  runSlam<TestType>(scenario, 10000, 1234, 1.0, [&](int k, const TestType& ekf, const Vec<3>&) {
    if ((k + 1) % 1000 != 0) return;
    const Eigen::MatrixXd P = ekf.covariance();
    REQUIRE(P.allFinite());
    const double min_eig = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(P, Eigen::EigenvaluesOnly).eigenvalues().minCoeff();
    worst = std::min(worst, min_eig / P.cwiseAbs().maxCoeff());
    CHECK(min_eig >= -1e-12 * P.cwiseAbs().maxCoeff());
    ++checks;
  });
  INFO("worst relative eigenvalue " << worst);
  CHECK(checks == 10);
}

TEST_CASE("robot-pose NEES over 50 runs: inside the 95% bounds when told the truth, outside when told 10x less noise",
          "[filter][consistency][slow]") {
  const Scenario scenario;
  const int runs = 50;
  const int steps = 1000;  // one lap of 100 m, with the loop closure
  // The start pose is known exactly (P0 = 0) and one step of odometry noise has rank 2, so the
  // pose covariance is singular for the first step; NEES is recorded from step 10 on.
  constexpr int kFirstStep = 10;
  auto series = [&](double told_scale) {
    NeesSeries out(3);
    for (int run = 0; run < runs; ++run) {
      runSlam<Ekf<Unicycle2D, Point2>>(scenario, steps, sim::deriveSeed(99, run), told_scale,
                                       [&](int k, const Ekf<Unicycle2D, Point2>& ekf, const Vec<3>& truth) {
                                         if (k >= kFirstStep)
                                           out.add(k - kFirstStep, poseNees(truth, ekf.robotMean(), ekf.robotCovariance()));
                                       });
    }
    return out;
  };
  const NeesSeries told_truth = series(1.0);
  const auto [lo, hi] = told_truth.bounds(0.95);
  INFO("true noise: mean NEES " << told_truth.mean() << " in [" << lo << ", " << hi << "], "
                                << 100 * told_truth.fractionInside() << "% of steps inside");
  CHECK(told_truth.mean() > lo);
  CHECK(told_truth.mean() < hi);
  // Per step, EKF-SLAM's known optimism (linearization at the estimate; Bailey et al. 2006,
  // Huang et al. 2008) lifts the run-averaged NEES from ~3 to ~4 along the lap until the loop
  // closes: measured 72% of steps inside with these noise levels, 97-100% with the 10x smaller
  // odometry noise of the thesis' Table 3.1. The bar below catches a real inconsistency.
  CHECK(told_truth.fractionInside() > 0.6);

  const NeesSeries told_less = series(0.1);
  INFO("10x smaller noise: mean NEES " << told_less.mean() << ", "
                                       << 100 * told_less.fractionInside() << "% of steps inside");
  CHECK(told_less.mean() > hi);
  CHECK(told_less.fractionInside() < 0.2);
}

}  // namespace unity_filter_slam_run
