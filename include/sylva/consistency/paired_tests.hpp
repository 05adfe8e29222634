#pragma once
/// @file
/// Tests for comparing two estimators run on identical inputs, and the interval of a rate:
///
/// - `mcnemarExact`: did one converge more often than the other? Only the discordant runs
///   count (b: A converged and B did not, c: the reverse); under "no difference" b is
///   Binomial(b + c, 1/2), and the two-sided p-value is 2 P(X <= min(b, c)), capped at 1
///   (McNemar 1947; the exact form: Agresti, Categorical Data Analysis, 3rd ed., Sec. 11.1).
/// - `wilcoxonSignedRank`: is one error typically lower, run by run? Ranks |d_i| of the
///   non-zero differences (ties get their mean rank), W+ = sum of the ranks of d_i > 0. Exact
///   null distribution (all 2^n sign patterns, by counting) when n <= 50 and no |d| ties;
///   otherwise the normal approximation with the tie correction of the variance and a
///   continuity correction (Hollander, Wolfe, Chicken, Nonparametric Statistical Methods, 3rd
///   ed., Sec. 3.1).
/// - `wilsonInterval`: the score interval of a binomial proportion (Wilson 1927), which keeps
///   its coverage near 0 and 1 where the textbook p +- z sqrt(p (1 - p) / n) does not.
///
/// Uses Boost.Math (header-only); the filter itself needs only Eigen.

#include <algorithm>
#include <boost/math/distributions/binomial.hpp>
#include <boost/math/distributions/normal.hpp>
#include <cmath>
#include <cstddef>
#include <sstream>
#include <utility>
#include <vector>

#include "sylva/core/error.hpp"

namespace sylva {

/// Two-sided exact McNemar test: `a_only` runs where only A succeeded, `b_only` where only B
/// did. Returns the p-value (1 when there is no discordant run).
inline double mcnemarExact(long a_only, long b_only) {
  if (a_only < 0 || b_only < 0) {
    std::ostringstream os;
    os << "mcnemarExact: counts must be >= 0, got " << a_only << " and " << b_only;
    fail(ErrorCode::kInvalidArgument, os.str());
  }
  const long n = a_only + b_only;
  if (n == 0) return 1.0;
  const boost::math::binomial_distribution<double> null(static_cast<double>(n), 0.5);
  return std::min(1.0, 2.0 * boost::math::cdf(null, static_cast<double>(std::min(a_only, b_only))));
}

struct SignedRankResult {
  int n = 0;                 ///< non-zero differences (zeros are dropped)
  double w_plus = 0.0;       ///< sum of the ranks of the positive differences
  double p_value = 1.0;      ///< two-sided
  bool exact = false;        ///< exact null distribution, or the normal approximation
  int positive = 0;          ///< differences > 0
  int negative = 0;          ///< differences < 0
};

/// Two-sided Wilcoxon signed-rank test of "the differences are symmetric about 0". Throws
/// kInvalidArgument on a non-finite difference.
inline SignedRankResult wilcoxonSignedRank(const std::vector<double>& differences) {
  std::vector<double> d;
  for (const double x : differences) {
    if (!std::isfinite(x)) {
      std::ostringstream os;
      os << "wilcoxonSignedRank: a difference is not finite (" << x << ")";
      fail(ErrorCode::kInvalidArgument, os.str());
    }
    if (x != 0.0) d.push_back(x);
  }
  SignedRankResult r;
  r.n = static_cast<int>(d.size());
  if (r.n == 0) return r;
  std::sort(d.begin(), d.end(), [](double a, double b) { return std::abs(a) < std::abs(b); });
  // Mean ranks over runs of equal |d|; the tie term sum(t^3 - t) / 48 enters the variance.
  double tie_term = 0.0;
  bool ties = false;
  for (std::size_t i = 0; i < d.size();) {
    std::size_t j = i;
    while (j < d.size() && std::abs(d[j]) == std::abs(d[i])) ++j;
    const double rank = 0.5 * static_cast<double>(i + 1 + j);  // mean of ranks i+1 .. j
    const double t = static_cast<double>(j - i);
    if (j - i > 1) ties = true;
    tie_term += (t * t * t - t) / 48.0;
    for (std::size_t k = i; k < j; ++k) {
      if (d[k] > 0.0) {
        r.w_plus += rank;
        ++r.positive;
      } else {
        ++r.negative;
      }
    }
    i = j;
  }
  const double n = r.n;
  const double mean = n * (n + 1.0) / 4.0;
  if (!ties && r.n <= 50) {
    // counts[s]: sign patterns whose positive ranks sum to s (ranks 1..n, each in or out).
    const int max_sum = r.n * (r.n + 1) / 2;
    std::vector<double> counts(static_cast<std::size_t>(max_sum) + 1, 0.0);
    counts[0] = 1.0;
    for (int rank = 1; rank <= r.n; ++rank)
      for (int s = max_sum; s >= rank; --s) counts[static_cast<std::size_t>(s)] += counts[static_cast<std::size_t>(s - rank)];
    const double w = std::min(r.w_plus, n * (n + 1.0) / 2.0 - r.w_plus);  // the smaller tail
    double tail = 0.0;
    for (int s = 0; s <= static_cast<int>(std::floor(w)); ++s) tail += counts[static_cast<std::size_t>(s)];
    r.p_value = std::min(1.0, 2.0 * tail / std::ldexp(1.0, r.n));
    r.exact = true;
    return r;
  }
  const double variance = n * (n + 1.0) * (2.0 * n + 1.0) / 24.0 - tie_term;
  if (!(variance > 0.0)) return r;
  const double z = std::max(0.0, std::abs(r.w_plus - mean) - 0.5) / std::sqrt(variance);
  r.p_value = std::min(1.0, 2.0 * boost::math::cdf(boost::math::complement(boost::math::normal_distribution<double>(), z)));
  return r;
}

/// Wilson score interval of `successes` out of `trials` at `confidence` (two-sided).
inline std::pair<double, double> wilsonInterval(long successes, long trials, double confidence = 0.95) {
  if (trials <= 0 || successes < 0 || successes > trials || !(confidence > 0.0 && confidence < 1.0)) {
    std::ostringstream os;
    os << "wilsonInterval: need 0 <= successes <= trials, trials > 0 and 0 < confidence < 1, got " << successes
       << " of " << trials << " at " << confidence;
    fail(ErrorCode::kInvalidArgument, os.str());
  }
  const double z = boost::math::quantile(boost::math::normal_distribution<double>(), 0.5 * (1.0 + confidence));
  const double n = static_cast<double>(trials);
  const double p = static_cast<double>(successes) / n;
  const double centre = (p + z * z / (2.0 * n)) / (1.0 + z * z / n);
  const double half = z / (1.0 + z * z / n) * std::sqrt(p * (1.0 - p) / n + z * z / (4.0 * n * n));
  return {std::max(0.0, centre - half), std::min(1.0, centre + half)};
}

}  // namespace sylva
