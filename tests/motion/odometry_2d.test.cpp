// Odometry2D: pose composition with an odometry increment, its Jacobians against central
// differences, and the filter's prediction with it (process noise = the increment's
// covariance rotated into the world frame).

#include <sylva/filter/ekf.hpp>
#include <sylva/landmarks/point2.hpp>
#include <sylva/measurements/range_bearing.hpp>
#include <sylva/motion/unicycle_2d.hpp>
#include <sylva/motion/odometry_2d.hpp>
#include <sylva/testing/check_jacobians.hpp>

#include "motion_autodiff.hpp"
#include "sylva_catch.hpp"

using namespace sylva;

namespace unity_motion_odometry_2d {

/// The rotation that carries a vector from the frame of a robot with heading `theta` into
/// the world frame, with the heading component left alone.
Mat<3, 3> planarRotation(double theta) {
  Mat<3, 3> R;
  R << std::cos(theta), -std::sin(theta), 0.0,  //
      std::sin(theta), std::cos(theta), 0.0,    //
      0.0, 0.0, 1.0;
  return R;
}

}  // namespace unity_motion_odometry_2d

TEST_CASE("Odometry2D composes the pose with the increment", "[motion]") {
  const Odometry2D motion;
  // Heading +90 degrees: forward in the robot frame is +y in the world, left is -x.
  const Vec<3> next = motion(Vec<3>(1.0, 2.0, kPi / 2), Vec<3>(0.5, 0.25, 0.1), 1.0);
  CHECK(next[0] == Approx(1.0 - 0.25));
  CHECK(next[1] == Approx(2.0 + 0.5));
  CHECK(next[2] == Approx(kPi / 2 + 0.1));
  // dt is not used: the increment is the whole motion.
  CHECK(motion(Vec<3>(1.0, 2.0, 0.3), Vec<3>(0.5, 0.25, 0.1), 0.0) ==
        motion(Vec<3>(1.0, 2.0, 0.3), Vec<3>(0.5, 0.25, 0.1), 7.0));
  // Crossing the seam keeps theta in (-pi, pi].
  const Vec<3> wrapped = motion(Vec<3>(0.0, 0.0, 3.1), Vec<3>(0.0, 0.0, 0.1), 1.0);
  CHECK(wrapped[2] == Approx(3.2 - 2 * kPi));
  // Composing with the zero increment leaves the pose unchanged.
  const Vec<3> pose(-4.0, 3.0, -2.5);
  CHECK((motion(pose, Vec<3>::Zero(), 1.0) - pose).norm() < 1e-15);
}

TEST_CASE("Odometry2D Jacobians match numerical and automatic differentiation", "[motion][jacobian]") {
  struct Case {
    const char* name;
    Vec<3> x;
    Vec<3> u;
  };
  const Case cases[] = {
      {"ordinary", Vec<3>(1.0, 2.0, 0.3), Vec<3>(1.0, 0.05, 0.02)},
      {"standing still", Vec<3>(1.0, 2.0, 0.3), Vec<3>(0.0, 0.0, 0.0)},
      {"sideways and backwards", Vec<3>(-3.0, 0.5, -1.0), Vec<3>(-0.7, 1.5, -0.4)},
      {"heading at the seam", Vec<3>(0.0, 0.0, kPi - 1e-3), Vec<3>(2.0, 0.5, 0.1)},
      {"large turn", Vec<3>(5.0, 5.0, 2.0), Vec<3>(3.0, -2.0, 2.5)},
  };
  for (const Case& c : cases) {
    INFO(c.name);
    sylva_test::requireMotionJacobians(Odometry2D{}, c.x, c.u, 1.0);
  }
}

TEST_CASE("Odometry2D noise Jacobian is the rotation by the heading", "[motion]") {
  Mat<3, 3> J_x;
  Mat<3, 3> J_n;
  const Vec<3> x(0.5, -1.0, 0.7);
  Odometry2D{}(x, Vec<3>(1.0, 0.2, 0.05), 1.0, J_x, J_n);
  CHECK((J_n - unity_motion_odometry_2d::planarRotation(0.7)).norm() < 1e-15);
}

TEST_CASE("Ekf with Odometry2D predicts F P F^T + R(theta) Sigma_u R(theta)^T", "[motion][filter]") {
  const Vec<3> x0(1.0, 2.0, 0.4);
  Mat<3, 3> P0;
  P0 << 0.04, 0.01, 0.002,  //
      0.01, 0.09, -0.003,   //
      0.002, -0.003, 0.01;
  Ekf<Odometry2D, Point2> ekf(x0, P0);
  Mat<3, 3> sigma_u;
  sigma_u << 4e-4, 1e-5, 0.0,  //
      1e-5, 1e-4, 0.0,         //
      0.0, 0.0, 2e-5;
  const Vec<3> u(0.8, 0.1, 0.05);
  ekf.predict(u, 1.0, Gaussian<3>::covariance(sigma_u));

  Mat<3, 3> F;
  const Vec<3> expected_mean = Odometry2D{}(x0, u, 1.0, F, {});
  const Mat<3, 3> R = unity_motion_odometry_2d::planarRotation(x0[2]);
  const Mat<3, 3> expected_cov = F * P0 * F.transpose() + R * sigma_u * R.transpose();
  CHECK((ekf.robotMean() - expected_mean).norm() < 1e-15);
  CHECK((ekf.robotCovariance() - expected_cov).norm() < 1e-15);
}

TEST_CASE("RangeBearing, written for Pose2D, serves Odometry2D and Unicycle2D alike", "[motion][filter]") {
  // The same prior and the same observation through both robots: the update only reads the
  // pose, so the posteriors must agree to rounding.
  const Vec<3> x0(1.0, 2.0, 0.4);
  const Mat<3, 3> P0 = Vec<3>(0.04, 0.09, 0.01).asDiagonal();
  const auto noise = Gaussian<2>::sigmas({0.1, 0.02});
  Ekf<Odometry2D, Point2> odometry(x0, P0);
  Ekf<Unicycle2D, Point2> unicycle(x0, P0);
  odometry.add(3, InverseRangeBearing{}, Vec<2>(4.0, 0.3), noise);
  unicycle.add(3, InverseRangeBearing{}, Vec<2>(4.0, 0.3), noise);
  const Vec<2> before = odometry.landmarkMean<Point2>(3);
  odometry.update(RangeBearing{}, 3, Vec<2>(4.1, 0.28), noise);
  unicycle.update(RangeBearing{}, 3, Vec<2>(4.1, 0.28), noise);
  CHECK((odometry.mean() - unicycle.mean()).norm() < 1e-14);
  CHECK((odometry.covariance() - unicycle.covariance()).norm() < 1e-14);
  CHECK((odometry.landmarkMean<Point2>(3) - before).norm() > 1e-2);  // the update did act
}
