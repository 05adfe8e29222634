// The laser_camera_slam corner extractor on synthetic scans: one L corner, a flat wall, an
// occluding edge, noise.

#include <cmath>
#include <limits>
#include <vector>

#include <sylva/sim/laser_scanner_2d.hpp>

#include "laser_camera_slam/corners.hpp"
#include "sylva_catch.hpp"

namespace unity_laser_camera_slam_corners {

using namespace laser_camera_slam;
using sylva::Vec;

TEST_CASE("extractCorners finds the corner of two walls and nothing on a flat wall", "[laser_camera_slam]") {
  sylva::sim::LaserScanner2DOptions o;
  o.sigma_range_m = 0.0;
  const sylva::sim::LaserScanner2D scanner(o);
  const auto g = scanner.geometry();
  sylva::sim::Rng rng(1);
  {
    sylva::sim::LaserScene2D scene;
    scene.addPolyline({Vec<2>(3.0, -4.0), Vec<2>(3.0, 1.0), Vec<2>(-2.0, 1.0)}, false, 1);  // concave corner at (3, 1)
    const auto corners = extractCorners(scanner.scan(Vec<3>::Zero(), scene, rng).ranges_m, g);
    REQUIRE(corners.size() == 1);
    CHECK((corners[0].point - Vec<2>(3.0, 1.0)).norm() < 0.01);
    CHECK(corners[0].z[0] == Approx(std::sqrt(10.0)).margin(0.01));
  }
  {
    sylva::sim::LaserScene2D scene;
    scene.addSegment(Vec<2>(2.0, -6.0), Vec<2>(2.0, 6.0), 1);
    CHECK(extractCorners(scanner.scan(Vec<3>::Zero(), scene, rng).ranges_m, g).empty());
  }
  {
    // A V pointing away (a corner at (3, 0), both faces seen) and a separate wall whose
    // ends are occluding edges, not corners.
    sylva::sim::LaserScene2D scene;
    scene.addPolyline({Vec<2>(2.0, -1.0), Vec<2>(3.0, 0.0), Vec<2>(2.0, 1.0)}, false, 1);
    scene.addSegment(Vec<2>(5.0, 2.0), Vec<2>(5.0, 5.0), 2);
    const auto corners = extractCorners(scanner.scan(Vec<3>::Zero(), scene, rng).ranges_m, g);
    REQUIRE(corners.size() == 1);
    CHECK((corners[0].point - Vec<2>(3.0, 0.0)).norm() < 0.01);
  }
}

TEST_CASE("extractCorners is accurate to about a centimetre with 1 cm range noise", "[laser_camera_slam]") {
  const sylva::sim::LaserScanner2D scanner;  // 1 cm
  const auto g = scanner.geometry();
  sylva::sim::LaserScene2D scene;
  scene.addPolyline({Vec<2>(4.0, -4.0), Vec<2>(4.0, 1.5), Vec<2>(-2.0, 1.5)}, false, 1);
  sylva::sim::Rng rng(3);
  double se = 0.0;
  int found = 0;
  for (int i = 0; i < 50; ++i) {
    const auto corners = extractCorners(scanner.scan(Vec<3>::Zero(), scene, rng).ranges_m, g);
    for (const auto& c : corners) {
      se += (c.point - Vec<2>(4.0, 1.5)).squaredNorm();
      ++found;
    }
  }
  CHECK(found == 50);
  CHECK(std::sqrt(se / std::max(1, found)) < 0.03);
}

TEST_CASE("extractCorners skips invalid readings", "[laser_camera_slam]") {
  const sylva::sim::LaserScanner2D scanner;
  const auto g = scanner.geometry();
  std::vector<double> ranges(static_cast<std::size_t>(g.beams), std::numeric_limits<double>::quiet_NaN());
  CHECK(extractCorners(ranges, g).empty());
  ranges.assign(ranges.size(), std::numeric_limits<double>::infinity());
  CHECK(extractCorners(ranges, g).empty());
}

}  // namespace unity_laser_camera_slam_corners
