#include "sylva_catch.hpp"

#include "error_helpers.hpp"

#include <cmath>
#include <limits>
#include <vector>

#include "sylva/core/angles.hpp"
#include "sylva/sim/dynamic_scene_2d.hpp"
#include "sylva/sim/laser_scanner_2d.hpp"
#include "sylva/sim/laser_scene_2d.hpp"
#include "sylva/sim/walking_person_2d.hpp"

namespace unity_sim_laser_scanner_2d {

using sylva::ErrorCode;
using sylva::Id;
using sylva::kPi;
using sylva::Vec;
using sylva::sim::DynamicScene2D;
using sylva::sim::kNoObject;
using sylva::sim::LaserScan2D;
using sylva::sim::LaserScanner2D;
using sylva::sim::LaserScanner2DOptions;
using sylva::sim::LaserScene2D;
using sylva::sim::RigidObject2D;
using sylva::sim::Rng;
using sylva::sim::WalkingPerson2D;
using sylva::sim::WalkingPerson2DOptions;
using sylva_test::throwsCode;

// The range of a beam that hits nothing.
constexpr double kNoReturn = std::numeric_limits<double>::infinity();

LaserScanner2D noiselessScanner(double max_range = 8.0) {
  LaserScanner2DOptions o;
  o.sigma_range_m = 0.0;
  o.max_range_m = max_range;
  return LaserScanner2D(o);
}

WalkingPerson2DOptions straightWalk() {
  WalkingPerson2DOptions o;
  // Along y = -5, starting 1 m in so that no foot is behind the start of the route (where
  // a ping-pong route folds back and the legs swap sides).
  o.waypoints = {Vec<2>(0.0, -5.0), Vec<2>(10.0, -5.0)};
  o.speed_mps = 1.0;
  o.step_length_m = 0.6;
  o.start_distance_m = 1.0;
  return o;
}

}  // namespace unity_sim_laser_scanner_2d

using namespace unity_sim_laser_scanner_2d;

TEST_CASE("Laser ray casting: circle and segment distances are exact", "[sim][laser]") {
  const Vec<2> o(0.0, 0.0);
  const Vec<2> x(1.0, 0.0);
  CHECK(sylva::sim::rayCircleDistance(o, x, Vec<2>(5.0, 0.0), 0.5) == Approx(4.5));
  // Off-axis: the chord at height 0.3 of a unit circle centred at (4, 0.3).
  CHECK(sylva::sim::rayCircleDistance(o, x, Vec<2>(4.0, 0.3), 1.0) ==
        Approx(4.0 - std::sqrt(1.0 - 0.09)));
  CHECK(sylva::sim::rayCircleDistance(o, x, Vec<2>(4.0, 1.2), 1.0) == kNoReturn);   // misses
  CHECK(sylva::sim::rayCircleDistance(o, x, Vec<2>(-4.0, 0.0), 1.0) == kNoReturn);  // behind
  CHECK(sylva::sim::rayCircleDistance(o, x, Vec<2>(0.1, 0.0), 1.0) == 0.0);    // inside
  const Vec<2> d = Vec<2>(1.0, 1.0).normalized();
  CHECK(sylva::sim::raySegmentDistance(o, d, Vec<2>(3.0, -5.0), Vec<2>(3.0, 5.0)) ==
        Approx(3.0 * std::sqrt(2.0)));
  CHECK(sylva::sim::raySegmentDistance(o, d, Vec<2>(3.0, -5.0), Vec<2>(3.0, 2.0)) == kNoReturn);
  CHECK(sylva::sim::raySegmentDistance(o, x, Vec<2>(1.0, 0.0), Vec<2>(2.0, 0.0)) == kNoReturn);  // parallel
  CHECK(sylva::sim::raySegmentDistance(o, x, Vec<2>(-3.0, -1.0), Vec<2>(-3.0, 1.0)) == kNoReturn);
}

TEST_CASE("LaserScanner2D: 361 beams over 180 deg and exact ranges to a wall", "[sim][laser]") {
  const LaserScanner2D scanner = noiselessScanner(20.0);
  REQUIRE(scanner.beamCount() == 361);
  CHECK(scanner.beamAngle(0) == Approx(-90.0 * sylva::kRadPerDeg));
  CHECK(scanner.beamAngle(180) == Approx(0.0).margin(1e-12));
  CHECK(scanner.beamAngle(360) == Approx(90.0 * sylva::kRadPerDeg));
  // The geometry handed to scan readers names the same beams and range interval.
  const sylva::LaserScanGeometry g = scanner.geometry();
  REQUIRE(g.beams == 361);
  for (int k : {0, 1, 180, 360}) CHECK(g.beamAngle(k) == Approx(scanner.beamAngle(k)).margin(1e-12));
  CHECK(g.min_range_m == scanner.options().min_range_m);
  CHECK(g.max_range_m == 20.0);
  LaserScene2D scene;
  scene.addSegment(Vec<2>(6.0, -50.0), Vec<2>(6.0, 50.0), 7);  // a wall 5 m ahead of the sensor
  Rng rng(3);
  const Vec<3> pose(1.0, 0.0, 0.0);
  const LaserScan2D scan = scanner.scan(pose, scene, rng);
  REQUIRE(scan.ranges_m.size() == 361);
  int hits = 0;
  for (int i = 0; i < 361; ++i) {
    const auto k = static_cast<std::size_t>(i);
    const double alpha = scanner.beamAngle(i);
    const double expected = std::cos(alpha) > 1e-9 ? 5.0 / std::cos(alpha) : kNoReturn;
    if (expected <= 20.0) {
      ++hits;
      CHECK(scan.ranges_m[k] == Approx(expected).epsilon(1e-12));
      CHECK(scan.hit_object[k] == 7);
    } else {
      CHECK(scan.ranges_m[k] == kNoReturn);
      CHECK(scan.hit_object[k] == kNoObject);
    }
  }
  // Beams within acos(5/20) = 75.5 deg of the heading reach the wall.
  CHECK(hits == 2 * 151 + 1);
}

TEST_CASE("LaserScanner2D: nearest shape wins, occlusion, min and max range", "[sim][laser]") {
  LaserScanner2DOptions options;
  options.sigma_range_m = 0.0;
  options.min_range_m = 0.3;
  options.max_range_m = 6.0;
  const LaserScanner2D scanner(options);
  LaserScene2D scene;
  scene.addSegment(Vec<2>(4.0, -1.0), Vec<2>(4.0, 1.0), 1);  // wall ahead
  scene.addCircle(Vec<2>(2.0, 0.0), 0.1, 2);                 // a pole in front of it
  scene.addCircle(Vec<2>(0.0, 0.2), 0.1, 3);                 // touching the scanner on the left
  Rng rng(1);
  const LaserScan2D scan = scanner.scan(Vec<3>(0.0, 0.0, 0.0), scene, rng);
  CHECK(scan.ranges_m[180] == Approx(1.9));  // straight ahead: the pole's front
  CHECK(scan.hit_object[180] == 2);
  CHECK(scan.hit_object[180 + 8] == 1);                                   // 4 deg left: the wall
  CHECK(scan.ranges_m[180 + 8] == Approx(4.0 / std::cos(4.0 * sylva::kRadPerDeg)));
  CHECK(std::isnan(scan.ranges_m[360]));  // 90 deg left: the close circle, under min range
  CHECK(scan.hit_object[360] == 3);
  CHECK(scan.ranges_m[0] == kNoReturn);  // to the right: nothing
  CHECK(scan.true_range_m[0] == kNoReturn);
}

TEST_CASE("LaserScanner2D: range noise has the configured sigma and is reproducible", "[sim][laser]") {
  LaserScanner2DOptions options;
  options.sigma_range_m = 0.02;
  options.fov_rad = 2.0 * kPi;
  const LaserScanner2D scanner(options);
  LaserScene2D scene;
  scene.addCircle(Vec<2>(0.0, 0.0), 4.0, 1);
  scene.addCircle(Vec<2>(0.0, 0.0), 4.5, 2);  // beyond the first from inside: never seen
  // From inside the circle of radius 4 nothing is hit (the scanner is inside it).
  Rng rng(5);
  const LaserScan2D inside = scanner.scan(Vec<3>(0.0, 0.0, 0.3), scene, rng);
  CHECK(std::isnan(inside.ranges_m[10]));

  LaserScene2D ring;
  for (int k = 0; k < 72; ++k) {
    const double a = k * 5.0 * sylva::kRadPerDeg;
    ring.addSegment(Vec<2>(3.0 * std::cos(a), 3.0 * std::sin(a)),
                    Vec<2>(3.0 * std::cos(a + 5.0 * sylva::kRadPerDeg), 3.0 * std::sin(a + 5.0 * sylva::kRadPerDeg)), k);
  }
  double sum = 0.0, sum2 = 0.0;
  int n = 0;
  Rng a(11), b(11);
  for (int s = 0; s < 20; ++s) {
    const LaserScan2D first = scanner.scan(Vec<3>(0.0, 0.0, 0.1 * s), ring, a);
    const LaserScan2D second = scanner.scan(Vec<3>(0.0, 0.0, 0.1 * s), ring, b);
    REQUIRE(first.ranges_m == second.ranges_m);
    for (std::size_t i = 0; i < first.ranges_m.size(); ++i) {
      const double e = first.ranges_m[i] - first.true_range_m[i];
      sum += e;
      sum2 += e * e;
      ++n;
    }
  }
  const double mean = sum / n;
  const double sigma = std::sqrt(sum2 / n - mean * mean);
  CHECK(std::abs(mean) < 0.001);
  CHECK(sigma == Approx(0.02).epsilon(0.05));
}

TEST_CASE("LaserScanner2D and LaserScene2D refuse nonsense", "[sim][laser]") {
  auto with = [](auto change) {
    LaserScanner2DOptions o;
    change(o);
    return [o]() { LaserScanner2D s(o); };
  };
  CHECK(throwsCode(with([](auto& o) { o.fov_rad = 0.0; }), ErrorCode::kInvalidArgument));
  CHECK(throwsCode(with([](auto& o) { o.fov_rad = 7.0; }), ErrorCode::kInvalidArgument));
  CHECK(throwsCode(with([](auto& o) { o.resolution_rad = -0.01; }), ErrorCode::kInvalidArgument));
  CHECK(throwsCode(with([](auto& o) { o.resolution_rad = 1e-9; }), ErrorCode::kInvalidArgument));
  CHECK(throwsCode(with([](auto& o) { o.max_range_m = 0.01; }), ErrorCode::kInvalidArgument));
  CHECK(throwsCode(with([](auto& o) { o.min_range_m = std::nan(""); }), ErrorCode::kInvalidArgument));
  CHECK(throwsCode(with([](auto& o) { o.sigma_range_m = -1.0; }), ErrorCode::kInvalidArgument));
  LaserScene2D scene;
  CHECK(throwsCode([&] { scene.addCircle(Vec<2>(1.0, 1.0), 0.0, 1); }, ErrorCode::kInvalidArgument));
  CHECK(throwsCode([&] { scene.addCircle(Vec<2>(kNoReturn, 1.0), 1.0, 1); }, ErrorCode::kNonFinite));
  CHECK(throwsCode([&] { scene.addSegment(Vec<2>(1.0, 1.0), Vec<2>(1.0, 1.0), 1); },
                   ErrorCode::kInvalidArgument));
  CHECK(throwsCode([&] { scene.addPolyline({Vec<2>(0.0, 0.0)}, false, 1); },
                   ErrorCode::kInvalidArgument));
  CHECK(scene.empty());
  const LaserScanner2D scanner;
  Rng rng(1);
  CHECK(throwsCode([&] { scanner.scan(Vec<3>(0.0, std::nan(""), 0.0), scene, rng); }, ErrorCode::kNonFinite));
  // An empty scene is legal: every beam reads no return.
  const LaserScan2D empty = scanner.scan(Vec<3>::Zero(), scene, rng);
  for (const double r : empty.ranges_m) CHECK(r == kNoReturn);
}

TEST_CASE("WalkingPerson2D: legs alternate, stance legs stand still, feet keep up with the body",
          "[sim][laser][person]") {
  const WalkingPerson2D person(straightWalk(), 10, 11);
  const double dt = 0.01;
  Vec<2> previous[2] = {person.legCenter(0, 0.0), person.legCenter(1, 0.0)};
  double max_speed = 0.0;
  for (int k = 1; k <= 600; ++k) {  // 6 s: 6 m of a 10 m straight route
    const double t = k * dt;
    CHECK_FALSE((!person.inStance(0, t) && !person.inStance(1, t)));  // never both swinging
    for (int leg = 0; leg < 2; ++leg) {
      const Vec<2> c = person.legCenter(leg, t);
      const double speed = (c - previous[leg]).norm() / dt;
      max_speed = std::max(max_speed, speed);
      // Stance legs rest (the stance phase at t began before t - dt unless it just started).
      if (person.inStance(leg, t) && person.inStance(leg, t - dt)) CHECK(speed < 1e-9);
      CHECK(std::abs(c.y() - (leg == 0 ? -4.9 : -5.1)) < 1e-12);  // left leg on the left
      // The foot is L/2 behind the body when it lifts and L/2 ahead when it lands; the
      // cosine profile lags a little early in the swing (at most 0.551 L).
      CHECK(std::abs(c.x() - person.bodyPosition(t).x()) <= 0.552 * 0.6);
      previous[leg] = c;
    }
  }
  CHECK(max_speed == Approx(kPi * 1.0).epsilon(0.01));  // peak swing speed pi v
  // Over whole gait cycles each foot advances as much as the body.
  const double cycle = 2.0 * 0.6 / 1.0;
  for (int leg = 0; leg < 2; ++leg)
    CHECK((person.legCenter(leg, 0.3 + 3.0 * cycle) - person.legCenter(leg, 0.3)).x() ==
          Approx(3.0 * 2.0 * 0.6));
}

TEST_CASE("WalkingPerson2D: ping-pong and closed routes, bad options", "[sim][laser][person]") {
  WalkingPerson2DOptions o = straightWalk();
  o.start_distance_m = 9.0;
  const WalkingPerson2D back(o, 1, 2);
  CHECK(back.bodyPosition(0.0).x() == Approx(9.0));
  CHECK(back.bodyPosition(2.0).x() == Approx(9.0));  // 1 m out, 1 m back
  CHECK(back.routeDirection(11.5).x() == Approx(-1.0));
  o.waypoints = {Vec<2>(0.0, 0.0), Vec<2>(4.0, 0.0), Vec<2>(4.0, 3.0)};
  o.closed = true;
  o.start_distance_m = 0.0;
  const WalkingPerson2D loop(o, 1, 2);
  CHECK(loop.routePeriod() == Approx(12.0));
  CHECK((loop.routePoint(6.0) - Vec<2>(4.0, 2.0)).norm() < 1e-12);
  CHECK((loop.routePoint(10.0) - Vec<2>(1.6, 1.2)).norm() < 1e-12);
  CHECK((loop.routePoint(-2.0) - Vec<2>(1.6, 1.2)).norm() < 1e-12);

  auto make = [](WalkingPerson2DOptions w) { return [w] { WalkingPerson2D p(w, 1, 2); }; };
  WalkingPerson2DOptions bad = straightWalk();
  bad.waypoints = {Vec<2>(1.0, 1.0)};
  CHECK(throwsCode(make(bad), ErrorCode::kInvalidArgument));
  bad = straightWalk();
  bad.waypoints.push_back(bad.waypoints.back());
  CHECK(throwsCode(make(bad), ErrorCode::kInvalidArgument));
  bad = straightWalk();
  bad.step_length_m = 0.0;
  CHECK(throwsCode(make(bad), ErrorCode::kInvalidArgument));
  bad = straightWalk();
  bad.speed_mps = std::nan("");
  CHECK(throwsCode(make(bad), ErrorCode::kNonFinite));
  CHECK(throwsCode([&] { (void)back.legCenter(2, 0.0); }, ErrorCode::kInvalidArgument));
}

TEST_CASE("DynamicScene2D: snapshots move rigid objects and legs, truth ids", "[sim][laser]") {
  LaserScene2D walls;
  walls.addSegment(Vec<2>(8.0, -10.0), Vec<2>(8.0, 10.0), 1);
  DynamicScene2D world(walls);
  world.addRigidObject(RigidObject2D::box(100, 1.0, 0.5, Vec<3>(4.0, -2.0, 0.0), Vec<3>(0.0, 1.0, 0.0)));
  world.addPerson(WalkingPerson2D(straightWalk(), 200, 201));
  CHECK(world.isDynamic(100));
  CHECK(world.isDynamic(201));
  CHECK_FALSE(world.isDynamic(1));
  CHECK((*world.objectPosition(100, 2.0) - Vec<2>(4.0, 0.0)).norm() < 1e-12);
  CHECK_FALSE(world.objectPosition(1, 0.0).has_value());
  CHECK(world.dynamicObjectPositions(0.0).size() == 3);

  const LaserScanner2D scanner = noiselessScanner(20.0);
  Rng rng(1);
  LaserScene2D snapshot;
  world.snapshot(2.0, snapshot);
  CHECK(snapshot.segments().size() == 1 + 4);
  CHECK(snapshot.circles().size() == 2);
  const LaserScan2D scan = scanner.scan(Vec<3>(0.0, 0.0, 0.0), snapshot, rng);
  CHECK(scan.hit_object[180] == 100);  // the box now straight ahead, its near side at x = 3.5
  CHECK(scan.ranges_m[180] == Approx(3.5));
  world.snapshot(0.0, snapshot);
  const LaserScan2D before = scanner.scan(Vec<3>(0.0, 0.0, 0.0), snapshot, rng);
  CHECK(before.hit_object[180] == 1);  // the wall, the box still 2 m to the right

  CHECK(throwsCode([&] { world.addRigidObject(RigidObject2D::disc(200, 0.2, Vec<3>::Zero(), Vec<3>::Zero())); },
                   ErrorCode::kDuplicateId));
  CHECK(throwsCode([&] { world.addRigidObject(RigidObject2D::disc(1, 0.2, Vec<3>::Zero(), Vec<3>::Zero())); },
                   ErrorCode::kDuplicateId));
  CHECK(throwsCode([&] { world.addRigidObject(RigidObject2D{}); }, ErrorCode::kInvalidArgument));
  CHECK(throwsCode([&] { world.snapshot(kNoReturn, snapshot); }, ErrorCode::kNonFinite));
}
