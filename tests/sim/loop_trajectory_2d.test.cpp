#include "sylva_catch.hpp"

#include "error_helpers.hpp"

#include <cmath>

#include "sylva/sim/loop_trajectory_2d.hpp"

using sylva::ErrorCode;
using sylva::kPi;
using sylva::Vec;
using sylva::sim::LoopTrajectory2D;
using sylva::sim::LoopTrajectory2DOptions;
using sylva::sim::Rng;

namespace {

using sylva_test::throwsCode;

}  // namespace

TEST_CASE("LoopTrajectory2D: defaults are a 120 m lap of 1200 steps", "[sim][trajectory]") {
  const LoopTrajectory2D trajectory;
  CHECK(std::abs(trajectory.path().perimeter() - 120.0) < 1e-9);
  CHECK(trajectory.stepsPerLap() == 1200);
  CHECK(std::abs(trajectory.speed() - 1.0) < 1e-9);
  CHECK(trajectory.dt() == 0.1);
}

TEST_CASE("LoopTrajectory2D: the speed is adjusted to whole steps per lap", "[sim][trajectory]") {
  LoopTrajectory2DOptions options;
  options.perimeter_m = 100.03;
  options.speed_mps = 1.0;
  const LoopTrajectory2D trajectory(options);
  CHECK(trajectory.stepsPerLap() == 1000);
  CHECK(std::abs(trajectory.speed() - 1.0003) < 1e-12);
}

TEST_CASE("LoopTrajectory2D: the loop closes after one lap and after two", "[sim][trajectory]") {
  const LoopTrajectory2D trajectory;
  Rng rng(1);
  const auto steps = trajectory.simulate(2 * trajectory.stepsPerLap(), rng);
  const Vec<3> start = trajectory.startPose();
  for (int laps : {1, 2}) {
    const Vec<3> end =
        steps[static_cast<std::size_t>(laps * trajectory.stepsPerLap() - 1)].true_pose;
    const Vec<3> d = sylva::Unicycle2D::difference(end, start);
    CHECK(d.head<2>().norm() < 1e-3);
    CHECK(std::abs(d[2]) < 1e-9);
  }
}

TEST_CASE("LoopTrajectory2D: true poses follow the path", "[sim][trajectory]") {
  LoopTrajectory2DOptions options;
  options.perimeter_m = 80.0;
  options.corner_radius_m = 4.0;
  options.aspect = 1.5;
  const LoopTrajectory2D trajectory(options);
  Rng rng(5);
  const auto steps = trajectory.simulate(rng);
  REQUIRE(static_cast<int>(steps.size()) == trajectory.stepsPerLap());
  double worst = 0.0;
  for (std::size_t k = 0; k < steps.size(); ++k) {
    const double s = (k + 1) * trajectory.speed() * trajectory.dt();
    worst = std::max(worst, (steps[k].true_pose.head<2>() - trajectory.path().position(s)).norm());
    const double heading_error =
        sylva::wrapAngle(steps[k].true_pose[2] - trajectory.path().heading(s));
    REQUIRE(std::abs(heading_error) < 1e-9);
    REQUIRE(std::abs(steps[k].time_s - (k + 1) * trajectory.dt()) < 1e-12);
    REQUIRE(steps[k].true_control[0] == trajectory.speed());
  }
  CHECK(worst < 1e-3);
  // Straight sides drive with omega = 0, corners with v / r.
  CHECK(std::abs(steps[5].true_control[1]) < 1e-12);
  const int in_corner = static_cast<int>((0.5 * (trajectory.path().length() - 8.0) + 2.0) /
                                         (trajectory.speed() * trajectory.dt()));
  CHECK(std::abs(steps[static_cast<std::size_t>(in_corner)].true_control[1] -
                 trajectory.speed() / 4.0) < 1e-9);
}

TEST_CASE("LoopTrajectory2D: odometry is reproducible from the seed", "[sim][trajectory]") {
  const LoopTrajectory2D trajectory;
  Rng a(77), b(77), c(78);
  const auto sa = trajectory.simulate(500, a);
  const auto sb = trajectory.simulate(500, b);
  const auto sc = trajectory.simulate(500, c);
  int differ = 0;
  for (std::size_t k = 0; k < sa.size(); ++k) {
    REQUIRE(sa[k].odometry == sb[k].odometry);
    REQUIRE(sa[k].true_pose == sc[k].true_pose);  // the truth does not depend on the noise
    differ += sa[k].odometry != sc[k].odometry ? 1 : 0;
  }
  CHECK(differ == 500);
}

TEST_CASE("LoopTrajectory2D: odometry noise has the requested sigmas", "[sim][trajectory]") {
  LoopTrajectory2DOptions options;
  options.sigma_v_mps = 0.05;
  options.sigma_omega_radps = 0.02;
  const LoopTrajectory2D trajectory(options);
  Rng rng(9);
  const auto steps = trajectory.simulate(40000, rng);
  double sv = 0, sv2 = 0, sw = 0, sw2 = 0, cross = 0;
  for (const auto& step : steps) {
    const Vec<2> e = step.odometry - step.true_control;
    sv += e[0];
    sv2 += e[0] * e[0];
    sw += e[1];
    sw2 += e[1] * e[1];
    cross += e[0] * e[1];
  }
  const double n = static_cast<double>(steps.size());
  // 5 standard errors: mean sd = sigma / sqrt(n), variance relative sd = sqrt(2 / n).
  CHECK(std::abs(sv / n) < 5.0 * 0.05 / std::sqrt(n));
  CHECK(std::abs(sw / n) < 5.0 * 0.02 / std::sqrt(n));
  CHECK(std::abs(sv2 / n / (0.05 * 0.05) - 1.0) < 5.0 * std::sqrt(2.0 / n));
  CHECK(std::abs(sw2 / n / (0.02 * 0.02) - 1.0) < 5.0 * std::sqrt(2.0 / n));
  CHECK(std::abs(cross / n / (0.05 * 0.02)) < 5.0 / std::sqrt(n));
  const auto& Q = trajectory.odometryNoise().covariance();
  CHECK(std::abs(Q(0, 0) - 0.05 * 0.05) < 1e-15);
  CHECK(std::abs(Q(1, 1) - 0.02 * 0.02) < 1e-15);
}

TEST_CASE("LoopTrajectory2D: invalid arguments throw", "[sim][trajectory]") {
  const double nan = std::nan("");
  auto with = [](auto change) {
    LoopTrajectory2DOptions o;
    change(o);
    return o;
  };
  const ErrorCode bad = ErrorCode::kInvalidArgument;
  CHECK(throwsCode([&] { LoopTrajectory2D(with([](auto& o) { o.sigma_v_mps = 0.0; })); }, bad));
  CHECK(throwsCode([&] { LoopTrajectory2D(with([](auto& o) { o.sigma_omega_radps = -1.0; })); },
                   bad));
  CHECK(throwsCode([&] { LoopTrajectory2D(with([&](auto& o) { o.dt_s = nan; })); }, bad));
  CHECK(throwsCode([&] { LoopTrajectory2D(with([](auto& o) { o.dt_s = 0.0; })); }, bad));
  CHECK(throwsCode([&] { LoopTrajectory2D(with([](auto& o) { o.speed_mps = -1.0; })); }, bad));
  CHECK(throwsCode([&] { LoopTrajectory2D(with([](auto& o) { o.perimeter_m = 0.0; })); }, bad));
  CHECK(throwsCode([&] { LoopTrajectory2D(with([&](auto& o) { o.perimeter_m = nan; })); }, bad));
  const LoopTrajectory2D trajectory;
  Rng rng(0);
  CHECK(throwsCode([&] { trajectory.simulate(0, rng); }, bad));
  CHECK(throwsCode([&] { trajectory.simulate(-3, rng); }, bad));
}
