// sylva::laser::extractCornerFeatures (the laser-only landmarks of laser_camera_slam) on
// synthetic scans: one L corner, a flat wall, an occluding edge, noise, and bad input.

#include "sylva_catch.hpp"

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <sylva/laser/corner_features.hpp>
#include <sylva/sim/laser_scanner_2d.hpp>

#include "error_helpers.hpp"

namespace unity_laser_corner_features {

using sylva::Vec;
using sylva::laser::CornerOptions;
using sylva::laser::extractCornerFeatures;

TEST_CASE("extractCornerFeatures finds the corner of two walls and nothing on a flat wall",
          "[laser]") {
  sylva::sim::LaserScanner2DOptions o;
  o.sigma_range_m = 0.0;
  const sylva::sim::LaserScanner2D scanner(o);
  const auto g = scanner.geometry();
  sylva::sim::Rng rng(1);
  {
    sylva::sim::LaserScene2D scene;
    scene.addPolyline({Vec<2>(3.0, -4.0), Vec<2>(3.0, 1.0), Vec<2>(-2.0, 1.0)},
                      false,
                      1);  // concave corner at (3, 1)
    const auto corners =
        extractCornerFeatures(scanner.scan(Vec<3>::Zero(), scene, rng).ranges_m, g);
    REQUIRE(corners.size() == 1);
    CHECK((corners[0].point - Vec<2>(3.0, 1.0)).norm() < 0.01);
    CHECK(corners[0].z[0] == Approx(std::sqrt(10.0)).margin(0.01));
  }
  {
    sylva::sim::LaserScene2D scene;
    scene.addSegment(Vec<2>(2.0, -6.0), Vec<2>(2.0, 6.0), 1);
    CHECK(extractCornerFeatures(scanner.scan(Vec<3>::Zero(), scene, rng).ranges_m, g).empty());
  }
  {
    // A V pointing away (a corner at (3, 0), both faces seen) and a separate wall whose
    // ends are occluding edges, not corners.
    sylva::sim::LaserScene2D scene;
    scene.addPolyline({Vec<2>(2.0, -1.0), Vec<2>(3.0, 0.0), Vec<2>(2.0, 1.0)}, false, 1);
    scene.addSegment(Vec<2>(5.0, 2.0), Vec<2>(5.0, 5.0), 2);
    const auto corners =
        extractCornerFeatures(scanner.scan(Vec<3>::Zero(), scene, rng).ranges_m, g);
    REQUIRE(corners.size() == 1);
    CHECK((corners[0].point - Vec<2>(3.0, 0.0)).norm() < 0.01);
  }
}

TEST_CASE("extractCornerFeatures is accurate to about a centimetre with 1 cm range noise",
          "[laser]") {
  const sylva::sim::LaserScanner2D scanner;  // 1 cm
  const auto g = scanner.geometry();
  sylva::sim::LaserScene2D scene;
  scene.addPolyline({Vec<2>(4.0, -4.0), Vec<2>(4.0, 1.5), Vec<2>(-2.0, 1.5)}, false, 1);
  sylva::sim::Rng rng(3);
  double se = 0.0;
  int found = 0;
  for (int i = 0; i < 50; ++i) {
    const auto corners =
        extractCornerFeatures(scanner.scan(Vec<3>::Zero(), scene, rng).ranges_m, g);
    for (const auto& c : corners) {
      se += (c.point - Vec<2>(4.0, 1.5)).squaredNorm();
      ++found;
    }
  }
  CHECK(found == 50);
  CHECK(std::sqrt(se / std::max(1, found)) < 0.03);
}

TEST_CASE("extractCornerFeatures skips invalid readings", "[laser]") {
  const sylva::sim::LaserScanner2D scanner;
  const auto g = scanner.geometry();
  std::vector<double> ranges(static_cast<std::size_t>(g.beams),
                             std::numeric_limits<double>::quiet_NaN());
  CHECK(extractCornerFeatures(ranges, g).empty());
  ranges.assign(ranges.size(), std::numeric_limits<double>::infinity());
  CHECK(extractCornerFeatures(ranges, g).empty());
}

TEST_CASE("extractCornerFeatures refuses a scan of the wrong length and options out of range",
          "[laser]") {
  const sylva::sim::LaserScanner2D scanner;
  const auto g = scanner.geometry();
  const std::vector<double> ranges(static_cast<std::size_t>(g.beams), 3.0);
  const auto invalid = sylva::ErrorCode::kInvalidArgument;
  CHECK(sylva_test::throwsCode(
      [&] { extractCornerFeatures(std::vector<double>(ranges.begin() + 1, ranges.end()), g); },
      invalid));
  CHECK(sylva_test::throwsCode([&] { extractCornerFeatures(std::vector<double>{}, g); }, invalid));
  const auto refuses = [&](auto edit) {
    CornerOptions o;
    edit(o);
    return sylva_test::throwsCode([&] { extractCornerFeatures(ranges, g, o); }, invalid);
  };
  CHECK(refuses([](CornerOptions& o) { o.gap_m = o.gap_per_m = 0.0; }));
  CHECK(refuses([](CornerOptions& o) { o.gap_m = std::numeric_limits<double>::quiet_NaN(); }));
  CHECK(refuses([](CornerOptions& o) { o.split_m = 0.0; }));
  CHECK(refuses([](CornerOptions& o) { o.min_points = 1; }));
  CHECK(refuses([](CornerOptions& o) { o.min_length_m = -1.0; }));
  CHECK(refuses([](CornerOptions& o) { o.min_angle_rad = 0.5 * sylva::kPi; }));
  CHECK(
      refuses([](CornerOptions& o) { o.max_offset_m = std::numeric_limits<double>::infinity(); }));
  CHECK(refuses([](CornerOptions& o) { o.sigma_m = 0.0; }));
  CHECK_NOTHROW(extractCornerFeatures(ranges, g, CornerOptions{}));
  std::string message;
  try {
    extractCornerFeatures(std::vector<double>(3, 1.0), g);
  } catch (const sylva::Error& e) {
    message = e.what();
  }
  CHECK(message.find("3 readings for") != std::string::npos);
}

}  // namespace unity_laser_corner_features
