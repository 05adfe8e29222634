// The simulated camera: eq. 5.3 against hand computations, visibility, the goal pose that
// sees the reference, pixel noise.
#include "sylva_catch.hpp"

#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "error_helpers.hpp"
#include "parking/station_camera.hpp"

namespace unity_parking_station_camera {

using ::parking::CameraParams;
using ::parking::Pose;
using ::parking::StationCamera;
using sylva::ErrorCode;
using sylva_test::throwsCode;

constexpr double kHalfPi = 1.57079632679489661923;

/// Eq. 5.3 written out for one feature: gamma is the bearing measured clockwise.
double handProjection(const CameraParams& c, const Pose& pose, double feature_x) {
  const double bearing_ccw = std::atan2(0.0 - pose[1], feature_x - pose[0]) - pose[2];
  const double gamma = -bearing_ccw;
  return c.focal_px * std::tan(gamma) + 0.5 * c.image_width_px;
}

}  // namespace unity_parking_station_camera

using namespace unity_parking_station_camera;

TEST_CASE("station camera: facing P2 on the axis, P2 is at the centre, P1 and P3 symmetric",
          "[parking]") {
  const StationCamera cam;
  const CameraParams& c = cam.params();
  const ::parking::StationView v = cam.view(Pose(0.0, -1.0, kHalfPi));
  REQUIRE(v.allVisible());
  const double half = c.focal_px * c.spacing_m / 1.0;  // f tan(beta), tan(beta) = d / r
  CHECK(v.u[1] == Approx(0.5 * c.image_width_px));
  CHECK(v.u[0] == Approx(0.5 * c.image_width_px - half));
  CHECK(v.u[2] == Approx(0.5 * c.image_width_px + half));
}

TEST_CASE("station camera: eq. 5.3 matches a hand computation from an oblique pose", "[parking]") {
  const StationCamera cam;
  const Pose pose(0.23, -0.81, 1.75);
  const ::parking::StationView v = cam.view(pose);
  REQUIRE(v.allVisible());
  for (int i = 0; i < 3; ++i)
    CHECK(v.u[static_cast<std::size_t>(i)] ==
          Approx(handProjection(cam.params(), pose, cam.feature(i).x())).epsilon(1e-12));
}

TEST_CASE("station camera: turning left (counter-clockwise) moves every feature right",
          "[parking]") {
  const StationCamera cam;
  const ::parking::StationView a = cam.view(Pose(0.1, -0.9, kHalfPi));
  const ::parking::StationView b = cam.view(Pose(0.1, -0.9, kHalfPi + 0.05));
  for (std::size_t i = 0; i < 3; ++i) CHECK(b.u[i] > a.u[i]);
  // The half of the station nearer the robot looks wider: on P3's side, f2 > f1.
  const ::parking::StationView side = cam.view(Pose(0.4, -0.8, std::atan2(0.8, -0.4)));
  CHECK(side.u[2] - side.u[1] > side.u[1] - side.u[0]);
}

TEST_CASE("station camera: features behind, outside the image or seen from behind are hidden",
          "[parking]") {
  const StationCamera cam;
  CHECK_FALSE(cam.view(Pose(0.0, -1.0, -kHalfPi)).visible[1]);  // facing away
  // Turned 31.5 deg left: P2 and P3 fall beyond the right image edge, P1 is still seen.
  const ::parking::StationView edge = cam.view(Pose(0.0, -1.0, kHalfPi + 0.55));
  CHECK(edge.visible[0]);
  CHECK_FALSE(edge.visible[1]);
  CHECK_FALSE(edge.visible[2]);
  CHECK_FALSE(cam.view(Pose(0.0, 1.0, -kHalfPi)).allVisible());  // behind the station
  sylva::sim::Rng rng(3);
  CHECK(cam.observe(Pose(0.0, -1.0, -kHalfPi), rng).empty());
}

TEST_CASE("station camera: the goal pose sees the reference exactly", "[parking]") {
  const StationCamera cam;
  const std::array<double, 3> reference{478.0, 695.0, 910.0};
  const Pose goal = cam.goalPose(reference);
  const ::parking::StationView v = cam.view(goal);
  for (std::size_t i = 0; i < 3; ++i) CHECK(v.u[i] == Approx(reference[i]).margin(1e-6));
  // Table 5.2's reference is slightly lopsided (f1^r = 217 > f2^r = 215, u2^r one pixel left
  // of centre): the goal lies 1.6 cm on P1's side, 0.61 m away, 1.5 deg off straight ahead.
  CHECK(goal[0] == Approx(-0.0157).margin(5e-4));
  CHECK(goal[1] == Approx(-0.608).margin(1e-3));
  CHECK(goal[2] == Approx(kHalfPi - 1.52 * 3.14159265358979 / 180).margin(1e-3));
  // A symmetric reference centred in the image puts the goal on the axis at r = 2 f d / A^r.
  const Pose on_axis = cam.goalPose({480.0, 696.0, 912.0});
  CHECK(on_axis[0] == Approx(0.0).margin(1e-9));
  CHECK(on_axis[2] == Approx(kHalfPi).margin(1e-9));
  CHECK(on_axis[1] == Approx(-2.0 * 1240.0 * 0.106 / 432.0));
}

TEST_CASE("station camera: a reference no pose can see is refused", "[parking]") {
  const StationCamera cam;
  CHECK(throwsCode([&] { cam.goalPose({100.0, 101.0, 1300.0}); }, ErrorCode::kDegenerateGeometry));
}

TEST_CASE("station camera: measured positions carry Gaussian pixel noise", "[parking]") {
  CameraParams c;
  c.sigma_px = 0.0;
  const Pose pose(0.05, -0.9, 1.6);
  sylva::sim::Rng rng(11);
  const ::parking::StationView truth = StationCamera(c).view(pose);
  const std::vector<double> exact = StationCamera(c).observe(pose, rng);
  REQUIRE(exact.size() == 3);
  for (std::size_t i = 0; i < 3; ++i) CHECK(exact[i] == truth.u[i]);
  c.sigma_px = 0.5;
  const StationCamera noisy(c);
  double sum = 0.0, sum2 = 0.0;
  const int n = 4000;
  for (int k = 0; k < n; ++k) {
    const double e = noisy.observe(pose, rng)[1] - truth.u[1];
    sum += e;
    sum2 += e * e;
  }
  CHECK(sum / n == Approx(0.0).margin(0.03));
  CHECK(std::sqrt(sum2 / n) == Approx(0.5).epsilon(0.05));
}

TEST_CASE("station camera: nonsense camera parameters are refused", "[parking]") {
  CameraParams c;
  c.focal_px = std::numeric_limits<double>::quiet_NaN();
  CHECK(throwsCode([&] { StationCamera cam(c); }, ErrorCode::kNonFinite));
  c = CameraParams{};
  c.sigma_px = -0.1;
  CHECK(throwsCode([&] { StationCamera cam(c); }, ErrorCode::kInvalidArgument));
  c = CameraParams{};
  c.frame_rate_hz = 0.0;
  CHECK(throwsCode([&] { StationCamera cam(c); }, ErrorCode::kInvalidArgument));
  c = CameraParams{};
  c.spacing_m = -0.1;
  CHECK(throwsCode([&] { StationCamera cam(c); }, ErrorCode::kInvalidArgument));
}
