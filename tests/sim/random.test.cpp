#include "sylva_catch.hpp"

#include "error_helpers.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "sylva/sim/random.hpp"

using sylva::ErrorCode;
using sylva::sim::Rng;

namespace {

using sylva_test::throwsCode;

}  // namespace

TEST_CASE("Rng: the engine is the standard mt19937_64", "[sim][random]") {
  // The C++ standard fixes the 10000th output of a default-seeded mt19937_64.
  Rng rng(5489u);
  std::uint64_t x = 0;
  for (int i = 0; i < 10000; ++i) x = rng.engine()();
  CHECK(x == 9981545732273789042ULL);
}

TEST_CASE("Rng: uniform01 is the top 53 bits of the engine", "[sim][random]") {
  Rng a(42);
  std::mt19937_64 reference(42);
  for (int i = 0; i < 100; ++i) {
    const double expected = static_cast<double>(reference() >> 11) / 9007199254740992.0;
    REQUIRE(a.uniform01() == expected);
  }
}

TEST_CASE("Rng: the same seed gives the same sequence bit for bit", "[sim][random]") {
  Rng a(12345);
  Rng b(12345);
  for (int i = 0; i < 1000; ++i) {
    REQUIRE(a.normal() == b.normal());
    REQUIRE(a.uniform(-3.0, 7.0) == b.uniform(-3.0, 7.0));
  }
  CHECK(a.seed() == 12345u);
}

TEST_CASE("Rng: different seeds give different sequences", "[sim][random]") {
  Rng a(1);
  Rng b(2);
  int equal = 0;
  for (int i = 0; i < 1000; ++i) equal += a.normal() == b.normal() ? 1 : 0;
  CHECK(equal == 0);
}

TEST_CASE("Rng: normal() has the moments of N(0, 1)", "[sim][random]") {
  Rng rng(2024);
  const int n = 200000;
  double sum = 0.0, sum2 = 0.0, sum3 = 0.0, sum4 = 0.0;
  int within_one = 0;
  for (int i = 0; i < n; ++i) {
    const double x = rng.normal();
    sum += x;
    sum2 += x * x;
    sum3 += x * x * x;
    sum4 += x * x * x * x;
    within_one += std::abs(x) <= 1.0 ? 1 : 0;
  }
  const double mean = sum / n;
  const double var = sum2 / n - mean * mean;
  // Tolerances are 5 standard errors: sd(mean) = 1/sqrt(n), sd(var) = sqrt(2/n),
  // sd(skew) = sqrt(6/n), sd(kurtosis) = sqrt(24/n), sd(fraction) = sqrt(p(1-p)/n).
  const double root_n = std::sqrt(static_cast<double>(n));
  CHECK(std::abs(mean) < 5.0 / root_n);
  CHECK(std::abs(var - 1.0) < 5.0 * std::sqrt(2.0) / root_n);
  CHECK(std::abs(sum3 / n) < 5.0 * std::sqrt(6.0) / root_n);
  CHECK(std::abs(sum4 / n - 3.0) < 5.0 * std::sqrt(24.0) / root_n);
  const double p = 0.6826894921370859;
  CHECK(std::abs(static_cast<double>(within_one) / n - p) < 5.0 * std::sqrt(p * (1 - p)) / root_n);
}

TEST_CASE("Rng: uniform(lo, hi) stays at or above lo and below hi, with the right mean", "[sim][random]") {
  Rng rng(7);
  const int n = 100000;
  double sum = 0.0;
  double lo_seen = 1e9, hi_seen = -1e9;
  for (int i = 0; i < n; ++i) {
    const double x = rng.uniform(-2.0, 3.0);
    REQUIRE(x >= -2.0);
    REQUIRE(x < 3.0);
    sum += x;
    lo_seen = std::min(lo_seen, x);
    hi_seen = std::max(hi_seen, x);
  }
  // Mean 0.5, sd of the mean = 5 / sqrt(12 n).
  CHECK(std::abs(sum / n - 0.5) < 5.0 * 5.0 / std::sqrt(12.0 * n));
  CHECK(lo_seen < -1.99);
  CHECK(hi_seen > 2.99);
}

TEST_CASE("Rng: normal(mean, sigma) scales and shifts", "[sim][random]") {
  Rng a(99);
  Rng b(99);
  for (int i = 0; i < 100; ++i) REQUIRE(a.normal(3.0, 0.5) == 3.0 + 0.5 * b.normal());
}

TEST_CASE("Rng: sample(Gaussian) draws with the covariance", "[sim][random]") {
  Rng rng(3);
  const auto noise = sylva::Gaussian<2>::sigmas(sylva::Vec<2>(2.0, 0.1));
  const int n = 50000;
  sylva::Mat<2, 2> acc = sylva::Mat<2, 2>::Zero();
  for (int i = 0; i < n; ++i) {
    const sylva::Vec<2> x = rng.sample(noise);
    acc += x * x.transpose();
  }
  acc /= n;
  CHECK(std::abs(acc(0, 0) / 4.0 - 1.0) < 0.05);
  CHECK(std::abs(acc(1, 1) / 0.01 - 1.0) < 0.05);
  CHECK(std::abs(acc(0, 1)) / (2.0 * 0.1) < 0.05);
}

TEST_CASE("Rng: invalid arguments throw", "[sim][random]") {
  Rng rng(0);
  const double nan = std::nan("");
  CHECK(throwsCode([&] { rng.uniform(1.0, 1.0); }, ErrorCode::kInvalidArgument));
  CHECK(throwsCode([&] { rng.uniform(2.0, 1.0); }, ErrorCode::kInvalidArgument));
  CHECK(throwsCode([&] { rng.uniform(nan, 1.0); }, ErrorCode::kInvalidArgument));
  CHECK(throwsCode([&] { rng.normal(0.0, -1.0); }, ErrorCode::kInvalidArgument));
  CHECK(throwsCode([&] { rng.normal(nan, 1.0); }, ErrorCode::kInvalidArgument));
}

TEST_CASE("deriveSeed: distinct, deterministic streams", "[sim][random]") {
  std::vector<std::uint64_t> seeds;
  for (std::uint64_t i = 0; i < 1000; ++i) seeds.push_back(sylva::sim::deriveSeed(1, i));
  std::vector<std::uint64_t> sorted = seeds;
  std::sort(sorted.begin(), sorted.end());
  CHECK(std::adjacent_find(sorted.begin(), sorted.end()) == sorted.end());
  CHECK(sylva::sim::deriveSeed(1, 5) == seeds[5]);
  CHECK(sylva::sim::deriveSeed(2, 5) != seeds[5]);
}
