#include "sylva_catch.hpp"

#include "error_helpers.hpp"

#include <cmath>
#include <map>

#include "sylva/sim/range_bearing_sensor.hpp"

using sylva::ErrorCode;
using sylva::kPi;
using sylva::Vec;
using sylva::sim::RangeBearingSensor2D;
using sylva::sim::RangeBearingSensor2DOptions;
using sylva::sim::Rng;
using sylva::sim::TrueLandmark2D;

namespace {

using sylva_test::throwsCode;

std::vector<TrueLandmark2D> grid(double half, double step) {
  std::vector<TrueLandmark2D> out;
  sylva::Id id = 0;
  for (double x = -half; x <= half; x += step)
    for (double y = -half; y <= half; y += step)
      out.push_back({id++, Vec<2>(x + 0.013, y + 0.029)});
  return out;
}

}  // namespace

TEST_CASE("RangeBearingSensor2D: sees exactly what is in range and field of view",
          "[sim][sensor]") {
  RangeBearingSensor2DOptions options;
  options.max_range_m = 6.0;
  options.min_range_m = 0.5;
  options.fov_half_angle_rad = 60.0 * kPi / 180.0;
  const RangeBearingSensor2D sensor(options);
  const auto landmarks = grid(10.0, 0.5);
  const Vec<3> pose(0.3, -0.2, 2.5);  // heading near 143 deg: the FOV straddles no wrap
  Rng rng(1);
  const auto readings = sensor.observe(pose, landmarks, rng);
  std::map<sylva::Id, Vec<2>> seen;
  for (const auto& r : readings) seen[r.id] = r.z;
  const sylva::RangeBearing model;
  int expected = 0;
  for (const auto& l : landmarks) {
    const Vec<2> z = model(pose, l.position);
    const bool in = z[0] >= 0.5 && z[0] <= 6.0 && std::abs(z[1]) <= options.fov_half_angle_rad;
    expected += in ? 1 : 0;
    REQUIRE(sensor.visible(pose, l.position) == in);
    REQUIRE((seen.count(l.id) == 1) == in);
    if (in) {
      // Within 6 sigma of the truth.
      REQUIRE(std::abs(seen[l.id][0] - z[0]) < 6.0 * 0.05);
      REQUIRE(std::abs(sylva::wrapAngle(seen[l.id][1] - z[1])) < 6.0 * kPi / 180.0);
    }
  }
  CHECK(expected > 50);
  CHECK(static_cast<int>(readings.size()) == expected);
}

TEST_CASE("RangeBearingSensor2D: the field of view wraps around +-pi", "[sim][sensor]") {
  RangeBearingSensor2DOptions options;
  options.fov_half_angle_rad = 0.5 * kPi;
  const RangeBearingSensor2D sensor(options);
  const Vec<3> pose(0.0, 0.0, kPi - 0.1);  // looking along -x
  CHECK(sensor.visible(pose, Vec<2>(-3.0, 0.5)));
  CHECK(sensor.visible(pose, Vec<2>(-3.0, -0.5)));
  CHECK_FALSE(sensor.visible(pose, Vec<2>(3.0, 0.0)));
}

TEST_CASE("RangeBearingSensor2D: noise statistics match the sigmas", "[sim][sensor]") {
  RangeBearingSensor2DOptions options;
  options.fov_half_angle_rad = kPi;
  options.sigma_range_m = 0.1;
  options.sigma_bearing_rad = 0.05;
  const RangeBearingSensor2D sensor(options);
  // Landmark straight behind: its true bearing is pi, so noisy readings wrap to both signs.
  const Vec<3> pose(1.0, 2.0, 0.0);
  const std::vector<TrueLandmark2D> landmarks{{7, Vec<2>(-4.0, 2.0)}};
  Rng rng(21);
  const int n = 50000;
  double sr = 0, sr2 = 0, sb = 0, sb2 = 0;
  int negative = 0;
  for (int i = 0; i < n; ++i) {
    const auto readings = sensor.observe(pose, landmarks, rng);
    REQUIRE(readings.size() == 1u);
    REQUIRE(readings[0].id == 7);
    const double er = readings[0].z[0] - 5.0;
    REQUIRE(readings[0].z[1] > -kPi);
    REQUIRE(readings[0].z[1] <= kPi);
    negative += readings[0].z[1] < 0.0 ? 1 : 0;
    const double eb = sylva::wrapAngle(readings[0].z[1] - kPi);
    sr += er;
    sr2 += er * er;
    sb += eb;
    sb2 += eb * eb;
  }
  CHECK(std::abs(sr / n) < 5.0 * 0.1 / std::sqrt(n));
  CHECK(std::abs(sb / n) < 5.0 * 0.05 / std::sqrt(n));
  CHECK(std::abs(sr2 / n / 0.01 - 1.0) < 5.0 * std::sqrt(2.0 / n));
  CHECK(std::abs(sb2 / n / 0.0025 - 1.0) < 5.0 * std::sqrt(2.0 / n));
  CHECK(negative > n / 3);
  CHECK(negative < 2 * n / 3);
  CHECK(sensor.noise().covariance()(0, 0) == 0.1 * 0.1);
}

TEST_CASE("RangeBearingSensor2D: reproducible from the seed", "[sim][sensor]") {
  const RangeBearingSensor2D sensor;
  const auto landmarks = grid(8.0, 1.0);
  Rng a(5), b(5), c(6);
  const Vec<3> pose(0.0, 0.0, 0.3);
  const auto ra = sensor.observe(pose, landmarks, a);
  const auto rb = sensor.observe(pose, landmarks, b);
  const auto rc = sensor.observe(pose, landmarks, c);
  REQUIRE(ra.size() == rb.size());
  REQUIRE(ra.size() == rc.size());
  REQUIRE(!ra.empty());
  for (std::size_t i = 0; i < ra.size(); ++i) {
    REQUIRE(ra[i].id == rb[i].id);
    REQUIRE(ra[i].z == rb[i].z);
    REQUIRE(ra[i].z != rc[i].z);
  }
}

TEST_CASE("RangeBearingSensor2D: invalid arguments throw", "[sim][sensor]") {
  const double nan = std::nan("");
  auto with = [](auto change) {
    RangeBearingSensor2DOptions o;
    change(o);
    return o;
  };
  const ErrorCode bad = ErrorCode::kInvalidArgument;
  CHECK(throwsCode([&] { RangeBearingSensor2D(with([](auto& o) { o.max_range_m = 0.0; })); }, bad));
  CHECK(
      throwsCode([&] { RangeBearingSensor2D(with([](auto& o) { o.min_range_m = -1.0; })); }, bad));
  CHECK(throwsCode([&] { RangeBearingSensor2D(with([](auto& o) { o.min_range_m = 9.0; })); }, bad));
  CHECK(throwsCode([&] { RangeBearingSensor2D(with([](auto& o) { o.fov_half_angle_rad = 0.0; })); },
                   bad));
  CHECK(throwsCode([&] { RangeBearingSensor2D(with([](auto& o) { o.fov_half_angle_rad = 4.0; })); },
                   bad));
  CHECK(
      throwsCode([&] { RangeBearingSensor2D(with([](auto& o) { o.sigma_range_m = 0.0; })); }, bad));
  CHECK(throwsCode([&] { RangeBearingSensor2D(with([&](auto& o) { o.sigma_bearing_rad = nan; })); },
                   bad));
  const RangeBearingSensor2D sensor;
  Rng rng(0);
  CHECK(throwsCode([&] { sensor.observe(Vec<3>(nan, 0.0, 0.0), {}, rng); }, ErrorCode::kNonFinite));
}
