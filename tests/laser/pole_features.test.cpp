#include "sylva_catch.hpp"

#include <cmath>
#include <vector>

#include <sylva/laser/pole_features.hpp>
#include <sylva/sim/laser_scanner_2d.hpp>

#include "moving_objects/slam_run.hpp"  // the example's hall with poles and people

namespace unity_laser_pole_features {

using sylva::Vec;

}  // namespace unity_laser_pole_features

using namespace unity_laser_pole_features;

TEST_CASE("Point features: a pole's centre within centimetres, walls and wide things are no features", "[moving_objects]") {
  sylva::sim::LaserScene2D scene;
  scene.addSegment(Vec<2>(7.0, -10.0), Vec<2>(7.0, 10.0), 1);     // a wall
  scene.addCircle(Vec<2>(3.0, 1.0), 0.08, 1000);                  // a pole
  scene.addCircle(Vec<2>(4.0, -2.0), 0.5, 2);                     // a wide pillar
  scene.addSegment(Vec<2>(2.0, -3.5), Vec<2>(2.8, -3.5), 3);      // a board, 0.8 m
  const sylva::sim::LaserScanner2D scanner;
  const auto g = scanner.geometry();
  double worst = 0.0;
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    sylva::sim::Rng rng(seed);
    const Vec<3> pose(0.0, 0.0, 0.1);
    const auto scan = scanner.scan(pose, scene, rng);
    const auto aligned = sylva::laser::alignScan(g, scan.ranges_m, pose);
    const auto features = sylva::laser::extractPointFeatures(g, aligned, sylva::laser::FeatureOptions{});
    REQUIRE(features.size() == 1);
    CHECK(moving_objects::majorityObject(scan, features[0].beams) == 1000);
    worst = std::max(worst, (features[0].world - Vec<2>(3.0, 1.0)).norm());
    CHECK(features[0].radius_m == Approx(0.08).margin(0.03));
  }
  CHECK(worst < 0.04);
}

TEST_CASE("SLAM with removal: removed features are legs, and without people removal changes nothing", "[moving_objects]") {
  moving_objects::SlamRunOptions o;
  o.scene.laps = 0.3;
  o.scene.people = 0;
  const auto still = moving_objects::simulateSlam(o, 3);
  const auto plain = moving_objects::runSlam(still, o, false);
  const auto removed = moving_objects::runSlam(still, o, true);
  CHECK(removed.removed == 0);
  CHECK(plain.landmark_rmse_m == removed.landmark_rmse_m);
  CHECK(plain.spurious_landmarks == 0);
  CHECK(plain.landmark_rmse_m < 0.05);

  o.scene.people = 6;
  const auto busy = moving_objects::simulateSlam(o, 3);
  const auto without = moving_objects::runSlam(busy, o, false);
  const auto with = moving_objects::runSlam(busy, o, true);
  CHECK(without.features_on_legs > 50);
  CHECK(with.removed > 20);
  CHECK(with.removed_on_legs >= 0.95 * with.removed);  // what is removed is legs
  CHECK(with.spurious_landmarks < without.spurious_landmarks);
  o.memory_s = 1.0;
  const auto memory = moving_objects::runSlam(busy, o, true);
  CHECK(memory.removed > with.removed);
  CHECK(memory.spurious_landmarks < with.spurious_landmarks);
}
