// LaserCameraCalibration: the least-squares polynomial recovers a known curve, evaluates
// with its derivative, and refuses bad degrees, too few or degenerate pairs, NaN.

#include <cmath>
#include <limits>
#include <vector>

#include <sylva/core/angles.hpp>
#include <sylva/laser_camera/calibration.hpp>
#include <sylva/sim/random.hpp>

#include "error_helpers.hpp"
#include "sylva_catch.hpp"

namespace unity_measurements_laser_camera_calibration {

using namespace sylva;
using sylva_test::throwsCode;

double trueError(double t) { return 0.02 - 0.05 * t + 0.3 * t * t * t; }

std::vector<CalibrationPair> pairsOf(int n, double noise, std::uint64_t seed) {
  sim::Rng rng(seed);
  std::vector<CalibrationPair> pairs;
  for (int i = 0; i < n; ++i) {
    const double c = -0.5 + 1.0 * i / (n - 1);
    pairs.push_back({c, c + trueError(c) + (noise > 0.0 ? noise * rng.normal() : 0.0)});
  }
  return pairs;
}

TEST_CASE("LaserCameraCalibration fit recovers a known cubic exactly from noiseless pairs",
          "[measurements][laser_camera]") {
  const auto cal = LaserCameraCalibration::fit(pairsOf(12, 0.0, 1), 3);
  REQUIRE(cal.degree() == 3);
  CHECK(cal.coefficients()[0] == Approx(0.02).margin(1e-12));
  CHECK(cal.coefficients()[1] == Approx(-0.05).margin(1e-12));
  CHECK(cal.coefficients()[2] == Approx(0.0).margin(1e-12));
  CHECK(cal.coefficients()[3] == Approx(0.3).margin(1e-12));
  CHECK(cal.residualRms() < 1e-13);
  for (double t : {-0.4, -0.1, 0.0, 0.25, 0.5}) {
    CHECK(cal.error(t) == Approx(trueError(t)).margin(1e-12));
    CHECK(cal.toLaser(t) == Approx(t + trueError(t)).margin(1e-12));
    CHECK(cal.toLaserDerivative(t) == Approx(1.0 - 0.05 + 0.9 * t * t).margin(1e-12));
    const double h = 1e-6;
    CHECK(cal.errorDerivative(t) == Approx((cal.error(t + h) - cal.error(t - h)) / (2 * h)).margin(1e-8));
  }
}

TEST_CASE("LaserCameraCalibration fit from noisy pairs stays within the noise and reports it",
          "[measurements][laser_camera]") {
  const double noise = 0.2 * kPi / 180.0;
  const auto cal = LaserCameraCalibration::fit(pairsOf(200, noise, 7), 3);
  CHECK(cal.residualRms() == Approx(noise).epsilon(0.15));
  for (double t = -0.5; t <= 0.5; t += 0.05) CHECK(std::abs(cal.error(t) - trueError(t)) < noise);
  // A higher degree than needed still fits (the extra terms come out small).
  const auto cal5 = LaserCameraCalibration::fit(pairsOf(200, noise, 7), 5);
  for (double t = -0.45; t <= 0.45; t += 0.05) CHECK(std::abs(cal5.error(t) - trueError(t)) < noise);
}

TEST_CASE("LaserCameraCalibration default is the identity mapping", "[measurements][laser_camera]") {
  const LaserCameraCalibration cal;
  CHECK(cal.degree() == 0);
  CHECK(cal.toLaser(0.3) == 0.3);
  CHECK(cal.toLaserDerivative(0.3) == 1.0);
}

TEST_CASE("LaserCameraCalibration refuses bad degrees, too few or degenerate pairs and NaN",
          "[measurements][laser_camera]") {
  const auto pairs = pairsOf(5, 0.0, 1);
  CHECK(throwsCode([&] { LaserCameraCalibration::fit(pairs, -1); }, ErrorCode::kInvalidArgument));
  CHECK(throwsCode([&] { LaserCameraCalibration::fit(pairsOf(20, 0.0, 1), LaserCameraCalibration::kMaxDegree + 1); },
                   ErrorCode::kInvalidArgument));
  CHECK(throwsCode([&] { LaserCameraCalibration::fit(pairs, 5); }, ErrorCode::kInvalidArgument));
  CHECK(throwsCode([&] { LaserCameraCalibration::fit({}, 0); }, ErrorCode::kInvalidArgument));
  // Ten pairs at only two distinct angles cannot fix a cubic.
  std::vector<CalibrationPair> two_angles;
  for (int i = 0; i < 10; ++i) two_angles.push_back({i % 2 ? 0.1 : -0.1, 0.0});
  CHECK(throwsCode([&] { LaserCameraCalibration::fit(two_angles, 3); }, ErrorCode::kDegenerateGeometry));
  auto bad = pairs;
  bad[2].laser_rad = std::numeric_limits<double>::quiet_NaN();
  CHECK(throwsCode([&] { LaserCameraCalibration::fit(bad, 2); }, ErrorCode::kNonFinite));
  CHECK(throwsCode([&] { LaserCameraCalibration(Eigen::VectorXd(0)); }, ErrorCode::kInvalidArgument));
  Eigen::VectorXd nan_coefficients(2);
  nan_coefficients << 1.0, std::numeric_limits<double>::infinity();
  CHECK(throwsCode([&] { LaserCameraCalibration{nan_coefficients}; }, ErrorCode::kNonFinite));
  try {
    LaserCameraCalibration::fit(pairs, 5);
  } catch (const Error& e) {
    CHECK(std::string(e.what()).find("at least 6 calibration pairs") != std::string::npos);
  }
}

}  // namespace unity_measurements_laser_camera_calibration
