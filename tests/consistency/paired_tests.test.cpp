// Paired tests and the Wilson interval against an independent implementation: the reference
// values were computed with SciPy 1.10 (scipy.stats.wilcoxon, binomtest and its
// proportion_ci(method="wilson")) on the same numbers, and agree with the worked examples of
// the textbooks cited in paired_tests.hpp.

#include <limits>
#include <vector>

#include <sylva/consistency/paired_tests.hpp>

#include "error_helpers.hpp"
#include "sylva_catch.hpp"

using sylva::mcnemarExact;
using sylva::wilcoxonSignedRank;
using sylva::wilsonInterval;

TEST_CASE("mcnemarExact is the two-sided binomial test of the discordant runs", "[consistency]") {
  CHECK(mcnemarExact(10, 2) == Approx(0.03857421875).epsilon(1e-12));
  CHECK(mcnemarExact(2, 10) == Approx(0.03857421875).epsilon(1e-12));
  CHECK(mcnemarExact(7, 7) == 1.0);
  CHECK(mcnemarExact(0, 5) == Approx(0.0625).epsilon(1e-12));
  CHECK(mcnemarExact(30, 12) == Approx(0.007915897334896727).epsilon(1e-10));
  CHECK(mcnemarExact(0, 0) == 1.0);
  CHECK(sylva_test::throwsCode([] { mcnemarExact(-1, 3); }, sylva::ErrorCode::kInvalidArgument));
}

TEST_CASE("wilcoxonSignedRank: exact without ties, normal with the tie correction otherwise", "[consistency]") {
  // Hollander and Wolfe's paired example (x - y of nine patients): W- = 5, so W+ = 45 - 5.
  const std::vector<double> nine = {0.952, -0.147, 1.022, 0.43, 0.62, 0.59, 0.49, -0.08, 0.01};
  auto r = wilcoxonSignedRank(nine);
  CHECK(r.exact);
  CHECK(r.n == 9);
  CHECK(r.w_plus == 40.0);
  CHECK(r.positive == 7);
  CHECK(r.negative == 2);
  CHECK(r.p_value == Approx(0.0390625).epsilon(1e-12));
  // Flipping every sign mirrors W+ and keeps p.
  std::vector<double> flipped;
  for (const double x : nine) flipped.push_back(-x);
  CHECK(wilcoxonSignedRank(flipped).w_plus == 5.0);
  CHECK(wilcoxonSignedRank(flipped).p_value == Approx(r.p_value).epsilon(1e-12));

  // 30 differences without ties: still exact.
  const std::vector<double> thirty = {0.645,   0.6407,  -0.8066, -0.27,   1.1504,  -0.5966, -0.0112, -0.2212,
                                      0.4092,  -0.5649, -0.3524, 0.0424,  -0.097,  -1.065,  0.6958,  -1.4985,
                                      -1.4011, -1.4825, 0.767,   -0.5606, -1.171,  -1.336,  0.2211,  -1.2548,
                                      -1.4721, 0.414,   -1.3967, -0.5224, -0.2068, -0.6453};
  r = wilcoxonSignedRank(thirty);
  CHECK(r.exact);
  CHECK(r.w_plus == 116.0);
  CHECK(r.p_value == Approx(0.015460003167390823).epsilon(1e-10));

  // 56 non-zero differences rounded to 0.1 (many ties) and two zeros, which are dropped.
  const std::vector<double> tied = {-0.5, -1.0, 0.1,  0.7,  1.4, 0.4,  -0.3, -0.5, 1.0,  1.9,  0.6,  -0.9, -0.7, 1.9, 0.5,
                                    -1.4, 0.2,  -0.9, -0.3, -0.2, -0.4, 0.9, 0.2,  -0.3, 0.7,  1.1,  -1.3, -0.7, 0.1, -1.0,
                                    0.3,  0.3,  -0.7, -0.1, -0.8, -1.1, 0.5, -0.8, 1.5,  1.0,  -1.7, 0.6,  -0.8, 0.3, 0.3,
                                    -1.7, 0.1,  1.3,  -0.9, 1.0,  -0.8, -0.5, 1.7, 0.9,  2.7,  0.9,  0.0,  0.0};
  r = wilcoxonSignedRank(tied);
  CHECK_FALSE(r.exact);
  CHECK(r.n == 56);
  CHECK(r.w_plus == 850.0);
  CHECK(r.p_value == Approx(0.6741834688548565).epsilon(1e-10));

  CHECK(wilcoxonSignedRank({0.0, 0.0}).p_value == 1.0);
  CHECK(wilcoxonSignedRank({}).n == 0);
  CHECK(sylva_test::throwsCode([] { wilcoxonSignedRank({1.0, std::numeric_limits<double>::quiet_NaN()}); },
                               sylva::ErrorCode::kInvalidArgument));
}

TEST_CASE("wilsonInterval: the score interval, clipped to 0 and 1 at the ends", "[consistency]") {
  auto [lo, hi] = wilsonInterval(81, 263);
  CHECK(lo == Approx(0.2552885198782742).epsilon(1e-9));
  CHECK(hi == Approx(0.36620957698280004).epsilon(1e-9));
  std::tie(lo, hi) = wilsonInterval(0, 10);
  CHECK(lo == 0.0);
  CHECK(hi == Approx(0.27753279986288926).epsilon(1e-9));
  std::tie(lo, hi) = wilsonInterval(10, 10);
  CHECK(lo == Approx(0.7224672001371109).epsilon(1e-9));
  CHECK(hi == Approx(1.0).epsilon(1e-12));
  std::tie(lo, hi) = wilsonInterval(27, 100);
  CHECK(lo == Approx(0.19269584149576344).epsilon(1e-9));
  CHECK(hi == Approx(0.36432116767945).epsilon(1e-9));
  CHECK(sylva_test::throwsCode([] { wilsonInterval(11, 10); }, sylva::ErrorCode::kInvalidArgument));
  CHECK(sylva_test::throwsCode([] { wilsonInterval(1, 0); }, sylva::ErrorCode::kInvalidArgument));
  CHECK(sylva_test::throwsCode([] { wilsonInterval(1, 10, 1.0); }, sylva::ErrorCode::kInvalidArgument));
}
