#include "sylva_catch.hpp"

#include "error_helpers.hpp"

#include <cmath>
#include <limits>
#include <vector>

#include <sylva/laser/object_position.hpp>
#include <sylva/laser/segments.hpp>
#include <sylva/laser/object_tracker.hpp>

namespace unity_laser_segments_and_position {

using sylva::laser::PointSet;
using sylva::LaserScanGeometry;
using sylva::laser::Segment;
using sylva::laser::SegmentOptions;
using sylva::Vec;

const LaserScanGeometry kGeometry{-sylva::kPi / 2, sylva::kPi / 180.0, 181, 0.05, 10.0};

/// A scan at the origin; every beam reads `ranges[i]`.
sylva::laser::AlignedScan scanOf(const std::vector<double>& ranges) {
  return sylva::laser::alignScan(kGeometry, ranges, Vec<3>::Zero());
}

std::vector<PointSet> setOf(int n, std::initializer_list<std::pair<int, int>> spans) {
  std::vector<PointSet> sets(static_cast<std::size_t>(n), PointSet::kA);
  for (const auto& [a, b] : spans)
    for (int i = a; i <= b; ++i) sets[static_cast<std::size_t>(i)] = PointSet::kM;
  return sets;
}

}  // namespace unity_laser_segments_and_position

using namespace unity_laser_segments_and_position;

TEST_CASE("Segments: consecutive members close in space, dropouts bridged, range jumps cut", "[moving_objects]") {
  std::vector<double> ranges(181, 5.0);
  for (int i = 20; i <= 29; ++i) ranges[static_cast<std::size_t>(i)] = 2.0;
  ranges[24] = std::nan("");  // a dropout inside the first object
  for (int i = 30; i <= 35; ++i) ranges[static_cast<std::size_t>(i)] = 3.0;  // right behind it: a range jump
  const auto scan = scanOf(ranges);
  auto sets = setOf(181, {{20, 35}});
  sets[24] = PointSet::kNone;
  const auto segments = sylva::laser::segmentSet(kGeometry, scan, sets, PointSet::kM, SegmentOptions{});
  REQUIRE(segments.size() == 2);
  CHECK(segments[0].beams == std::vector<int>{20, 21, 22, 23, 25, 26, 27, 28, 29});
  CHECK(segments[1].first() == 30);
  CHECK(segments[1].last() == 35);
  // A valid reading of another set between two members cuts the segment.
  sets[24] = PointSet::kA;
  ranges[24] = 2.0;
  const auto cut = sylva::laser::segmentSet(kGeometry, scanOf(ranges), sets, PointSet::kM, SegmentOptions{});
  CHECK(cut.size() == 3);
  // More dropouts than max_beam_gap cut it too.
  for (int i = 23; i <= 25; ++i) ranges[static_cast<std::size_t>(i)] = std::nan("");
  for (int i = 23; i <= 25; ++i) sets[static_cast<std::size_t>(i)] = PointSet::kNone;
  CHECK(sylva::laser::segmentSet(kGeometry, scanOf(ranges), sets, PointSet::kM, SegmentOptions{}).size() == 3);
}

TEST_CASE("Join: ends within the threshold merge, the joined segment leaves B, repeated until B stops shrinking",
          "[moving_objects]") {
  std::vector<double> ranges(181, 5.0);
  for (int i = 40; i <= 60; ++i) ranges[static_cast<std::size_t>(i)] = 2.0;  // one object at 2 m, beams 40-60
  const auto scan = scanOf(ranges);
  std::vector<Segment> a{Segment{{40, 41, 42}}};
  std::vector<Segment> b{Segment{{43, 44, 45, 46}}, Segment{{47, 48, 49, 50, 51}}, Segment{{100, 101}}, Segment{{10, 11}}};
  const int merged = sylva::laser::join(kGeometry, scan, SegmentOptions{}, a, b);
  CHECK(merged == 2);  // 43-46 touches 40-42; then 47-51 touches the grown segment
  REQUIRE(a.size() == 1);
  CHECK(a[0].first() == 40);
  CHECK(a[0].last() == 51);
  CHECK(a[0].size() == 12);
  REQUIRE(b.size() == 2);  // the far-away segments stay
  CHECK(b[0].first() == 100);
  // Beam 39 is the 5 m background next to the object at 2 m: not close.
  std::vector<Segment> object{Segment{{40, 41}}};
  std::vector<Segment> background{Segment{{35, 36, 37, 38, 39}}};
  CHECK(sylva::laser::join(kGeometry, scan, SegmentOptions{}, object, background) == 0);
  CHECK(background.size() == 1);
}

TEST_CASE("Object position: convex hull, its area centroid and the bounding box", "[moving_objects]") {
  using sylva::laser::convexHull;
  using sylva::laser::hullCentroid;
  // A square with interior and edge points: the hull is its four corners.
  std::vector<Vec<2>> square{Vec<2>(0, 0), Vec<2>(2, 0), Vec<2>(2, 2), Vec<2>(0, 2), Vec<2>(1, 1), Vec<2>(1, 0), Vec<2>(0.5, 1.5)};
  CHECK(convexHull(square).size() == 4);
  CHECK((hullCentroid(square) - Vec<2>(1, 1)).norm() < 1e-12);
  // A triangle: the centroid of its area is the mean of its corners (not of the points).
  std::vector<Vec<2>> triangle{Vec<2>(0, 0), Vec<2>(3, 0), Vec<2>(0, 3), Vec<2>(0.1, 0.1), Vec<2>(0.2, 0.1)};
  CHECK((hullCentroid(triangle) - Vec<2>(1, 1)).norm() < 1e-12);
  // Collinear points (a board seen edge-on) and a single point.
  std::vector<Vec<2>> line{Vec<2>(1, 1), Vec<2>(2, 2), Vec<2>(4, 4), Vec<2>(3, 3)};
  CHECK((hullCentroid(line) - Vec<2>(2.5, 2.5)).norm() < 1e-12);
  CHECK((hullCentroid({Vec<2>(3, -1)}) - Vec<2>(3, -1)).norm() == 0.0);
  const auto box = sylva::laser::boundingBox(triangle);
  CHECK((box.min - Vec<2>(0, 0)).norm() == 0.0);
  CHECK((box.max - Vec<2>(3, 3)).norm() == 0.0);
  CHECK((box.center() - Vec<2>(1.5, 1.5)).norm() == 0.0);
  CHECK(sylva_test::throwsCode([] { hullCentroid({}); }, sylva::ErrorCode::kInvalidArgument));
  // The readings of a disc's near half: the hull centroid lies between the front and the centre.
  std::vector<Vec<2>> arc;
  for (int k = -8; k <= 8; ++k) {
    const double a = sylva::kPi + k * 0.15;
    arc.push_back(Vec<2>(3.0 + 0.1 * std::cos(a), 0.1 * std::sin(a)));
  }
  const Vec<2> c = hullCentroid(arc);
  CHECK(c.x() > 2.9);
  CHECK(c.x() < 3.0);
}

TEST_CASE("Tracker: legs grouped into people, nearest-neighbour tracks confirmed after three hits", "[moving_objects]") {
  std::vector<sylva::laser::DetectedObject> objects(3);
  objects[0].hull_centroid = Vec<2>(1.0, 0.0);
  objects[1].hull_centroid = Vec<2>(1.0, 0.3);
  objects[2].hull_centroid = Vec<2>(4.0, 0.0);
  const auto people = sylva::laser::groupPeople(objects, 0.6);
  REQUIRE(people.size() == 2);
  CHECK(people[0].legs == 2);
  CHECK((people[0].position - Vec<2>(1.0, 0.15)).norm() < 1e-12);
  sylva::laser::NearestNeighborTracker tracker;
  for (int k = 0; k < 5; ++k)
    tracker.update(0.2 * k, {Vec<2>(1.0 + 0.2 * k, 0.0), Vec<2>(5.0, 3.0 - 0.25 * k)});
  CHECK(tracker.tracks().size() == 2);
  CHECK(tracker.confirmedCount() == 2);
  for (int k = 5; k < 12; ++k) tracker.update(0.2 * k, {});
  CHECK(tracker.activeConfirmed() == 0);  // both ended after 5 misses
  tracker.update(2.4, {Vec<2>(9.0, 9.0)});
  CHECK(tracker.tracks().size() == 3);
  CHECK(tracker.confirmedCount() == 2);
}
