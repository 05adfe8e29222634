#pragma once
/// @file
/// Error metrics of monocular SLAM after similarity alignment (tree-width thesis,
/// Sec. 4.1.2 and 4.2):
///
///   landmark error    e_l = 1/N sum_i |T(p_est,i) - p_true,i|^2            (eq. 4.2)
///   trajectory error  e_t = 1/N sum_k |T(t_est,k) - t_true,k|^2            (eq. 4.12)
///
/// Both are MEAN SQUARED distances (m^2 in the true map's units), as in the thesis, not RMS;
/// `rms` gives the square root for people. A run counts as converged when e_l < 10 and
/// e_t < 3 (Sec. 4.2, the saturation levels of eq. 4.16-4.17), `ConvergenceCriteria`.

#include <algorithm>
#include <cmath>
#include <vector>

#include "sylva/core/error.hpp"
#include "sylva/core/types.hpp"
#include "sylva/eval/similarity.hpp"

namespace sylva::eval {

/// 1/N sum |T(estimated_i) - truth_i|^2; throws kInvalidArgument for different sizes or no
/// points.
inline double meanSquaredError(const Similarity3& T,
                               const std::vector<Vec<3>>& estimated,
                               const std::vector<Vec<3>>& truth) {
  if (estimated.size() != truth.size() || truth.empty())
    fail(ErrorCode::kInvalidArgument, "meanSquaredError: need the same number (> 0) of estimated and true points, got " +
                                          std::to_string(estimated.size()) + " and " + std::to_string(truth.size()));
  double sum = 0.0;
  for (std::size_t i = 0; i < truth.size(); ++i) sum += (T(estimated[i]) - truth[i]).squaredNorm();
  return sum / static_cast<double>(truth.size());
}

inline double rms(double mean_squared_error) { return std::sqrt(mean_squared_error); }

/// Thresholds on e_l and e_t (m^2) under which a run counts as converged (thesis Sec. 4.2).
struct ConvergenceCriteria {
  double max_landmark_error = 10.0;
  double max_trajectory_error = 3.0;

  bool converged(double landmark_error, double trajectory_error) const {
    return landmark_error < max_landmark_error && trajectory_error < max_trajectory_error;
  }
};

/// The saturated average of eq. 4.16-4.17: 1/n sum max(-limit, -e_i) (<= 0; 0 is perfect).
inline double negativeSaturatedAverage(const std::vector<double>& errors, double limit) {
  if (errors.empty()) fail(ErrorCode::kInvalidArgument, "negativeSaturatedAverage: no errors given");
  double sum = 0.0;
  for (double e : errors) sum += std::max(-limit, -e);
  return sum / static_cast<double>(errors.size());
}

}  // namespace sylva::eval
