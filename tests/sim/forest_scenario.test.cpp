// The forest simulator (thesis Sec. 4.1.1): forest statistics and reproducibility, the
// Bezier loop, the camera trajectory's conventions, the observer's visibility and occlusion
// rules, the default scenario, and bad options.

#include "sylva_catch.hpp"

#include <cmath>
#include <vector>

#include <Eigen/Geometry>

#include <sylva/motion/constant_velocity_3d.hpp>
#include <sylva/sim/forest_scenario.hpp>

#include "error_helpers.hpp"

using namespace sylva;
using namespace sylva::sim;
using sylva_test::throwsCode;

TEST_CASE("forest statistics follow the options and the seed", "[sim][forest]") {
  ForestOptions options;
  options.x_min_m = options.y_min_m = -200.0;
  options.x_max_m = options.y_max_m = 200.0;
  options.grid_spacing_m = 4.0;  // 100 x 100 cells
  Rng rng(1);
  const std::vector<Tree> trees = generateForest(options, rng);
  const double cells = 100.0 * 100.0;
  // Binomial(10000, 0.6): mean 6000, sigma 49.
  CHECK(std::abs(static_cast<double>(trees.size()) - 0.6 * cells) < 5.0 * std::sqrt(cells * 0.6 * 0.4));
  double sum = 0.0, sum2 = 0.0;
  for (const Tree& t : trees) {
    sum += t.radius_m;
    sum2 += t.radius_m * t.radius_m;
    CHECK(t.radius_m >= options.radius_min_m);
    CHECK(t.base.z() == options.groundElevation(t.base.x(), t.base.y()));
  }
  const double mean = sum / trees.size();
  const double sigma = std::sqrt(sum2 / trees.size() - mean * mean);
  CHECK(mean == Approx(0.25).epsilon(0.01));
  CHECK(sigma == Approx(0.07).epsilon(0.05));
  for (std::size_t i = 0; i < trees.size(); ++i) CHECK(trees[i].id == static_cast<Id>(i));

  Rng same(1), other(2);
  const std::vector<Tree> again = generateForest(options, same);
  REQUIRE(again.size() == trees.size());
  CHECK(again.back().base == trees.back().base);
  CHECK(generateForest(options, other).front().base != trees.front().base);
}

TEST_CASE("trees keep clear of the path", "[sim][forest]") {
  ForestOptions options;
  options.presence_probability = 1.0;
  Rng rng(4);
  const std::vector<Vec<2>> path{Vec<2>(0.0, 0.0), Vec<2>(2.0, 2.0)};
  for (const Tree& t : generateForest(options, rng, path))
    for (const Vec<2>& p : path) CHECK((t.base.head<2>() - p).norm() >= options.clearance_m + t.radius_m);
}

TEST_CASE("the Bezier loop passes through its waypoints, is closed, C1 and sampled at constant speed", "[sim][bezier]") {
  const BezierLoop2D loop(defaultForestWaypoints());
  const auto& w = loop.waypoints();
  const int n = static_cast<int>(w.size());
  for (int i = 0; i < n; ++i) {
    CHECK((loop.bezier(i, 0.0) - w[i]).norm() < 1e-12);
    CHECK((loop.bezier(i, 1.0) - w[(i + 1) % n]).norm() < 1e-12);
    // Tangent continuity at the joint.
    CHECK((loop.derivative(i, 1.0) - loop.derivative((i + 1) % n, 0.0)).norm() < 1e-12);
  }
  CHECK((loop.position(0.0) - loop.position(loop.length())).norm() < 1e-9);
  const double step = 0.1;
  for (double s = 0.0; s < loop.length() - step; s += step)
    CHECK((loop.position(s + step) - loop.position(s)).norm() == Approx(step).epsilon(0.01));
  CHECK(throwsCode([] { BezierLoop2D(std::vector<Vec<2>>{Vec<2>(0, 0), Vec<2>(1, 0)}); }, ErrorCode::kInvalidArgument));
  CHECK(throwsCode([] { BezierLoop2D(std::vector<Vec<2>>{Vec<2>(0, 0), Vec<2>(0, 0), Vec<2>(1, 1)}); }, ErrorCode::kInvalidArgument));
}

TEST_CASE("camera frames follow the camera conventions", "[sim][trajectory]") {
  const BezierLoop2D loop(defaultForestWaypoints());
  ForestOptions forest;
  TrajectoryOptions options;
  const auto frames = forestTrajectory(loop, options, [&](double x, double y) { return forest.groundElevation(x, y); });
  CHECK(frames.size() == static_cast<std::size_t>(std::floor(2.0 * loop.length() / 0.1 + 1e-9)) + 1);
  CHECK(frames.front().lap == 0);
  CHECK(frames.back().lap == 1);
  for (std::size_t k = 0; k < frames.size(); k += 37) {
    const Vec<13>& x = frames[k].state;
    CHECK(x.segment<4>(3).norm() == Approx(1.0).epsilon(1e-12));
    CHECK(x.z() - forest.groundElevation(x.x(), x.y()) == Approx(1.5));
    CHECK(x.segment<3>(7).norm() == Approx(1.0).epsilon(0.01));
    const Mat<3, 3> R = Eigen::Quaterniond(x[3], x[4], x[5], x[6]).toRotationMatrix();
    // A point ahead along the direction of travel is in front (Z > 0); one to the right
    // has X > 0; one below has Y > 0.
    const Vec<2> t = loop.tangent(0.1 * k);
    const Vec<3> ahead = x.head<3>() + 5.0 * Vec<3>(t.x(), t.y(), 0.0);
    const Vec<3> right = x.head<3>() + 5.0 * Vec<3>(t.x(), t.y(), 0.0) + Vec<3>(t.y(), -t.x(), 0.0);
    CHECK((R.transpose() * (ahead - x.head<3>())).z() > 0.0);
    CHECK((R.transpose() * (right - x.head<3>())).x() > 0.0);
    CHECK((R.transpose() * Vec<3>(0, 0, -1)).y() > 0.0);
  }
  TrajectoryOptions bad;
  bad.dt_s = 0.0;
  CHECK(throwsCode([&] { forestTrajectory(loop, bad, [](double, double) { return 0.0; }); }, ErrorCode::kInvalidArgument));
}

TEST_CASE("the observer's visibility and occlusion rules", "[sim][observer]") {
  const PinholeCamera camera{500.0, 500.0, 320.0, 240.0, 640, 480};
  ObserverOptions options;
  options.sigma_px = options.sigma_width_px = 0.0;
  // Camera at 1.5 m looking along +x, pitched down 15 deg.
  Vec<13> x = Vec<13>::Zero();
  const Eigen::Quaterniond q(cameraOrientation(Vec<2>(1.0, 0.0), 15.0 * 3.14159265358979323846 / 180.0));
  x << 0.0, 0.0, 1.5, q.w(), q.x(), q.y(), q.z(), 0, 0, 0, 0, 0, 0;
  const std::vector<Tree> trees{
      Tree{0, Vec<3>(8.0, 0.0, 0.0), 0.3},    // ahead
      Tree{1, Vec<3>(12.0, 0.1, 0.0), 0.3},   // behind tree 0, overlapping in u
      Tree{2, Vec<3>(-8.0, 0.0, 0.0), 0.3},   // behind the camera
      Tree{3, Vec<3>(8.0, 30.0, 0.0), 0.3},   // far to the left, out of the image
      Tree{4, Vec<3>(1.0, 0.0, 0.0), 0.3},    // too close: base below the image
      Tree{5, Vec<3>(10.0, -4.0, 0.0), 0.3},  // ahead on the right, clear
  };
  Rng rng(1);
  std::vector<Id> ids;
  for (const auto& o : TreeObserver(camera, options).observe(x, trees, rng)) {
    ids.push_back(o.id);
    CHECK(o.z == o.z_true);
    CHECK(o.z_true == TreeWidth(camera)(ConstantVelocity3D::pose(x), trees[o.id].xyzr()));
  }
  CHECK(ids == std::vector<Id>{0, 5});
  options.occlusion = false;
  ids.clear();
  for (const auto& o : TreeObserver(camera, options).observe(x, trees, rng)) ids.push_back(o.id);
  CHECK(ids == std::vector<Id>{0, 1, 5});

  // Noise statistics.
  options.sigma_px = 2.0;
  options.sigma_width_px = 0.5;
  const TreeObserver noisy(camera, options);
  double su = 0.0, sw = 0.0;
  const int n = 4000;
  for (int i = 0; i < n; ++i) {
    const auto o = noisy.observe(x, {trees[0]}, rng).at(0);
    su += (o.z[0] - o.z_true[0]) * (o.z[0] - o.z_true[0]);
    sw += (o.z[2] - o.z_true[2]) * (o.z[2] - o.z_true[2]);
  }
  CHECK(std::sqrt(su / n) == Approx(2.0).epsilon(0.05));
  CHECK(std::sqrt(sw / n) == Approx(0.5).epsilon(0.05));
  options.sigma_px = -1.0;
  CHECK(throwsCode([&] { TreeObserver(camera, options); }, ErrorCode::kInvalidArgument));
}

TEST_CASE("the default scenario is reproducible and sees trees in every frame", "[sim][scenario][slow]") {
  const ForestScenario a = makeForestScenario(ForestScenarioOptions{}, 1);
  const ForestScenario b = makeForestScenario(ForestScenarioOptions{}, 1);
  REQUIRE(a.frames.size() == a.observations.size());
  REQUIRE(a.observations.size() == b.observations.size());
  std::size_t total = 0, fewest = 1000, most = 0;
  for (std::size_t k = 0; k < a.observations.size(); ++k) {
    REQUIRE(a.observations[k].size() == b.observations[k].size());
    for (std::size_t i = 0; i < a.observations[k].size(); ++i) CHECK(a.observations[k][i].z == b.observations[k][i].z);
    total += a.observations[k].size();
    fewest = std::min(fewest, a.observations[k].size());
    most = std::max(most, a.observations[k].size());
  }
  WARN("default scenario: " << a.trees.size() << " trees, " << a.frames.size() << " frames, observed trees per frame: mean "
                            << static_cast<double>(total) / a.frames.size() << ", min " << fewest << ", max " << most);
  CHECK(a.trees.size() >= 30);
  CHECK(fewest >= 3);
}

TEST_CASE("the scenario's parts: thinned forests and other noise on the same forest", "[sim][scenario][slow]") {
  // One lap is enough for these properties (the default scenario drives two; it has a case
  // of its own), and the case builds four scenarios.
  ForestScenarioOptions options;
  options.trajectory.laps = 1;
  const std::vector<Tree> trees = makeForestTrees(options, 7);
  // makeForestScenario is the composition of its parts.
  const ForestScenario whole = makeForestScenario(options, 7);
  const ForestScenario parts = observeForest(options, trees, deriveSeed(7, 2));
  REQUIRE(whole.trees.size() == trees.size());
  REQUIRE(whole.observations.size() == parts.observations.size());
  for (std::size_t k = 0; k < whole.observations.size(); ++k) {
    REQUIRE(whole.observations[k].size() == parts.observations[k].size());
    for (std::size_t i = 0; i < whole.observations[k].size(); ++i) CHECK(whole.observations[k][i].z == parts.observations[k][i].z);
  }
  // Another noise seed: the same trees are seen, with other noise.
  const ForestScenario other = observeForest(options, trees, deriveSeed(7, 3));
  REQUIRE(other.observations[10].size() == parts.observations[10].size());
  CHECK(other.observations[10][0].z_true == parts.observations[10][0].z_true);
  CHECK(other.observations[10][0].z != parts.observations[10][0].z);

  // Thinning keeps round(fraction N) trees, renumbered, in order, all from the original.
  Rng rng(3);
  const std::vector<Tree> thin = thinForest(trees, 0.6, rng);
  CHECK(thin.size() == static_cast<std::size_t>(std::llround(0.6 * static_cast<double>(trees.size()))));
  std::size_t from = 0;
  for (std::size_t i = 0; i < thin.size(); ++i) {
    CHECK(thin[i].id == static_cast<Id>(i));
    while (from < trees.size() && trees[from].base != thin[i].base) ++from;
    CHECK(from < trees.size());  // found, and after the previous one: order kept
  }
  Rng rng_again(3);
  const std::vector<Tree> thin_again = thinForest(trees, 0.6, rng_again);
  for (std::size_t i = 0; i < thin.size(); ++i) CHECK(thin_again[i].base == thin[i].base);
  Rng rng_other(4);
  const std::vector<Tree> thin_other = thinForest(trees, 0.6, rng_other);
  bool differs = false;
  for (std::size_t i = 0; i < thin.size(); ++i) differs = differs || thin_other[i].base != thin[i].base;
  CHECK(differs);
  CHECK(thinForest(trees, 1.0, rng).size() == trees.size());
  CHECK(thinForest(trees, 0.0, rng).empty());
  CHECK(observeForest(options, thin, 1).trees.size() == thin.size());

  CHECK(throwsCode([&] { thinForest(trees, 1.5, rng); }, ErrorCode::kInvalidArgument));
  CHECK(throwsCode([&] { thinForest(trees, std::nan(""), rng); }, ErrorCode::kInvalidArgument));
  std::vector<Tree> bad_ids = trees;
  bad_ids[1].id = 5;
  CHECK(throwsCode([&] { observeForest(options, bad_ids, 1); }, ErrorCode::kInvalidArgument));
}
