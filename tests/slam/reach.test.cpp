// landmarksInReach: the candidates of association, from the range-bearing sensor's own
// prediction (range from the sensor position, bearing relative to the heading).

#include "sylva_catch.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <sylva/filter/ekf.hpp>
#include <sylva/measurements/range_bearing_diameter.hpp>
#include <sylva/motion/unicycle_2d.hpp>
#include <sylva/slam/reach.hpp>

#include "error_helpers.hpp"

// Own namespace: the tests of a folder are compiled as one unity translation unit.
namespace unity_slam_reach {

using namespace sylva;
using sylva_test::throwsCode;

using Filter = Ekf<Unicycle2D, Point2, TreeXYR>;

// A robot at (1, 2) heading +90 degrees, points added at exact (range, bearing) readings from
// the robot's origin: ids 1..6 with ranges 2, 5, 9, 5, 5, 5 m and bearings 0, 30, 0, 80, 100,
// -179 degrees; one tree (id 7) at range 3 m, bearing 0.
Filter makeFilter() {
  Filter ekf(Vec<3>(1.0, 2.0, 0.5 * kPi), Mat<3, 3>::Zero());
  const Gaussian<2> noise = Gaussian<2>::sigmas(Vec<2>(0.1, 0.01));
  const double ranges[] = {2.0, 5.0, 9.0, 5.0, 5.0, 5.0};
  const double bearings_deg[] = {0.0, 30.0, 0.0, 80.0, 100.0, -179.0};
  for (int i = 0; i < 6; ++i)
    ekf.add(i + 1, InverseRangeBearing{}, Vec<2>(ranges[i], bearings_deg[i] * kRadPerDeg), noise);
  ekf.add(7, InverseRangeBearingDiameter{}, Vec<3>(3.0, 0.0, 0.4), Gaussian<3>::sigmas(Vec<3>(0.1, 0.01, 0.05)));
  return ekf;
}

TEST_CASE("landmarksInReach keeps the landmarks whose predicted reading is within range and field of view",
          "[slam][reach]") {
  const Filter ekf = makeFilter();
  slam::RangeBearingReach reach;
  reach.max_range_m = 6.0;
  reach.half_fov_rad = 90.0 * kRadPerDeg;
  CHECK(slam::landmarksInReach<Point2>(ekf, RangeBearing{}, reach) == std::vector<Id>{1, 2, 4});
  // The other type's slots are asked for separately.
  CHECK(slam::landmarksInReach<TreeXYR>(ekf, RangeBearing{}, reach) == std::vector<Id>{7});
  // The default reach is everything around, at any range.
  CHECK(slam::landmarksInReach<Point2>(ekf, RangeBearing{}, slam::RangeBearingReach{}) ==
        std::vector<Id>{1, 2, 3, 4, 5, 6});
  // A minimum range drops the closest.
  reach.min_range_m = 3.0;
  CHECK(slam::landmarksInReach<Point2>(ekf, RangeBearing{}, reach) == std::vector<Id>{2, 4});
}

TEST_CASE("landmarksInReach measures from a mounted sensor as RangeBearing does", "[slam][reach]") {
  const Filter ekf = makeFilter();
  // A sensor 4 m ahead of the robot's origin: landmark 3 (9 m ahead) is 5 m from it,
  // landmark 1 (2 m ahead) is behind the sensor, and landmark 2 is 2.5 m from it, 82.5 degrees
  // to the left of the heading.
  const RangeBearing mounted(Vec<2>(4.0, 0.0));
  slam::RangeBearingReach reach;
  reach.max_range_m = 5.5;
  reach.half_fov_rad = 90.0 * kRadPerDeg;
  const std::vector<Id> in = slam::landmarksInReach<Point2>(ekf, mounted, reach);
  CHECK(in == std::vector<Id>{2, 3});
  // Every id in reach has a reading within it, and every other one has not.
  for (const LandmarkSlot& s : ekf.slots()) {
    if (!ekf.holds<Point2>(s.id)) continue;
    const Vec<2> z = mounted(ekf.robotMean(), ekf.landmarkMean<Point2>(s.id));
    const bool inside = z[0] <= reach.max_range_m && std::abs(z[1]) <= reach.half_fov_rad;
    CHECK(inside == (std::find(in.begin(), in.end(), s.id) != in.end()));
  }
}

TEST_CASE("landmarksInReach refuses a malformed reach and leaves the output as it was", "[slam][reach]") {
  const Filter ekf = makeFilter();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<Id> out = {42};
  const auto refused = [&](slam::RangeBearingReach reach) {
    return throwsCode([&] { slam::landmarksInReach<Point2>(ekf, RangeBearing{}, reach, out); },
                      ErrorCode::kInvalidArgument) &&
           out == std::vector<Id>{42};
  };
  CHECK(refused({nan, 1.0, 0.0}));
  CHECK(refused({5.0, nan, 0.0}));
  CHECK(refused({5.0, 1.0, nan}));
  CHECK(refused({5.0, -0.1, 0.0}));
  CHECK(refused({5.0, 1.0, -1.0}));
  CHECK(refused({2.0, 1.0, 3.0}));  // min above max
  CHECK(refused({std::numeric_limits<double>::infinity(), 1.0, std::numeric_limits<double>::infinity()}));
}

}  // namespace unity_slam_reach
