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
  using Robot = sylva::Unicycle2D;  // the robot the sensor rides on
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
  using Robot = sylva::Unicycle2D;
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
  using Robot = sylva::Unicycle2D;
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
                             "tutorial-residual"}) {
    const std::string code = sylva_docs::markedRegion(__FILE__, region);
    INFO("region " << region);
    REQUIRE(code.size() > 100);
    CHECK(page.find(code) != std::string::npos);
  }
}
