#include "sylva_catch.hpp"

#include "error_helpers.hpp"

#include <cmath>

#include "sylva/sim/landmarks_2d.hpp"
#include "sylva/sim/planar_loop_world.hpp"

using sylva::ErrorCode;
using sylva::Vec;
using sylva::sim::LandmarkField2DOptions;
using sylva::sim::LoopPath2D;
using sylva::sim::Rng;

namespace {

using sylva_test::throwsCode;

}  // namespace

TEST_CASE("landmarksAlongPath: ids, band and separation", "[sim][landmarks]") {
  const LoopPath2D path = LoopPath2D::withPerimeter(120.0, 2.0, 8.0);
  LandmarkField2DOptions options;
  options.count = 150;
  options.band_min_m = 1.5;
  options.band_max_m = 6.0;
  options.min_separation_m = 1.2;
  Rng rng(11);
  const auto landmarks = sylva::sim::landmarksAlongPath(path, options, rng);
  REQUIRE(landmarks.size() == 150u);
  int inside = 0;
  for (std::size_t i = 0; i < landmarks.size(); ++i) {
    REQUIRE(landmarks[i].id == static_cast<sylva::Id>(i));
    const double d = path.distanceTo(landmarks[i].position);
    REQUIRE(d >= 1.5 - 1e-9);
    REQUIRE(d <= 6.0 + 1e-9);
    for (std::size_t j = 0; j < i; ++j)
      REQUIRE((landmarks[i].position - landmarks[j].position).norm() >= 1.2);
    const Vec<2>& p = landmarks[i].position;
    const bool in_box =
        std::abs(p.x()) < 0.5 * path.length() && p.y() > 0.0 && p.y() < path.width();
    inside += in_box ? 1 : 0;
  }
  // Both sides of the path are used (about half each).
  CHECK(inside > 45);
  CHECK(inside < 105);
}

TEST_CASE("landmarksAlongPath: reproducible from the seed", "[sim][landmarks]") {
  const LoopPath2D path = LoopPath2D::withPerimeter(120.0, 2.0, 8.0);
  Rng a(3), b(3), c(4);
  const auto la = sylva::sim::landmarksAlongPath(path, {}, a);
  const auto lb = sylva::sim::landmarksAlongPath(path, {}, b);
  const auto lc = sylva::sim::landmarksAlongPath(path, {}, c);
  REQUIRE(la.size() == 120u);
  for (std::size_t i = 0; i < la.size(); ++i) {
    REQUIRE(la[i].position == lb[i].position);
    REQUIRE(la[i].position != lc[i].position);
  }
}

TEST_CASE("landmarksAlongPath: invalid or impossible requests throw", "[sim][landmarks]") {
  const LoopPath2D path = LoopPath2D::withPerimeter(120.0, 2.0, 8.0);
  Rng rng(0);
  auto with = [](auto change) {
    LandmarkField2DOptions o;
    change(o);
    return o;
  };
  const ErrorCode bad = ErrorCode::kInvalidArgument;
  auto run = [&](const LandmarkField2DOptions& o) { sylva::sim::landmarksAlongPath(path, o, rng); };
  CHECK(throwsCode([&] { run(with([](auto& o) { o.count = 0; })); }, bad));
  CHECK(throwsCode([&] { run(with([](auto& o) { o.count = -5; })); }, bad));
  CHECK(throwsCode([&] { run(with([](auto& o) { o.band_min_m = -1.0; })); }, bad));
  CHECK(throwsCode([&] { run(with([](auto& o) { o.band_max_m = 0.5; })); }, bad));
  CHECK(throwsCode([&] { run(with([](auto& o) { o.min_separation_m = std::nan(""); })); }, bad));
  CHECK(throwsCode([&] { run(with([](auto& o) { o.max_attempts_per_landmark = 0; })); }, bad));
  // 1000 landmarks 5 m apart do not fit in a 12 m wide band along 120 m.
  CHECK(throwsCode(
      [&] {
        run(with([](auto& o) {
          o.count = 1000;
          o.min_separation_m = 5.0;
          o.max_attempts_per_landmark = 20;
        }));
      },
      bad));
}

TEST_CASE("PlanarLoopWorld: the range_bearing_slam world, the same from the same seed", "[sim]") {
  const sylva::sim::PlanarLoopWorldOptions options;
  CHECK(options.landmarks.count == 120);
  CHECK(options.sensor.max_range_m == 10.0);
  CHECK(options.trajectory.sigma_v_mps == 0.05);
  const auto a = sylva::sim::makePlanarLoopWorld(options, 7);
  const auto b = sylva::sim::makePlanarLoopWorld(options, 7);
  const auto c = sylva::sim::makePlanarLoopWorld(options, 8);
  REQUIRE(a.landmarks.size() == 120);
  bool same = true, differs = false;
  for (std::size_t i = 0; i < a.landmarks.size(); ++i) {
    same = same && a.landmarks[i].position == b.landmarks[i].position;
    differs = differs || a.landmarks[i].position != c.landmarks[i].position;
  }
  CHECK(same);
  CHECK(differs);
  // The landmarks come from the stream deriveSeed(seed, 0), as range_bearing_slam draws them.
  sylva::sim::Rng rng(sylva::sim::deriveSeed(7, 0));
  const auto direct = sylva::sim::landmarksAlongPath(a.trajectory.path(), options.landmarks, rng);
  CHECK(direct.front().position == a.landmarks.front().position);
  sylva::sim::PlanarLoopWorldOptions bad;
  bad.landmarks.count = 0;
  CHECK_THROWS_AS(sylva::sim::makePlanarLoopWorld(bad, 1), sylva::Error);
}
