#pragma once
/// @file
/// Monte Carlo consistency series: a statistic recorded per time step in each of N runs,
/// averaged over the runs, with the 95% (or any) acceptance interval of that average.
///
///   NeesSeries  run-averaged NEES or NIS per step (eq. 2.44): N * average ~ chi-square(N dof)
///   NmeeSeries  run-averaged normalized error per step and component (eq. 2.45): ~ N(0, 1/N)
///
///   NeesSeries series(3);                      // robot pose: 3 degrees of freedom
///   for (run...) for (step...) series.add(step, nees(error, P));
///   auto [lo, hi] = series.bounds();           // for the run-averaged value at each step
///   series.fractionInside();                   // share of steps whose average is inside

#include <boost/math/distributions/normal.hpp>
#include <cmath>
#include <limits>
#include <sstream>
#include <utility>
#include <vector>

#include "sylva/consistency/chi_square.hpp"
#include "sylva/core/error.hpp"
#include "sylva/core/types.hpp"

namespace sylva {

/// Run-averaged chi-square statistic (NEES or NIS) per step.
class NeesSeries {
 public:
  /// `dof`: degrees of freedom of one sample (state or measurement dimension).
  explicit NeesSeries(int dof) : dof_(dof) {
    if (dof <= 0) fail(ErrorCode::kInvalidArgument, "NeesSeries: dof must be > 0");
  }

  /// Records the statistic of one run at `step` (steps may arrive in any order).
  void add(int step, double value) {
    if (step < 0) fail(ErrorCode::kInvalidArgument, "NeesSeries::add: negative step");
    if (!std::isfinite(value)) fail(ErrorCode::kNonFinite, "NeesSeries::add: value is not finite");
    if (step >= static_cast<int>(sum_.size())) {
      sum_.resize(step + 1, 0.0);
      count_.resize(step + 1, 0);
    }
    sum_[step] += value;
    count_[step] += 1;
  }

  int dof() const { return dof_; }
  int steps() const { return static_cast<int>(sum_.size()); }
  /// Number of runs: the smallest sample count over the recorded steps.
  int runs() const {
    int runs = 0;
    for (std::size_t k = 0; k < count_.size(); ++k) runs = k == 0 ? count_[k] : std::min(runs, count_[k]);
    return runs;
  }

  /// Run-averaged value at each step (eq. 2.44); steps never recorded are NaN.
  std::vector<double> averages() const {
    std::vector<double> out(sum_.size());
    for (std::size_t k = 0; k < sum_.size(); ++k)
      out[k] = count_[k] > 0 ? sum_[k] / count_[k] : std::numeric_limits<double>::quiet_NaN();
    return out;
  }

  /// Mean over steps of the run-averaged value.
  double mean() const {
    double total = 0.0;
    int used = 0;
    for (double a : averages())
      if (std::isfinite(a)) total += a, ++used;
    return used > 0 ? total / used : std::numeric_limits<double>::quiet_NaN();
  }

  /// Two-sided `confidence` interval of the run-averaged value at one step.
  std::pair<double, double> bounds(double confidence = 0.95) const {
    return averageChiSquareBounds(dof_, requireRuns(), confidence);
  }

  /// Share of steps whose run-averaged value lies inside `bounds(confidence)`.
  double fractionInside(double confidence = 0.95) const {
    const auto [lo, hi] = bounds(confidence);
    int inside = 0;
    int used = 0;
    for (double a : averages()) {
      if (!std::isfinite(a)) continue;
      ++used;
      if (a >= lo && a <= hi) ++inside;
    }
    return used > 0 ? static_cast<double>(inside) / used : 0.0;
  }

 private:
  int requireRuns() const {
    const int n = runs();
    if (n <= 0) fail(ErrorCode::kInvalidArgument, "NeesSeries: no samples recorded");
    return n;
  }
  int dof_;
  std::vector<double> sum_;
  std::vector<int> count_;
};

/// Run-averaged normalized estimation error per step and component (NMEE, eq. 2.45).
template <int N>
class NmeeSeries {
 public:
  void add(int step, const Vec<N>& normalized_error) {
    if (step < 0) fail(ErrorCode::kInvalidArgument, "NmeeSeries::add: negative step");
    if (!normalized_error.allFinite()) fail(ErrorCode::kNonFinite, "NmeeSeries::add: value is not finite");
    if (step >= static_cast<int>(sum_.size())) {
      sum_.resize(step + 1, Vec<N>::Zero());
      count_.resize(step + 1, 0);
    }
    sum_[step] += normalized_error;
    count_[step] += 1;
  }

  int steps() const { return static_cast<int>(sum_.size()); }

  /// Run-averaged normalized error at each step.
  std::vector<Vec<N>> averages() const {
    std::vector<Vec<N>> out(sum_.size());
    for (std::size_t k = 0; k < sum_.size(); ++k)
      out[k] = count_[k] > 0 ? Vec<N>(sum_[k] / count_[k]) : Vec<N>::Constant(std::numeric_limits<double>::quiet_NaN());
    return out;
  }

  /// Symmetric interval [-b, b] of an N(0, 1/runs) average: b = z_{(1+c)/2} / sqrt(runs).
  static std::pair<double, double> bounds(int runs, double confidence = 0.95) {
    if (runs <= 0 || !(confidence > 0.0 && confidence < 1.0))
      fail(ErrorCode::kInvalidArgument, "NmeeSeries::bounds: need runs > 0 and 0 < confidence < 1");
    const double z = boost::math::quantile(boost::math::normal_distribution<double>(), 0.5 * (1.0 + confidence));
    const double b = z / std::sqrt(static_cast<double>(runs));
    return {-b, b};
  }

 private:
  std::vector<Vec<N>> sum_;
  std::vector<int> count_;
};

}  // namespace sylva
