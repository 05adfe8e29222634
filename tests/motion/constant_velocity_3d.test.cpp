// ConstantVelocity3D: the constant-velocity camera motion with quaternion renormalization.

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <sylva/diff/numeric_diff.hpp>
#include <sylva/filter/ekf.hpp>
#include <sylva/motion/constant_velocity_3d.hpp>
#include <sylva/sim/forest_trajectory.hpp>
#include <sylva/testing/check_jacobians.hpp>

#include "../copy_init.hpp"
#include "sylva_catch.hpp"

using namespace sylva;

namespace {
Vec<13> cameraState(const Vec<3>& r, const Vec<4>& q, const Vec<3>& v, const Vec<3>& omega) {
  Vec<13> x;
  x << r, q, v, omega;
  return x;
}
const Vec<4> kIdentity(1.0, 0.0, 0.0, 0.0);
}  // namespace

TEST_CASE("ConstantVelocity3D moves at constant velocity and rotates by omega dt", "[motion]") {
  const ConstantVelocity3D motion;
  // Straight line.
  const Vec<13> x = cameraState(Vec<3>(1, 2, 3), kIdentity, Vec<3>(0.5, -1.0, 2.0), Vec<3>::Zero());
  const Vec<13> next = motion(x, Vec<0>(), 0.2);
  CHECK((next.head<3>() - Vec<3>(1.1, 1.8, 3.4)).norm() < 1e-15);
  CHECK(next.segment<4>(3) == kIdentity);
  CHECK(next.tail<6>() == x.tail<6>());
  // Turning about the camera's y axis at 0.5 rad/s for 2 s: a rotation of 1 rad.
  const Vec<13> turning = cameraState(Vec<3>::Zero(), kIdentity, Vec<3>::Zero(), Vec<3>(0.0, 0.5, 0.0));
  const Vec<4> q = motion(turning, Vec<0>(), 2.0).segment<4>(3);
  CHECK(q[0] == Approx(std::cos(0.5)));
  CHECK(q[2] == Approx(std::sin(0.5)));
  const Mat<3, 3> R = rotationMatrix<double>(q);
  CHECK(R(0, 0) == Approx(std::cos(1.0)));
  CHECK(R(0, 2) == Approx(std::sin(1.0)));
}

TEST_CASE("ConstantVelocity3D keeps the quaternion normalized", "[motion]") {
  const ConstantVelocity3D motion;
  Vec<13> x = cameraState(Vec<3>::Zero(), Vec<4>(2.0, 0.4, -0.2, 1.0), Vec<3>(1, 0, 0), Vec<3>(0.3, -0.2, 0.9));
  for (int k = 0; k < 1000; ++k) x = motion(x, Vec<0>(), 0.05);
  CHECK(x.segment<4>(3).norm() == Approx(1.0).epsilon(1e-14));
}

TEST_CASE("ConstantVelocity3D Jacobians match numerical differentiation", "[motion][jacobian]") {
  struct Case {
    const char* name;
    Vec<13> x;
    double dt;
  };
  const Vec<4> q = Vec<4>(0.9, 0.1, -0.3, 0.2).normalized();
  const Case cases[] = {
      {"ordinary", cameraState(Vec<3>(1, 2, 3), q, Vec<3>(0.5, -0.2, 0.1), Vec<3>(0.1, 0.2, -0.3)), 0.1},
      {"not rotating (exponential map at zero)", cameraState(Vec<3>(1, 2, 3), q, Vec<3>(0.5, 0, 0), Vec<3>::Zero()), 0.1},
      {"half a turn in one step", cameraState(Vec<3>::Zero(), q, Vec<3>::Zero(), Vec<3>(0.0, 0.0, 3.0)), 1.0},
      {"quaternion off the unit sphere", cameraState(Vec<3>::Zero(), 1.7 * q, Vec<3>(1, 1, 1), Vec<3>(0.2, 0.1, 0.0)), 0.1},
      {"zero time step", cameraState(Vec<3>(4, 5, 6), q, Vec<3>(1, 1, 1), Vec<3>(0.2, 0.1, 0.0)), 0.0},
  };
  for (const Case& c : cases) {
    INFO(c.name);
    const auto report = testing::checkMotionJacobians(ConstantVelocity3D{}, c.x, Vec<0>(), c.dt, 1e-6);
    INFO(report.message());
    CHECK(report.ok);
  }
}

TEST_CASE("ConstantVelocity3D with the velocity in the camera frame: Jacobians match numerical differentiation",
          "[motion][jacobian]") {
  const ConstantVelocity3D motion{ConstantVelocity3D::VelocityFrame::kCamera};
  const Vec<4> q = Vec<4>(0.9, 0.1, -0.3, 0.2).normalized();
  const Vec<13> cases[] = {
      cameraState(Vec<3>(1, 2, 3), q, Vec<3>(0.5, -0.2, 0.1), Vec<3>(0.1, 0.2, -0.3)),
      cameraState(Vec<3>(1, 2, 3), q, Vec<3>(0.5, 0, 0), Vec<3>::Zero()),           // exponential map at zero
      cameraState(Vec<3>::Zero(), q, Vec<3>(0, 0, 2), Vec<3>(0.0, 0.0, 3.0)),       // half a turn in one step
      cameraState(Vec<3>::Zero(), 1.7 * q, Vec<3>(1, 1, 1), Vec<3>(0.2, 0.1, 0.0)),  // quaternion off the sphere
  };
  for (const Vec<13>& x : cases)
    for (const double dt : {0.1, 1.0, 0.0}) {
      INFO("x = " << x.transpose() << ", dt = " << dt);
      const auto report = testing::checkMotionJacobians(motion, x, Vec<0>(), dt, 1e-6);
      INFO(report.message());
      CHECK(report.ok);
    }
}

TEST_CASE("ConstantVelocity3D with the velocity in the camera frame follows an arc", "[motion]") {
  using Frame = ConstantVelocity3D::VelocityFrame;
  // A camera looking along its direction of travel, pitched down, driving a circle of radius
  // 5 m at 1 m/s: its velocity and angular velocity are constant in its own frame.
  const double speed = 1.0, radius = 5.0, dt = 0.1, yaw_rate = speed / radius;
  const Mat<3, 3> R = sim::cameraOrientation(Vec<2>(1.0, 0.0), 0.25);
  const Eigen::Quaterniond q(R);
  const Vec<3> v_world(speed, 0.0, 0.0);
  const Vec<3> omega_camera = R.transpose() * Vec<3>(0.0, 0.0, yaw_rate);
  const Vec<13> world_state = cameraState(Vec<3>(0.0, -radius, 1.5), Vec<4>(q.w(), q.x(), q.y(), q.z()), v_world, omega_camera);
  const ConstantVelocity3D camera_frame{Frame::kCamera};
  Vec<13> x = camera_frame.fromWorldVelocity(world_state);
  CHECK((x.segment<3>(7) - R.transpose() * v_world).norm() < 1e-15);
  CHECK(ConstantVelocity3D{}.fromWorldVelocity(world_state) == world_state);
  const int steps = static_cast<int>(std::round(2.0 * kPi * radius / speed / dt));  // one lap
  for (int k = 0; k < steps; ++k) x = camera_frame(x, Vec<0>(), dt);
  // Back where it started, on the circle (chords of the arc: second order in yaw_rate dt).
  const Vec<3> centre(0.0, 0.0, 1.5);
  CHECK(std::abs((x.head<3>() - centre).norm() - radius) < 1e-3);
  CHECK((x.head<3>() - world_state.head<3>()).norm() < 2e-2);
  CHECK(x.segment<6>(7) == camera_frame.fromWorldVelocity(world_state).segment<6>(7));
  // The world-frame model drives straight on from the same state.
  Vec<13> y = world_state;
  for (int k = 0; k < steps; ++k) y = ConstantVelocity3D{}(y, Vec<0>(), dt);
  CHECK(y[0] == Approx(speed * steps * dt));
}

TEST_CASE("ConstantVelocity3D::normalizationJacobian is the derivative of normalize", "[motion][jacobian]") {
  // Checked against central differences of normalize itself (the dense reference filter calls
  // normalizationJacobian too, so agreeing with it proves nothing), at a unit quaternion, at
  // norms far from 1 and with a negative w.
  const auto normalized = [](const sylva::Vec<13>& x) {
    sylva::Vec<13> y = x;
    sylva::ConstantVelocity3D::normalize(y);
    return y;
  };
  for (const double scale : {1.0, 0.05, 3.0, 40.0}) {
    sylva::Vec<13> x;
    x << 1.0, -2.0, 0.5, sylva::Vec<4>(0.3, -0.5, 0.7, -0.41).normalized() * scale, 0.3, -0.2, 0.1, 0.05, 0.1, -0.2;
    if (scale == 40.0) x.segment<4>(3) *= -1.0;
    INFO("quaternion norm " << x.segment<4>(3).norm());
    const sylva::Mat<13, 13> analytic = sylva::ConstantVelocity3D::normalizationJacobian(x);
    const sylva::Mat<13, 13> numeric = sylva::numericJacobian<13, 13>(normalized, x, 1e-7);
    const double tolerance = 1e-7 * std::max(1.0, analytic.cwiseAbs().maxCoeff());
    CHECK((analytic - numeric).cwiseAbs().maxCoeff() < tolerance);
    // The normalization removes the radial direction: N q = 0 in the quaternion block.
    CHECK((analytic.block<4, 4>(3, 3) * x.segment<4>(3)).norm() < 1e-12 * analytic.norm() * x.segment<4>(3).norm());
  }
}

TEST_CASE("ConstantVelocity3D rejects a zero quaternion", "[motion][errors]") {
  using Catch::Matchers::Contains;
  const Vec<13> x = cameraState(Vec<3>::Zero(), Vec<4>::Zero(), Vec<3>::Zero(), Vec<3>::Zero());
  CHECK_THROWS_WITH(ConstantVelocity3D{}(x, Vec<0>(), 0.1), Contains("quaternion has norm 0"));
}

namespace {
struct Point3Stub {
  static constexpr int kDim = 3;
  static constexpr const char* kName = "Point3Stub";
};
}  // namespace

TEST_CASE("the filter predicts a camera with acceleration noise", "[motion][filter]") {
  const Vec<13> x0 = cameraState(Vec<3>::Zero(), kIdentity, Vec<3>(1, 0, 0), Vec<3>(0, 0.1, 0));
  Mat<13, 13> P0 = Mat<13, 13>::Zero();
  P0.bottomRightCorner<6, 6>() = 0.01 * Mat<6, 6>::Identity();
  Ekf<ConstantVelocity3D, Point3Stub> ekf(x0, P0);
  const auto acceleration = Gaussian<6>::sigmas((Vec<6>() << 0.5, 0.5, 0.5, 0.2, 0.2, 0.2).finished());
  for (int k = 0; k < 50; ++k) ekf.predict(Vec<0>(), 1.0 / 30.0, acceleration);
  CHECK(ekf.robotMean().segment<4>(3).norm() == Approx(1.0));
  CHECK(ekf.robotMean()[0] == Approx(50.0 / 30.0));
  const Mat<13, 13> P = ekf.robotCovariance();
  CHECK(Eigen::SelfAdjointEigenSolver<Mat<13, 13>>(P).eigenvalues().minCoeff() > -1e-12);
  CHECK(P(0, 0) > 0.01);  // position uncertainty grew from the velocity uncertainty
}

namespace {
/// Reads the camera quaternion directly (a test sensor; prediction only, so autodiff).
struct QuaternionSensor {
  using Robot = ConstantVelocity3D;
  using Landmark = Point3Stub;
  static constexpr int kDim = 4;
  static constexpr const char* kName = "QuaternionSensor";
  template <typename T>
  Vec<4, T> predict(const Vec<13, T>& x, const Vec<3, T>& /*l*/) const {
    return x.template segment<4>(3);
  }
};
}  // namespace

TEST_CASE("an update renormalizes the quaternion and projects its covariance", "[motion][filter]") {
  const Vec<4> q = Vec<4>(0.9, 0.1, -0.3, 0.2).normalized();
  const Vec<13> x0 = cameraState(Vec<3>::Zero(), q, Vec<3>::Zero(), Vec<3>::Zero());
  Mat<13, 13> P0 = Mat<13, 13>::Identity() * 0.01;
  P0.block<4, 4>(3, 3) = (Mat<4, 4>::Identity() - q * q.transpose()) * 0.01;  // tangent to the sphere
  Ekf<ConstantVelocity3D, Point3Stub> ekf(x0, P0);
  ekf.add(1, sylva_test::CopyInit<ConstantVelocity3D, Point3Stub>{}, Vec<3>(1, 2, 3), Gaussian<3>::sigmas(Vec<3>::Constant(0.1)));
  // A measured quaternion off the unit sphere pulls the mean off it before renormalization.
  ekf.update(QuaternionSensor{}, 1, Vec<4>(1.2 * q + Vec<4>(0.0, 0.05, 0.0, 0.0)),
             Gaussian<4>::sigmas(Vec<4>::Constant(0.05)));
  const Vec<4> q_new = ekf.robotMean().segment<4>(3);
  CHECK(q_new.norm() == Approx(1.0).epsilon(1e-14));
  const Mat<13, 13> P = ekf.robotCovariance();
  // No variance along the quaternion itself: the covariance lies in the sphere's tangent space.
  CHECK(q_new.dot(P.block<4, 4>(3, 3) * q_new) < 1e-15);
  CHECK(Eigen::SelfAdjointEigenSolver<Mat<13, 13>>(P).eigenvalues().minCoeff() > -1e-12);
}
