#pragma once
/// @file
/// Monte Carlo consistency series: a statistic recorded per time step in each of N runs,
/// averaged over the runs, with the 95% (or any) acceptance interval of that average.
///
///   NeesSeries  run-averaged NEES or NIS per step (eq. 2.44): N * average ~ chi-square(N dof)
///   NmeeSeries  run-averaged normalized error per step and component (eq. 2.45): ~ N(0, 1/N)
///   NeesEnsemble  NEES of each run at each step: the ensemble average per step and its bounds,
///               each run's time average and their median (what examples/consistency reports)
///   NisTally    NIS samples of one measurement type, pooled: their mean against its bounds and
///               the share above a gate
///
///   NeesSeries series(3);                      // robot pose: 3 degrees of freedom
///   for (run...) for (step...) series.add(step, nees(error, P));
///   auto [lo, hi] = series.bounds();           // for the run-averaged value at each step
///   series.fractionInside();                   // share of steps whose average is inside

#include <boost/math/distributions/normal.hpp>
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <tuple>
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

/// NEES (or NIS) of each run of a Monte Carlo ensemble at each step. A run whose covariance
/// stopped being positive definite may record +inf (it diverged): the ensemble average of that
/// step is then +inf and outside any bound, and the run's time average is +inf, which a median
/// over runs tolerates and a mean does not. NaN and negative values are refused.
class NeesEnsemble {
 public:
  struct Summary {
    double mean;             ///< mean over steps of the ensemble average (eq. 2.44)
    double median_run;       ///< median over runs of each run's time average
    double lower, upper;     ///< two-sided bounds of the ensemble average of `runs` runs
    double fraction_inside;  ///< share of steps whose ensemble average lies inside its bounds
    int runs;                ///< runs recorded (the most at any step)
    int dof;
  };

  explicit NeesEnsemble(int dof) : dof_(dof) {
    if (dof <= 0) fail(ErrorCode::kInvalidArgument, "NeesEnsemble: dof must be > 0");
  }

  /// Records run `run`'s statistic at `step` (each pair at most once; any order).
  void add(int run, int step, double value) {
    if (run < 0 || step < 0) fail(ErrorCode::kInvalidArgument, "NeesEnsemble::add: negative run or step");
    if (std::isnan(value) || value < 0.0) {
      std::ostringstream os;
      os << "NeesEnsemble::add: run " << run << ", step " << step << ": " << value << " is not a NEES (NaN or negative)";
      fail(ErrorCode::kInvalidArgument, os.str());
    }
    if (run >= static_cast<int>(values_.size())) values_.resize(static_cast<std::size_t>(run) + 1);
    auto& row = values_[static_cast<std::size_t>(run)];
    if (step >= static_cast<int>(row.size())) row.resize(static_cast<std::size_t>(step) + 1, kMissing);
    if (!std::isnan(row[static_cast<std::size_t>(step)])) {
      std::ostringstream os;
      os << "NeesEnsemble::add: run " << run << " already has a value at step " << step;
      fail(ErrorCode::kInvalidArgument, os.str());
    }
    row[static_cast<std::size_t>(step)] = value;
  }

  int dof() const { return dof_; }

  /// Ensemble average at each step, over the runs that recorded it (NaN where none did), and
  /// how many did.
  std::vector<double> stepAverages(std::vector<int>* counts = nullptr) const {
    std::size_t steps = 0;
    for (const auto& row : values_) steps = std::max(steps, row.size());
    std::vector<double> sum(steps, 0.0);
    std::vector<int> count(steps, 0);
    for (const auto& row : values_)
      for (std::size_t k = 0; k < row.size(); ++k)
        if (!std::isnan(row[k])) sum[k] += row[k], ++count[k];
    for (std::size_t k = 0; k < steps; ++k) sum[k] = count[k] > 0 ? sum[k] / count[k] : kMissing;
    if (counts != nullptr) *counts = count;
    return sum;
  }

  /// Time average of each run that recorded anything.
  std::vector<double> runAverages() const {
    std::vector<double> out;
    for (const auto& row : values_) {
      double sum = 0.0;
      int n = 0;
      for (double v : row)
        if (!std::isnan(v)) sum += v, ++n;
      if (n > 0) out.push_back(sum / n);
    }
    return out;
  }

  /// The figures above; `confidence` sets the bounds (0.95: two-sided 95%).
  Summary summary(double confidence = 0.95) const {
    std::vector<int> counts;
    const std::vector<double> averages = stepAverages(&counts);
    std::vector<double> runs = runAverages();
    if (runs.empty()) fail(ErrorCode::kInvalidArgument, "NeesEnsemble::summary: no samples recorded");
    Summary s{};
    s.dof = dof_;
    s.runs = *std::max_element(counts.begin(), counts.end());
    std::tie(s.lower, s.upper) = averageChiSquareBounds(dof_, s.runs, confidence);
    double total = 0.0;
    int used = 0, inside = 0;
    for (std::size_t k = 0; k < averages.size(); ++k) {
      if (counts[k] == 0) continue;
      ++used;
      total += averages[k];
      const auto [lo, hi] = counts[k] == s.runs ? std::make_pair(s.lower, s.upper)
                                                : averageChiSquareBounds(dof_, counts[k], confidence);
      if (averages[k] >= lo && averages[k] <= hi) ++inside;
    }
    s.mean = total / used;
    s.fraction_inside = static_cast<double>(inside) / used;
    const auto mid = runs.begin() + static_cast<std::ptrdiff_t>(runs.size() / 2);
    std::nth_element(runs.begin(), mid, runs.end());
    s.median_run = *mid;
    if (runs.size() % 2 == 0) s.median_run = 0.5 * (s.median_run + *std::max_element(runs.begin(), mid));
    return s;
  }

 private:
  static constexpr double kMissing = std::numeric_limits<double>::quiet_NaN();
  int dof_;
  std::vector<std::vector<double>> values_;  // [run][step], NaN where not recorded
};

/// NIS samples of one measurement type pooled over steps and runs, kept as running sums (so a
/// tally is small, copyable and can be merged). For a consistent filter each sample is
/// chi-square(dof), so their mean lies inside `bounds()` (the bounds of an average of
/// `count()` independent samples: the innovations of a consistent filter are white) and the
/// share above the gate of probability p (`fractionAbove()`) is near 1 - p.
class NisTally {
 public:
  /// `gate_probability`: the chi-square quantile that `fractionAbove` counts exceedances of.
  explicit NisTally(int dof, double gate_probability = 0.95) : dof_(dof), probability_(gate_probability) {
    if (dof <= 0) fail(ErrorCode::kInvalidArgument, "NisTally: dof must be > 0");
    gate_ = chiSquareGate(dof, gate_probability);
  }
  void add(double nis) {
    if (!(nis >= 0.0) || !std::isfinite(nis)) {
      std::ostringstream os;
      os << "NisTally::add: " << nis << " is not a NIS (negative or not finite)";
      fail(ErrorCode::kInvalidArgument, os.str());
    }
    sum_ += nis;
    ++count_;
    if (nis > gate_) ++above_;
  }
  /// Adds the samples of `other`, which must have the same dof and gate probability.
  void merge(const NisTally& other) {
    if (other.dof_ != dof_ || other.probability_ != probability_)
      fail(ErrorCode::kInvalidArgument, "NisTally::merge: the tallies differ in dof or gate probability");
    sum_ += other.sum_;
    count_ += other.count_;
    above_ += other.above_;
  }
  int dof() const { return dof_; }
  long long count() const { return count_; }
  double mean() const { return count_ > 0 ? sum_ / static_cast<double>(count_) : std::numeric_limits<double>::quiet_NaN(); }
  /// Two-sided `confidence` interval of the mean of count() chi-square(dof) samples.
  std::pair<double, double> bounds(double confidence = 0.95) const {
    if (count_ == 0) fail(ErrorCode::kInvalidArgument, "NisTally::bounds: no samples recorded");
    const double n = static_cast<double>(count_);
    const double total = n * dof_;
    return {chiSquareQuantile(0.5 * (1.0 - confidence), total) / n, chiSquareQuantile(0.5 * (1.0 + confidence), total) / n};
  }
  /// Share of samples above the chi-square(dof) quantile of the gate probability.
  double fractionAbove() const {
    return count_ > 0 ? static_cast<double>(above_) / static_cast<double>(count_) : std::numeric_limits<double>::quiet_NaN();
  }
  double gateProbability() const { return probability_; }

 private:
  int dof_;
  double probability_;
  double gate_;
  double sum_ = 0.0;
  long long count_ = 0;
  long long above_ = 0;
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
