// LaserCameraSensor: range and bearing of vertical lines on simulated scans; the covariance
// (eq. 3.5, propagated) against a Monte Carlo estimate; every rejection; bad input; scan
// edges and grazing incidence.

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <sylva/laser_camera/sensor.hpp>
#include <sylva/sim/random.hpp>

#include "error_helpers.hpp"
#include "sylva_catch.hpp"

namespace unity_measurements_laser_camera_sensor {

using namespace sylva;
using sylva_test::throwsCode;

constexpr double kDeg = kPi / 180.0;

/// Readings of a straight wall n . p = distance (normal at `normal` rad) for every beam;
/// beams that do not meet it read +infinity.
std::vector<double> wallScan(const LaserScanGeometry& g, double normal, double distance) {
  std::vector<double> r(static_cast<std::size_t>(g.beams));
  for (int k = 0; k < g.beams; ++k) {
    const double c = std::cos(g.beamAngle(k) - normal);
    r[static_cast<std::size_t>(k)] = c > 1e-9 ? distance / c : std::numeric_limits<double>::infinity();
    if (r[static_cast<std::size_t>(k)] > g.max_range_m) r[static_cast<std::size_t>(k)] = std::numeric_limits<double>::infinity();
  }
  return r;
}

/// A floor-to-ceiling line: it spans the whole image height.
VerticalLineDetection fullLine(double bearing) { return {bearing, -1.0, 1.0}; }

TEST_CASE("LaserCameraSensor measures a line on a flat wall exactly, at any resolution",
          "[measurements][laser_camera]") {
  for (double resolution : {0.25 * kDeg, 0.5 * kDeg, 1.0 * kDeg, 3.0 * kDeg}) {
    LaserScanGeometry g;
    g.angle_increment_rad = resolution;
    g.beams = static_cast<int>(std::floor(kPi / resolution + 1e-9)) + 1;
    g.max_range_m = 30.0;
    LaserCameraOptions o;
    o.max_jump_m = 2.0;
    const LaserCameraSensor sensor(g, {}, o);
    const auto scan = wallScan(g, 20.0 * kDeg, 3.0);
    for (double bearing : {-0.6, -0.123, 0.0, 0.2 + 0.3 * resolution, 0.7}) {
      INFO("resolution " << resolution / kDeg << " deg, bearing " << bearing);
      const auto m = sensor.measure(fullLine(bearing), scan);
      REQUIRE(m.ok());
      CHECK(m.z[0] == Approx(3.0 / std::cos(bearing - 20.0 * kDeg)).epsilon(1e-12));
      CHECK(m.z[1] == Approx(bearing).margin(1e-15));
    }
  }
}

TEST_CASE("LaserCameraSensor applies the calibration curve before reading the scan",
          "[measurements][laser_camera]") {
  Eigen::VectorXd c(4);
  c << 0.01, -0.02, 0.0, 0.2;  // e(t) = 0.01 - 0.02 t + 0.2 t^3
  const LaserCameraCalibration cal(c, 0.001);
  LaserScanGeometry g;
  const LaserCameraSensor sensor(g, cal);
  const auto scan = wallScan(g, 0.0, 2.0);
  const double tc = 0.3;
  const double tl = tc + 0.01 - 0.02 * tc + 0.2 * tc * tc * tc;
  const auto m = sensor.measure(fullLine(tc), scan);
  REQUIRE(m.ok());
  CHECK(m.z[1] == Approx(tl).margin(1e-15));
  CHECK(m.z[0] == Approx(2.0 / std::cos(tl)).epsilon(1e-12));
  // Bearing variance: (1 + e')^2 sigma^2 + residual^2.
  const double gain = 1.0 - 0.02 + 0.6 * tc * tc;
  const double sigma = sensor.options().sigma_bearing_rad;
  CHECK(m.covariance(1, 1) == Approx(gain * gain * sigma * sigma + 1e-6).epsilon(1e-12));
}

TEST_CASE("LaserCameraSensor covariance matches a Monte Carlo estimate", "[measurements][laser_camera]") {
  // Oblique wall (incidence 50 deg at the line) so that the range-bearing correlation matters.
  LaserScanGeometry g;
  LaserCameraOptions o;
  o.sigma_bearing_rad = 0.1 * kDeg;  // the bearing stays between the same two beams
  o.sigma_reading_m = 0.02;
  o.max_jump_m = 1.0;
  o.bend_fraction = 0.0;  // a flat wall: no model error
  const LaserCameraSensor sensor(g, {}, o);
  const double normal = -40.0 * kDeg;
  const double bearing = 10.0 * kDeg + 0.37 * g.angle_increment_rad;
  const auto truth_scan = wallScan(g, normal, 2.5);
  const auto nominal = sensor.measure(fullLine(bearing), truth_scan);
  REQUIRE(nominal.ok());
  CHECK(std::abs(nominal.covariance(0, 1)) > 0.1 * std::sqrt(nominal.covariance(0, 0) * nominal.covariance(1, 1)));

  sim::Rng rng(42);
  const int n = 40000;
  Vec<2> mean = Vec<2>::Zero();
  Mat<2, 2> second = Mat<2, 2>::Zero();
  auto scan = truth_scan;
  for (int s = 0; s < n; ++s) {
    for (std::size_t k = 0; k < scan.size(); ++k) scan[k] = truth_scan[k] + o.sigma_reading_m * rng.normal();
    const double b = bearing + o.sigma_bearing_rad * rng.normal();
    const auto m = sensor.measure(fullLine(b), scan);
    REQUIRE(m.ok());
    const Vec<2> e = m.z - Vec<2>(2.5 / std::cos(bearing - normal), bearing);
    mean += e;
    second += e * e.transpose();
  }
  mean /= n;
  const Mat<2, 2> cov = second / n - mean * mean.transpose();
  INFO("Monte Carlo\n" << cov << "\npropagated\n" << nominal.covariance);
  CHECK(cov(0, 0) == Approx(nominal.covariance(0, 0)).epsilon(0.05));
  CHECK(cov(1, 1) == Approx(nominal.covariance(1, 1)).epsilon(0.05));
  CHECK(cov(0, 1) == Approx(nominal.covariance(0, 1)).epsilon(0.06));
  CHECK(std::abs(mean[0]) < 0.01 * std::sqrt(cov(0, 0)) + 3.0 * std::sqrt(cov(0, 0) / n));
}

TEST_CASE("LaserCameraSensor covariance stays near a Monte Carlo estimate at 1 deg bearing noise",
          "[measurements][laser_camera]") {
  // The bearing error spans several beams: the chord-tilt term is capped (file comment);
  // the range variance is an approximation here, within 25 %.
  LaserScanGeometry g;
  LaserCameraOptions o;  // 1 deg, 1 cm
  o.max_jump_m = 0.3;    // at 50 deg incidence 4-sigma reading noise would reach 0.1 m
  o.bend_fraction = 0.0;
  const LaserCameraSensor sensor(g, {}, o);
  for (double normal : {0.0, -40.0 * kDeg}) {
    const double bearing = 10.0 * kDeg + 0.37 * g.angle_increment_rad;
    const auto truth_scan = wallScan(g, normal, 2.5);
    const auto nominal = sensor.measure(fullLine(bearing), truth_scan);
    REQUIRE(nominal.ok());
    sim::Rng rng(7);
    const int n = 20000;
    Mat<2, 2> second = Mat<2, 2>::Zero();
    auto scan = truth_scan;
    for (int s = 0; s < n; ++s) {
      for (std::size_t k = 0; k < scan.size(); ++k) scan[k] = truth_scan[k] + 0.01 * rng.normal();
      const auto m = sensor.measure(fullLine(bearing + kDeg * rng.normal()), scan);
      INFO(describe(m.status));
      REQUIRE(m.ok());
      const Vec<2> e = m.z - Vec<2>(2.5 / std::cos(bearing - normal), bearing);
      second += e * e.transpose();
    }
    const Mat<2, 2> cov = second / n;
    INFO("normal " << normal << "\nMonte Carlo\n" << cov << "\npropagated\n" << nominal.covariance);
    CHECK(cov(0, 0) == Approx(nominal.covariance(0, 0)).epsilon(0.25));
    CHECK(cov(1, 1) == Approx(nominal.covariance(1, 1)).epsilon(0.05));
  }
}

TEST_CASE("LaserCameraSensor covariance is the thesis' diagonal eq. 3.5 for a wall seen head-on",
          "[measurements][laser_camera]") {
  LaserScanGeometry g;
  LaserCameraOptions o;
  o.bend_fraction = 0.0;
  const LaserCameraSensor sensor(g, {}, o);
  const auto scan = wallScan(g, 0.0, 3.0);
  const auto m = sensor.measure(fullLine(0.25 * g.angle_increment_rad), scan);
  const LaserCameraSensor with_bend(g);  // default: + (0.3 r increment)^2
  const double bend = 0.3 * m.z[0] * g.angle_increment_rad;
  CHECK(with_bend.measure(fullLine(0.25 * g.angle_increment_rad), scan).covariance(0, 0) ==
        Approx(m.covariance(0, 0) + bend * bend).epsilon(1e-12));
  REQUIRE(m.ok());
  CHECK(std::abs(m.covariance(0, 1)) < 0.05 * std::sqrt(m.covariance(0, 0) * m.covariance(1, 1)));
  // Interpolating two readings: ((1-t)^2 + t^2) sigma_reading^2 to first order, plus the
  // chord-tilt term 2 sigma_reading^2 / delta^2 * delta^2 / 12 (1 deg > 0.5 deg: capped).
  const double t = 0.25;
  CHECK(m.covariance(0, 0) == Approx(((1 - t) * (1 - t) + t * t) * 1e-4 + 1e-4 / 6.0).epsilon(0.02));
}

TEST_CASE("LaserCameraSensor rejects every case with its reason", "[measurements][laser_camera]") {
  LaserScanGeometry g;  // 180 deg at 0.5 deg, 361 beams, 0.05 .. 8 m
  const LaserCameraSensor sensor(g);
  const auto wall = wallScan(g, 0.0, 3.0);
  const double b = 0.1 + 0.4 * g.angle_increment_rad;
  const int i = static_cast<int>(std::floor((b - g.angle_min_rad) / g.angle_increment_rad));
  auto at = [&](std::vector<double>& s, int k) -> double& { return s[static_cast<std::size_t>(k)]; };

  SECTION("outside the scan") {
    LaserScanGeometry narrow = g;
    narrow.angle_min_rad = -0.5;
    narrow.beams = 101;  // -0.5 .. -0.5 + 100 * 0.5 deg = 0.373 rad
    const LaserCameraSensor s(narrow);
    const auto m = s.measure(fullLine(0.4), wallScan(narrow, 0.0, 3.0));
    CHECK(m.status == LaserCameraStatus::kOutsideScan);
    CHECK(s.measure(fullLine(-0.51), wallScan(narrow, 0.0, 3.0)).status == LaserCameraStatus::kOutsideScan);
    // A calibration curve can push a bearing inside the image out of the scan.
    Eigen::VectorXd c(1);
    c << 0.2;
    const LaserCameraSensor shifted(narrow, LaserCameraCalibration(c));
    CHECK(shifted.measure(fullLine(0.2), wallScan(narrow, 0.0, 3.0)).status == LaserCameraStatus::kOutsideScan);
  }
  SECTION("invalid readings: NaN, no return, out of range") {
    for (double bad : {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(), 0.01, 9.0}) {
      auto s = wall;
      at(s, i + 1) = bad;
      const auto m = sensor.measure(fullLine(b), s);
      CHECK(m.status == LaserCameraStatus::kInvalidReading);
      CHECK(m.beam == i);
    }
  }
  SECTION("range discontinuity") {
    auto s = wall;
    for (int k = i + 1; k < g.beams; ++k) at(s, k) = 5.0;  // a door: the wall ends between the beams
    CHECK(sensor.measure(fullLine(b), s).status == LaserCameraStatus::kRangeDiscontinuity);
    CHECK(std::string(describe(LaserCameraStatus::kRangeDiscontinuity)).find("discontinuity") != std::string::npos);
  }
  SECTION("near side at a jump: the occluding edge is extrapolated along the nearer surface") {
    LaserCameraOptions o;
    o.near_side_at_jumps = true;
    const LaserCameraSensor near(g, {}, o);
    auto s = wall;
    for (int k = i + 1; k < g.beams; ++k) at(s, k) = 5.0;
    const auto m = near.measure(fullLine(b), s);
    REQUIRE(m.ok());
    CHECK(m.extrapolated);
    CHECK(m.z[0] == Approx(3.0 / std::cos(b)).epsilon(1e-12));
    // Nearer side not continuous either: rejected.
    at(s, i - 1) = 1.0;
    CHECK(near.measure(fullLine(b), s).status == LaserCameraStatus::kRangeDiscontinuity);
  }
  SECTION("grazing incidence") {
    // A wall whose normal is 86 deg from the line's bearing, 0.5 m away: neighbouring
    // readings differ by less than max_jump, but the beam almost slides along the wall.
    const double normal = b - 86.0 * kDeg;
    const auto s = wallScan(g, normal, 0.5 * std::cos(86.0 * kDeg));
    const auto m = sensor.measure(fullLine(b), s);
    CHECK(m.status == LaserCameraStatus::kGrazingIncidence);
    CHECK(m.incidence_rad == Approx(86.0 * kDeg).margin(1e-6));
  }
  SECTION("the line does not cross the laser plane") {
    // b = 0.19 m, wall at 3 m: the scan plane appears at y = 0.19 / (3 cos b') below the centre.
    const double y = 0.19 / (3.0 / std::cos(b) * std::cos(b));
    CHECK(sensor.measure({b, -0.5, y - 0.05}, wall).status == LaserCameraStatus::kMissesLaserPlane);  // poster above
    CHECK(sensor.measure({b, y + 0.05, 0.5}, wall).status == LaserCameraStatus::kMissesLaserPlane);   // below the plane
    CHECK(sensor.measure({b, y - 0.005, y + 0.005}, wall).ok());  // a short line through it
    CHECK(sensor.measure({b, -0.5, y - 0.005}, wall).ok());       // within the margin
  }
}

TEST_CASE("LaserCameraSensor handles the scan edges and exact beam angles", "[measurements][laser_camera]") {
  LaserScanGeometry g;
  g.max_range_m = 100.0;
  LaserCameraOptions o;
  o.max_jump_m = 5.0;
  o.max_incidence_rad = 0.5 * kPi;
  const LaserCameraSensor sensor(g, {}, o);
  const auto wall = wallScan(g, 0.0, 1.0);  // beams beyond ~89.4 deg read infinity
  // Exactly on a beam: the reading itself.
  const auto on_beam = sensor.measure(fullLine(g.beamAngle(200)), wall);
  REQUIRE(on_beam.ok());
  CHECK(on_beam.z[0] == Approx(wall[200]).epsilon(1e-12));
  // Near the first and the last beam (a camera bearing must stay below 90 deg).
  LaserScanGeometry narrow = g;
  narrow.angle_min_rad = -0.4;
  narrow.beams = 93;
  const LaserCameraSensor ns(narrow, {}, o);
  const auto nwall = wallScan(narrow, 0.0, 1.0);
  CHECK(ns.measure(fullLine(narrow.angle_min_rad), nwall).ok());
  CHECK(ns.measure(fullLine(narrow.angleMax()), nwall).ok());
  CHECK(ns.measure(fullLine(narrow.angleMax()), nwall).z[0] == Approx(1.0 / std::cos(narrow.angleMax())).epsilon(1e-12));
  CHECK(ns.measure(fullLine(narrow.angleMax() + 1e-6), nwall).status == LaserCameraStatus::kOutsideScan);
  // A scan beam that reads no return near the edge of the laser's view.
  CHECK(sensor.measure(fullLine(89.8 * kDeg), wall).status == LaserCameraStatus::kInvalidReading);
}

TEST_CASE("LaserCameraSensor refuses bad input and bad options", "[measurements][laser_camera]") {
  LaserScanGeometry g;
  const LaserCameraSensor sensor(g);
  const auto wall = wallScan(g, 0.0, 3.0);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  CHECK(throwsCode([&] { sensor.measure({nan, -1.0, 1.0}, wall); }, ErrorCode::kNonFinite));
  CHECK(throwsCode([&] { sensor.measure({0.1, nan, 1.0}, wall); }, ErrorCode::kNonFinite));
  CHECK(throwsCode([&] { sensor.measure({0.1, 0.5, -0.5}, wall); }, ErrorCode::kInvalidArgument));
  CHECK(throwsCode([&] { sensor.measure(fullLine(0.5 * kPi), wall); }, ErrorCode::kInvalidArgument));
  CHECK(throwsCode([&] { sensor.measure(fullLine(0.1), std::vector<double>(10, 1.0)); }, ErrorCode::kInvalidArgument));
  // Infinite extents are fine: the line spans the image.
  CHECK(sensor.measure({0.1, -std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()}, wall).ok());

  LaserScanGeometry bad = g;
  bad.angle_increment_rad = 0.0;
  CHECK(throwsCode([&] { LaserCameraSensor{bad}; }, ErrorCode::kInvalidArgument));
  bad = g;
  bad.beams = 1;
  CHECK(throwsCode([&] { LaserCameraSensor{bad}; }, ErrorCode::kInvalidArgument));
  bad = g;
  bad.max_range_m = 0.0;
  CHECK(throwsCode([&] { LaserCameraSensor{bad}; }, ErrorCode::kInvalidArgument));
  auto withOptions = [&](auto change) {
    LaserCameraOptions o;
    change(o);
    return throwsCode([&] { LaserCameraSensor(g, {}, o); }, ErrorCode::kInvalidArgument);
  };
  CHECK(withOptions([](LaserCameraOptions& o) { o.sigma_bearing_rad = 0.0; }));
  CHECK(withOptions([](LaserCameraOptions& o) { o.sigma_reading_m = std::numeric_limits<double>::quiet_NaN(); }));
  CHECK(withOptions([](LaserCameraOptions& o) { o.camera_above_laser_m = -0.1; }));
  CHECK(withOptions([](LaserCameraOptions& o) { o.max_jump_m = 0.0; }));
  CHECK(withOptions([](LaserCameraOptions& o) { o.max_incidence_rad = 2.0; }));
  CHECK(withOptions([](LaserCameraOptions& o) { o.plane_margin = -1.0; }));
  CHECK(withOptions([](LaserCameraOptions& o) { o.bend_fraction = -0.1; }));
}

}  // namespace unity_measurements_laser_camera_sensor
