#pragma once
/// @file
/// Chi-square quantiles and the two-sided acceptance interval of a Monte Carlo average
/// (Bar-Shalom, Li, Kirubarajan 2001, Sec. 5.4; multisensor thesis "Consistency Analysis").
/// Uses Boost.Math (header-only); the filter itself needs only Eigen.

#include <boost/math/distributions/chi_squared.hpp>
#include <sstream>
#include <utility>

#include "sylva/core/error.hpp"

namespace sylva {

/// The p-quantile of the chi-square distribution with `dof` degrees of freedom.
template <int = 0>  // compiled only where called (docs/build-time.md)
double chiSquareQuantile(double p, double dof) {
  if (!(p > 0.0 && p < 1.0) || !(dof > 0.0)) {
    std::ostringstream os;
    os << "chiSquareQuantile: need 0 < p < 1 and dof > 0, got p = " << p << ", dof = " << dof;
    fail(ErrorCode::kInvalidArgument, os.str());
  }
  return boost::math::quantile(boost::math::chi_squared_distribution<double>(dof), p);
}

/// Two-sided `confidence` interval [lo, hi] for the average over `runs` independent runs of a
/// chi-square(dof) statistic (NEES or NIS): runs * average ~ chi-square(runs * dof), so
/// lo = chi2inv((1 - c) / 2, runs dof) / runs and hi = chi2inv((1 + c) / 2, runs dof) / runs.
template <int = 0>  // compiled only where called (docs/build-time.md)
std::pair<double, double> averageChiSquareBounds(int dof, int runs, double confidence = 0.95) {
  if (dof <= 0 || runs <= 0) {
    std::ostringstream os;
    os << "averageChiSquareBounds: need dof > 0 and runs > 0, got dof = " << dof << ", runs = " << runs;
    fail(ErrorCode::kInvalidArgument, os.str());
  }
  const double total = static_cast<double>(dof) * runs;
  return {chiSquareQuantile(0.5 * (1.0 - confidence), total) / runs,
          chiSquareQuantile(0.5 * (1.0 + confidence), total) / runs};
}

/// Gate for individual compatibility: an innovation of dimension `dof` is accepted when its
/// NIS is below the `probability` quantile (e.g. 0.95 or 0.99).
template <int = 0>  // compiled only where called (docs/build-time.md)
double chiSquareGate(int dof, double probability = 0.95) {
  return chiSquareQuantile(probability, static_cast<double>(dof));
}

}  // namespace sylva
