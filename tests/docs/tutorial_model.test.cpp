// The code of docs/tutorial_add_measurement_model.md, compiled and run. Every region between
// "[tutorial-... begin]" and "[tutorial-... end]" is quoted verbatim in the tutorial; the
// last test case checks that, so the page cannot drift from code that works.
#include "sylva_catch.hpp"

#include <cmath>
#include <string>

#include <sylva/sylva.hpp>
#include <sylva/testing/check_jacobians.hpp>

#include "doc_snippets.hpp"

namespace {

// [tutorial-model begin]
// Where a Point2 landmark appears in the robot's own frame:  z = R(theta)^T (l - t),
// z = [ahead_m, left_m]. Think of a stereo camera or a laser scanner that reports the
// centre of a pole.
struct RelativePosition {
  using Robot = sylva::Pose2D;      // the pose the sensor sees: serves every planar robot
  using Landmark = sylva::Point2;   // the landmark parametrization it observes
  static constexpr int kDim = 2;    // size of one measurement
  static constexpr const char* kName = "RelativePosition";  // appears in error messages

  // h(robot, landmark), generic in the scalar T so that sylva can differentiate it.
  template <typename T>
  sylva::Vec<2, T> predict(const sylva::Vec<3, T>& robot, const sylva::Vec<2, T>& landmark) const {
    using std::cos;
    using std::sin;
    const T c = cos(robot[2]);
    const T s = sin(robot[2]);
    const T dx = landmark[0] - robot[0];
    const T dy = landmark[1] - robot[1];
    sylva::Vec<2, T> z;
    z[0] = c * dx + s * dy;   // ahead of the robot
    z[1] = -s * dx + c * dy;  // to its left
    return z;
  }
};
// [tutorial-model end]

// [tutorial-inverse begin]
// The landmark from one measurement:  l = t + R(theta) z, with its Jacobians
// J_l_x = dl/d[x, y, theta] (2x3) and J_l_z = dl/dz (2x2).
struct InverseRelativePosition {
  using Robot = sylva::Pose2D;
  using Landmark = sylva::Point2;
  static constexpr int kMeasurementDim = 2;
  static constexpr const char* kName = "InverseRelativePosition";

  sylva::Vec<2> operator()(const sylva::Vec<3>& robot,
                           const sylva::Vec<2>& z,
                           sylva::JacobianRef<2, 3> J_l_x = {},
                           sylva::JacobianRef<2, 2> J_l_z = {}) const {
    const double c = std::cos(robot[2]);
    const double s = std::sin(robot[2]);
    if (J_l_x) {
      *J_l_x << 1.0, 0.0, -s * z[0] - c * z[1],  //
          0.0, 1.0, c * z[0] - s * z[1];
    }
    if (J_l_z) {
      *J_l_z << c, -s,  //
          s, c;
    }
    return sylva::Vec<2>(robot[0] + c * z[0] - s * z[1], robot[1] + s * z[0] + c * z[1]);
  }
};
// [tutorial-inverse end]

// [tutorial-analytic begin]
// The same sensor with its analytic Jacobians. In your own code, put this operator() into
// the model struct itself; here it lives in a derived struct so that the test can compare
// both versions.
struct RelativePositionAnalytic : RelativePosition {
  static constexpr const char* kName = "RelativePositionAnalytic";

  // z, and when asked for: J_z_x = dz/d[x, y, theta] (2x3), J_z_l = dz/d[x_l, y_l] (2x2).
  sylva::Vec<2> operator()(const sylva::Vec<3>& robot,
                           const sylva::Vec<2>& landmark,
                           sylva::JacobianRef<2, 3> J_z_x = {},
                           sylva::JacobianRef<2, 2> J_z_l = {}) const {
    const sylva::Vec<2> z = predict<double>(robot, landmark);
    const double c = std::cos(robot[2]);
    const double s = std::sin(robot[2]);
    if (J_z_x) {
      *J_z_x << -c, -s, z[1],  //
          s, -c, -z[0];
    }
    if (J_z_l) {
      *J_z_l << c, s,  //
          -s, c;
    }
    return z;
  }
};
// [tutorial-analytic end]

// [tutorial-robot begin]
// A differential-drive robot whose gyro reads the turn rate with an unknown bias b, which
// the filter estimates as a state: x = [x, y, theta, b], control u = [v, omega_gyro],
// noise n = [n_v, n_omega, n_b] (speed and gyro noise, and the rate at which the bias
// drifts). Deriving from Pose2DWithExtras<4> gives it a pose view (`using Pose = Pose2D`
// and `pose(x, J)`, the first three entries), `normalize` and `difference`: every model
// written for Pose2D serves it unchanged.
struct GyroBiasUnicycle : sylva::Pose2DWithExtras<4> {
  static constexpr int kControlDim = 2;
  static constexpr int kNoiseDim = 3;
  static constexpr const char* kName = "GyroBiasUnicycle";
  using Control = sylva::Vec<2>;

  // The motion with noise n, generic in the scalar: what checkMotionJacobians differentiates.
  template <typename T>
  sylva::Vec<4, T> propagate(const sylva::Vec<4, T>& x, const sylva::Vec<2, T>& u,
                             const sylva::Vec<3, T>& n, double dt) const {
    using std::cos;
    using std::sin;
    const T v = u[0] + n[0];
    const T omega = u[1] + n[1] - x[3];              // the gyro reads omega + b
    const T heading = x[2] + T(0.5 * dt) * omega;    // the heading halfway through the step
    sylva::Vec<4, T> next;
    next[0] = x[0] + T(dt) * v * cos(heading);
    next[1] = x[1] + T(dt) * v * sin(heading);
    next[2] = sylva::wrapAngle(T(x[2] + T(dt) * omega));
    next[3] = x[3] + T(dt) * n[2];
    return next;
  }

  // x' = f(x, u, dt) with J_x = dx'/dx (4x4) and J_n = dx'/dn (4x3), at n = 0.
  sylva::Vec<4> operator()(const sylva::Vec<4>& x, const Control& u, double dt,
                           sylva::JacobianRef<4, 4> J_x = {},
                           sylva::JacobianRef<4, 3> J_n = {}) const {
    const double v = u[0];
    const double heading = x[2] + 0.5 * dt * (u[1] - x[3]);
    const double c = std::cos(heading);
    const double s = std::sin(heading);
    if (J_x) {
      *J_x << 1.0, 0.0, -dt * v * s, 0.5 * dt * dt * v * s,  //
          0.0, 1.0, dt * v * c, -0.5 * dt * dt * v * c,      //
          0.0, 0.0, 1.0, -dt,                                //
          0.0, 0.0, 0.0, 1.0;
    }
    if (J_n) {
      *J_n << dt * c, -0.5 * dt * dt * v * s, 0.0,  //
          dt * s, 0.5 * dt * dt * v * c, 0.0,       //
          0.0, dt, 0.0,                             //
          0.0, 0.0, dt;
    }
    return propagate<double>(x, u, sylva::Vec<3>::Zero(), dt);
  }
};
// [tutorial-robot end]

// A deliberately wrong Jacobian (one sign flipped), to show that the checker notices.
struct RelativePositionWrongSign : RelativePosition {
  sylva::Vec<2> operator()(const sylva::Vec<3>& robot,
                           const sylva::Vec<2>& landmark,
                           sylva::JacobianRef<2, 3> J_z_x = {},
                           sylva::JacobianRef<2, 2> J_z_l = {}) const {
    const sylva::Vec<2> z = RelativePositionAnalytic{}(robot, landmark, J_z_x, J_z_l);
    if (J_z_x) (*J_z_x)(0, 2) = -(*J_z_x)(0, 2);
    return z;
  }
};

// [tutorial-residual begin]
// Bearing only, e.g. a camera that sees the landmark but not how far away it is.
struct Bearing {
  using Robot = sylva::Pose2D;
  using Landmark = sylva::Point2;
  static constexpr int kDim = 1;
  static constexpr const char* kName = "Bearing";

  template <typename T>
  sylva::Vec<1, T> predict(const sylva::Vec<3, T>& robot, const sylva::Vec<2, T>& landmark) const {
    const T dx = landmark[0] - robot[0];
    const T dy = landmark[1] - robot[1];
    // No bearing to a landmark on top of the robot: say so instead of returning garbage.
    if (!(sylva::scalarValue(T(dx * dx + dy * dy)) > 1e-18))
      sylva::fail(sylva::ErrorCode::kDegenerateGeometry, "Bearing: landmark at the robot position");
    sylva::Vec<1, T> z;
    z[0] = sylva::wrapAngle(T(sylva::atan2Generic(dy, dx) - robot[2]));
    return z;
  }

  // z - z_hat with the angle wrapped: a measured 3.1 rad against a predicted -3.1 rad is an
  // innovation of -0.083 rad, not 6.2 rad.
  sylva::Vec<1> residual(const sylva::Vec<1>& z, const sylva::Vec<1>& z_hat) const {
    return sylva::Vec<1>(sylva::wrapAngle(z[0] - z_hat[0]));
  }
};
// [tutorial-residual end]

using Filter = sylva::Ekf<sylva::Unicycle2D, sylva::Point2>;

}  // namespace

TEST_CASE("tutorial: a new model works with Ekf::update through automatic differentiation") {
  // [tutorial-use begin]
  sylva::Ekf<sylva::Unicycle2D, sylva::Point2> ekf(sylva::Vec<3>::Zero(), sylva::Mat<3, 3>::Zero());
  const auto sensor_noise = sylva::Gaussian<2>::sigmas({0.05, 0.05});   // metres, both axes
  const auto odometry_noise = sylva::Gaussian<2>::sigmas({0.1, 0.05});  // [m/s, rad/s]

  // First sighting: 3 m ahead, 1 m to the left.
  ekf.add(1, InverseRelativePosition{}, sylva::Vec<2>(3.0, 1.0), sensor_noise);

  // Drive, then see landmark 1 again. RelativePosition has no analytic Jacobian, so the
  // filter differentiates predict<T> with Eigen's AutoDiffScalar.
  ekf.predict(sylva::Vec<2>(1.0, 0.2), 1.0, odometry_noise);
  const auto innovation =
      ekf.update(RelativePosition{}, 1, sylva::Vec<2>(2.144, 0.484), sensor_noise);
  // [tutorial-use end]

  // The measurement agrees with the prediction (the numbers were made from the true pose).
  CHECK(innovation.nu.norm() < 1e-3);
  CHECK((ekf.landmarkMean<sylva::Point2>(1) - sylva::Vec<2>(3.0, 1.0)).norm() < 1e-3);
  // Re-observing the landmark made the robot more certain than odometry alone.
  Filter odometry_only(sylva::Vec<3>::Zero(), sylva::Mat<3, 3>::Zero());
  odometry_only.add(1, InverseRelativePosition{}, sylva::Vec<2>(3.0, 1.0), sensor_noise);
  odometry_only.predict(sylva::Vec<2>(1.0, 0.2), 1.0, odometry_noise);
  CHECK(ekf.robotCovariance().trace() < odometry_only.robotCovariance().trace());
}

TEST_CASE("tutorial: analytic and automatic Jacobians give the same update") {
  const auto sensor_noise = sylva::Gaussian<2>::sigmas({0.05, 0.05});
  const auto odometry_noise = sylva::Gaussian<2>::sigmas({0.1, 0.05});
  Filter automatic(sylva::Vec<3>(0.5, -1.0, 0.3), sylva::Mat<3, 3>::Identity() * 0.01);
  Filter analytic = automatic;
  const sylva::Vec<2> landmarks[] = {{3.0, 1.0}, {-2.0, 4.0}, {5.0, -3.0}};
  sylva::Vec<3> truth(0.5, -1.0, 0.3);
  for (int i = 0; i < 3; ++i) {
    const sylva::Vec<2> z = RelativePosition{}.predict<double>(truth, landmarks[i]);
    automatic.add(i, InverseRelativePosition{}, z, sensor_noise);
    analytic.add(i, InverseRelativePosition{}, z, sensor_noise);
  }
  for (int step = 0; step < 20; ++step) {
    const sylva::Vec<2> u(0.8, 0.15);
    truth = sylva::Unicycle2D{}(truth, u, 0.5);
    automatic.predict(u, 0.5, odometry_noise);
    analytic.predict(u, 0.5, odometry_noise);
    for (int i = 0; i < 3; ++i) {
      // A fixed, made-up measurement error so that the updates do some work.
      const sylva::Vec<2> error(0.03 * std::sin(step + i), -0.02 * std::cos(2.0 * step + i));
      const sylva::Vec<2> z = RelativePosition{}.predict<double>(truth, landmarks[i]) + error;
      automatic.update(RelativePosition{}, i, z, sensor_noise);
      analytic.update(RelativePositionAnalytic{}, i, z, sensor_noise);
    }
  }
  CHECK((automatic.mean() - analytic.mean()).cwiseAbs().maxCoeff() < 1e-10);
  CHECK((automatic.covariance() - analytic.covariance()).cwiseAbs().maxCoeff() < 1e-10);
  CHECK((automatic.robotMean() - truth).head<2>().norm() < 0.2);
}

TEST_CASE("tutorial: the analytic Jacobians pass the numerical check") {
  // Ordinary and awkward geometry: heading near +-pi, landmark on top of the robot, far away.
  const sylva::Vec<3> robots[] = {
      {1.0, -2.0, 2.5}, {0.0, 0.0, sylva::kPi}, {0.0, 0.0, -sylva::kPi + 1e-9}, {1e3, -1e3, 0.1}};
  const sylva::Vec<2> landmarks[] = {{-3.0, 4.0}, {0.0, 0.0}, {1e-7, -1e-7}, {-1e3, 1e3}};
  for (const sylva::Vec<3>& robot : robots) {
    for (const sylva::Vec<2>& landmark : landmarks) {
      // [tutorial-check begin]
      const auto report =
          sylva::testing::checkMeasurementJacobians(RelativePositionAnalytic{}, robot, landmark);
      INFO(report.message());  // names the worst entry, e.g. "J_z_x(0, 2): analytic ..."
      CHECK(report.ok);

      const sylva::Vec<2> z = RelativePosition{}.predict<double>(robot, landmark);
      const auto inverse_report =
          sylva::testing::checkInverseJacobians(InverseRelativePosition{}, robot, z);
      INFO(inverse_report.message());
      CHECK(inverse_report.ok);
      // [tutorial-check end]
    }
  }
}

TEST_CASE("tutorial: the Jacobian check catches a wrong sign") {
  const auto report = sylva::testing::checkMeasurementJacobians(
      RelativePositionWrongSign{}, sylva::Vec<3>(1.0, -2.0, 2.5), sylva::Vec<2>(-3.0, 4.0));
  INFO(report.message());
  CHECK_FALSE(report.ok);
  CHECK(report.block == "J_z_x");
  CHECK(report.row == 0);
  CHECK(report.col == 2);
}

TEST_CASE("tutorial: the inverse model inverts the model") {
  const sylva::Vec<3> robot(2.0, -1.0, -2.2);
  const sylva::Vec<2> landmark(-4.0, 0.5);
  const sylva::Vec<2> z = RelativePosition{}.predict<double>(robot, landmark);
  CHECK((InverseRelativePosition{}(robot, z) - landmark).norm() < 1e-12);
}

TEST_CASE("tutorial: a residual keeps a bearing innovation small across +-pi") {
  // The landmark sits just left of straight behind the robot: predicted bearing +3.13 rad.
  Filter ekf(sylva::Vec<3>::Zero(), sylva::Mat<3, 3>::Identity() * 1e-4);
  const auto range_bearing_noise = sylva::Gaussian<2>::sigmas({0.05, 0.01});
  ekf.add(4, sylva::InverseRangeBearing{}, sylva::Vec<2>(5.0, 3.1316), range_bearing_noise);
  // A measurement just right of straight behind: -3.13 rad. Without the residual the
  // innovation would be about -6.26 rad.
  const auto innovation = ekf.update(
      Bearing{}, 4, sylva::Vec<1>(-3.1316), sylva::Gaussian<1>::sigmas(sylva::Vec<1>(0.01)));
  CHECK(std::abs(innovation.nu[0]) < 0.05);
  CHECK(std::abs(innovation.nu[0] - (2.0 * sylva::kPi - 2.0 * 3.1316)) < 1e-3);
  CHECK(ekf.landmarkMean<sylva::Point2>(4).norm() > 4.9);
  CHECK(ekf.landmarkMean<sylva::Point2>(4).norm() < 5.1);
}

TEST_CASE("tutorial: your own robot with an extra state uses the Pose2D models through its pose view") {
  const auto sensor_noise = sylva::Gaussian<2>::sigmas({0.05, 0.05});
  // [tutorial-robot-use begin]
  // Known start, an unknown gyro bias of about +-0.02 rad/s.
  const sylva::Vec<4> x0 = sylva::Vec<4>::Zero();
  const sylva::Mat<4, 4> P0 = sylva::Vec<4>(0.0, 0.0, 0.0, 0.02 * 0.02).asDiagonal();
  sylva::Ekf<GyroBiasUnicycle, sylva::Point2> ekf(x0, P0);
  const auto motion_noise = sylva::Gaussian<3>::sigmas({0.1, 0.01, 1e-4});  // [m/s, rad/s, rad/s^2]

  // The models of Steps 1 and 2, written for Pose2D, serve this robot as they are: the filter
  // evaluates them at pose(x) and chains J_z_x = J_z_pose J_pose_x.
  ekf.add(1, InverseRelativePosition{}, sylva::Vec<2>(3.0, 1.0), sensor_noise);
  ekf.predict(sylva::Vec<2>(1.0, 0.2), 1.0, motion_noise);
  ekf.update(RelativePosition{}, 1, sylva::Vec<2>(2.144, 0.484), sensor_noise);
  const double bias = ekf.robotMean()[3];  // the estimated gyro bias, rad/s
  // [tutorial-robot-use end]
  CHECK(std::isfinite(bias));

  // The chained Jacobian: the pose columns are the model's own, the bias column is zero.
  const auto lin = ekf.linearize(RelativePositionAnalytic{}, 1);
  sylva::Mat<2, 3> J_z_pose;
  RelativePositionAnalytic{}(sylva::Vec<3>(ekf.robotMean().head<3>()), ekf.landmarkMean<sylva::Point2>(1), J_z_pose);
  CHECK((lin.J_z_x.leftCols<3>() - J_z_pose).cwiseAbs().maxCoeff() < 1e-12);
  CHECK(lin.J_z_x.col(3).isZero(0.0));
}

TEST_CASE("tutorial: the robot's Jacobians pass the numerical check") {
  const sylva::Vec<4> states[] = {{1.0, -2.0, 0.4, 0.01}, {0.0, 0.0, sylva::kPi - 1e-9, -0.02}, {5.0, 3.0, -2.0, 0.0}};
  const sylva::Vec<2> controls[] = {{1.0, 0.2}, {0.0, 0.0}, {-0.5, 1.5}};
  for (const sylva::Vec<4>& x : states) {
    for (const sylva::Vec<2>& u : controls) {
      for (const double dt : {0.1, 1.0}) {
        const auto report = sylva::testing::checkMotionJacobians(GyroBiasUnicycle{}, x, u, dt);
        INFO(report.message());
        CHECK(report.ok);
      }
    }
  }
}

TEST_CASE("tutorial: the filter learns the gyro bias from the landmarks") {
  // A deterministic run: a loop past four landmarks, a true bias of 0.015 rad/s, made-up
  // measurement errors well inside the sensor noise.
  const auto sensor_noise = sylva::Gaussian<2>::sigmas({0.05, 0.05});
  const auto motion_noise = sylva::Gaussian<3>::sigmas({0.05, 0.01, 1e-4});
  const double true_bias = 0.015;
  const double prior_sigma = 0.02;
  sylva::Vec<4> truth(0.0, 0.0, 0.0, true_bias);
  sylva::Ekf<GyroBiasUnicycle, sylva::Point2> ekf(
      sylva::Vec<4>::Zero(), sylva::Mat<4, 4>(sylva::Vec<4>(0.0, 0.0, 0.0, prior_sigma * prior_sigma).asDiagonal()));
  const sylva::Vec<2> landmarks[] = {{4.0, 2.0}, {6.0, 8.0}, {-1.0, 7.0}, {-3.0, 1.0}};
  const auto seen = [&](int step, int i) {
    const sylva::Vec<2> error(0.02 * std::sin(3.0 * step + i), -0.02 * std::cos(5.0 * step + 2 * i));
    return sylva::Vec<2>(RelativePosition{}.predict<double>(sylva::Vec<3>(truth.head<3>()), landmarks[i]) + error);
  };
  for (int i = 0; i < 4; ++i) ekf.add(i, InverseRelativePosition{}, seen(0, i), sensor_noise);
  for (int step = 1; step <= 200; ++step) {
    const sylva::Vec<2> command(0.5, 0.15);                       // what the robot is told
    const sylva::Vec<2> gyro(command[0], command[1] + true_bias);  // what its sensors read
    truth = GyroBiasUnicycle{}(truth, gyro, 0.2);
    ekf.predict(gyro, 0.2, motion_noise);
    for (int i = 0; i < 4; ++i) ekf.update(RelativePosition{}, i, seen(step, i), sensor_noise);
  }
  const double sigma = std::sqrt(ekf.robotCovariance()(3, 3));
  INFO("bias " << ekf.robotMean()[3] << " +- " << sigma << ", true " << true_bias);
  CHECK(std::abs(ekf.robotMean()[3] - true_bias) < 3.0 * sigma);
  CHECK(sigma < 0.25 * prior_sigma);
}

TEST_CASE("tutorial: a model reports degenerate geometry and the filter stays unchanged") {
  Filter ekf(sylva::Vec<3>::Zero(), sylva::Mat<3, 3>::Identity() * 1e-4);
  ekf.add(2,
          InverseRelativePosition{},
          sylva::Vec<2>(0.0, 0.0),
          sylva::Gaussian<2>::sigmas({0.1, 0.1}));
  const Eigen::VectorXd mean = ekf.mean();
  const Eigen::MatrixXd covariance = ekf.covariance();
  try {
    ekf.update(Bearing{}, 2, sylva::Vec<1>(0.3), sylva::Gaussian<1>::sigmas(sylva::Vec<1>(0.01)));
    FAIL("a bearing to a landmark on top of the robot must throw");
  } catch (const sylva::Error& e) {
    CHECK(e.code() == sylva::ErrorCode::kDegenerateGeometry);
    CHECK(std::string(e.what()).find("Bearing") != std::string::npos);
  }
  CHECK(ekf.mean() == mean);
  CHECK(ekf.covariance() == covariance);
}

TEST_CASE("tutorial page quotes the tested code verbatim") {
  const std::string page = sylva_docs::fileText(sylva_docs::repositoryRoot() +
                                                "/docs/tutorial_add_measurement_model.md");
  REQUIRE(!page.empty());
  for (const char* region : {"tutorial-model",
                             "tutorial-inverse",
                             "tutorial-use",
                             "tutorial-analytic",
                             "tutorial-check",
                             "tutorial-residual",
                             "tutorial-robot",
                             "tutorial-robot-use"}) {
    const std::string code = sylva_docs::markedRegion(__FILE__, region);
    INFO("region " << region);
    REQUIRE(code.size() > 100);
    CHECK(page.find(code) != std::string::npos);
  }
}
