#include "sylva_catch.hpp"

#include "error_helpers.hpp"

#include <cmath>

#include "sylva/sim/loop_path_2d.hpp"

using sylva::ErrorCode;
using sylva::kPi;
using sylva::Vec;
using sylva::sim::LoopPath2D;

namespace {

using sylva_test::throwsCode;

}  // namespace

TEST_CASE("LoopPath2D: perimeter of a rounded rectangle", "[sim][path]") {
  const LoopPath2D path(40.0, 20.0, 5.0);
  CHECK(std::abs(path.perimeter() - (2 * 30.0 + 2 * 10.0 + 2 * kPi * 5.0)) < 1e-12);
  const LoopPath2D by_perimeter = LoopPath2D::withPerimeter(120.0, 2.0, 8.0);
  CHECK(std::abs(by_perimeter.perimeter() - 120.0) < 1e-9);
  CHECK(std::abs(by_perimeter.length() - 2.0 * by_perimeter.width()) < 1e-9);
}

TEST_CASE("LoopPath2D: starts at the origin heading +x and closes after one lap", "[sim][path]") {
  const LoopPath2D path(40.0, 20.0, 5.0);
  CHECK(path.position(0.0).norm() < 1e-12);
  CHECK(path.heading(0.0) == 0.0);
  CHECK(path.position(path.perimeter()).norm() < 1e-9);
  CHECK(std::abs(path.heading(path.perimeter()) - 2.0 * kPi) < 1e-12);
  CHECK(std::abs(path.heading(2.5 * path.perimeter()) - path.heading(0.5 * path.perimeter()) -
                 4.0 * kPi) < 1e-9);
  CHECK((path.position(2.5 * path.perimeter()) - path.position(0.5 * path.perimeter())).norm() <
        1e-9);
}

TEST_CASE("LoopPath2D: continuous, unit speed, inside its bounding box", "[sim][path]") {
  const LoopPath2D path(40.0, 20.0, 5.0);
  const double ds = 1e-3;
  double x_min = 1e9, x_max = -1e9, y_min = 1e9, y_max = -1e9;
  for (double s = 0.0; s < path.perimeter(); s += ds) {
    const Vec<2> p = path.position(s);
    const Vec<2> q = path.position(s + ds);
    // A chord of length ds along a curve of radius >= 5 m is ds up to 1e-9 relative.
    REQUIRE(std::abs((q - p).norm() - ds) < 1e-9);
    // The direction of motion is the heading.
    const Vec<2> tangent = (q - p) / ds;
    const double h = path.heading(s + 0.5 * ds);
    REQUIRE((tangent - Vec<2>(std::cos(h), std::sin(h))).norm() < 1e-6);
    x_min = std::min(x_min, p.x());
    x_max = std::max(x_max, p.x());
    y_min = std::min(y_min, p.y());
    y_max = std::max(y_max, p.y());
  }
  CHECK(std::abs(x_min + 20.0) < 1e-6);
  CHECK(std::abs(x_max - 20.0) < 1e-6);
  CHECK(std::abs(y_min) < 1e-6);
  CHECK(std::abs(y_max - 20.0) < 1e-6);
}

TEST_CASE("LoopPath2D: a circle is a rounded rectangle without straight sides", "[sim][path]") {
  const LoopPath2D circle(10.0, 10.0, 5.0);
  CHECK(std::abs(circle.perimeter() - 10.0 * kPi) < 1e-12);
  for (double s = 0.0; s < circle.perimeter(); s += 0.1)
    REQUIRE(std::abs((circle.position(s) - Vec<2>(0.0, 5.0)).norm() - 5.0) < 1e-9);
  CHECK(std::abs(circle.distanceTo(Vec<2>(0.0, 5.0)) - 5.0) < 1e-12);
  CHECK(std::abs(circle.distanceTo(Vec<2>(0.0, 12.0)) - 2.0) < 1e-12);
}

TEST_CASE("LoopPath2D: distanceTo", "[sim][path]") {
  const LoopPath2D path(40.0, 20.0, 5.0);
  for (double s = 0.0; s < path.perimeter(); s += 0.37) {
    REQUIRE(path.distanceTo(path.position(s)) < 1e-9);
    // Off the path along the normal, on either side (closer than any other part of the path).
    REQUIRE(std::abs(path.distanceTo(path.position(s) + 2.0 * path.leftNormal(s)) - 2.0) < 1e-9);
    REQUIRE(std::abs(path.distanceTo(path.position(s) - 3.0 * path.leftNormal(s)) - 3.0) < 1e-9);
  }
  // Centre of the bottom-right corner circle: 5 m from the arc and both adjacent sides.
  CHECK(std::abs(path.distanceTo(Vec<2>(15.0, 5.0)) - 5.0) < 1e-12);
  // Inside the corner's quadrant: distance to the arc is r - |p - centre|.
  CHECK(std::abs(path.distanceTo(Vec<2>(18.0, 2.0)) - (5.0 - std::hypot(3.0, 3.0))) < 1e-12);
  // Outside the corner's quadrant the arc's closest point is an end point, but the straight
  // side is closer still.
  CHECK(std::abs(path.distanceTo(Vec<2>(10.0, 2.0)) - 2.0) < 1e-12);
  // Below the bottom side: straight distance.
  CHECK(std::abs(path.distanceTo(Vec<2>(3.0, -4.0)) - 4.0) < 1e-12);
  // Centre of the loop.
  CHECK(std::abs(path.distanceTo(Vec<2>(0.0, 10.0)) - 10.0) < 1e-12);
}

TEST_CASE("LoopPath2D: invalid arguments throw", "[sim][path]") {
  const double nan = std::nan("");
  CHECK(throwsCode([] { LoopPath2D(40.0, 20.0, 11.0); }, ErrorCode::kInvalidArgument));
  CHECK(throwsCode([] { LoopPath2D(40.0, 20.0, 0.0); }, ErrorCode::kInvalidArgument));
  CHECK(throwsCode([] { LoopPath2D(40.0, 20.0, -1.0); }, ErrorCode::kInvalidArgument));
  CHECK(throwsCode([&] { LoopPath2D(nan, 20.0, 5.0); }, ErrorCode::kInvalidArgument));
  CHECK(throwsCode([] { LoopPath2D::withPerimeter(30.0, 2.0, 8.0); }, ErrorCode::kInvalidArgument));
  CHECK(
      throwsCode([] { LoopPath2D::withPerimeter(120.0, 0.5, 8.0); }, ErrorCode::kInvalidArgument));
  CHECK(throwsCode([] { LoopPath2D::withPerimeter(-1.0, 2.0, 8.0); }, ErrorCode::kInvalidArgument));
  const LoopPath2D path(40.0, 20.0, 5.0);
  CHECK(throwsCode([&] { path.position(nan); }, ErrorCode::kNonFinite));
}
