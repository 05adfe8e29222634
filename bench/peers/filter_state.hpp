#pragma once
/// @file
/// A filter's state in a form both peers can hand out and take back: the mean, the full
/// covariance and the landmark id of every 2-D block, in state order. Plus the comparison
/// the agreement checks use (landmarks matched by id, not by position in the state).

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <unordered_map>
#include <vector>

#include "sylva/core/angles.hpp"
#include "sylva/core/types.hpp"

namespace sylva_peers {

struct FilterState {
  Eigen::VectorXd mean;               ///< [x, y, theta, l0x, l0y, l1x, ...]
  Eigen::MatrixXd cov;                ///< full, both triangles
  std::vector<sylva::Id> ids;         ///< ids[i]: landmark at rows 3 + 2i, 3 + 2i + 1
};

/// The state of a sylva 2-D filter (robot [x, y, theta], Point2 landmarks).
template <typename Filter>
FilterState stateOf(const Filter& ekf) {
  FilterState s;
  s.mean = ekf.mean();
  s.cov = ekf.covariance();
  s.ids.reserve(ekf.slots().size());
  for (const auto& slot : ekf.slots()) s.ids.push_back(slot.id);
  return s;
}

/// How far apart two states are. Landmarks are matched by id.
struct StateDifference {
  bool same_landmarks = true;       ///< the same set of ids
  double max_mean = 0.0;            ///< max |a - b| over the mean (heading wrapped)
  double max_robot_mean = 0.0;      ///< the same over [x, y, theta] only
  double max_cov = 0.0;             ///< max |P_a - P_b| over all entries
  double max_cov_relative = 0.0;    ///< max_cov / max |P_a|
  std::string why;                  ///< what differs when same_landmarks is false

  std::string summary() const {
    std::ostringstream os;
    os.precision(3);
    if (!same_landmarks) return "different maps: " + why;
    os << "max |mean diff| = " << max_mean << " (robot " << max_robot_mean << "), max |cov diff| = " << max_cov
       << " (" << max_cov_relative << " of max |P|)";
    return os.str();
  }
};

inline StateDifference compareStates(const FilterState& a, const FilterState& b) {
  StateDifference d;
  if (a.ids.size() != b.ids.size() || a.mean.size() != b.mean.size()) {
    d.same_landmarks = false;
    d.why = std::to_string(a.ids.size()) + " vs " + std::to_string(b.ids.size()) + " landmarks";
    return d;
  }
  // perm[i]: the block of b that holds a's landmark i.
  std::unordered_map<sylva::Id, int> where;
  for (std::size_t j = 0; j < b.ids.size(); ++j) where.emplace(b.ids[j], static_cast<int>(j));
  const int n = static_cast<int>(a.mean.size());
  std::vector<int> row(static_cast<std::size_t>(n));  // row of b for row i of a
  for (int i = 0; i < 3; ++i) row[static_cast<std::size_t>(i)] = i;
  for (std::size_t i = 0; i < a.ids.size(); ++i) {
    const auto it = where.find(a.ids[i]);
    if (it == where.end()) {
      d.same_landmarks = false;
      d.why = "landmark " + std::to_string(a.ids[i]) + " is missing from the second state";
      return d;
    }
    for (int k = 0; k < 2; ++k)
      row[static_cast<std::size_t>(3 + 2 * i + k)] = 3 + 2 * it->second + k;
  }
  for (int i = 0; i < n; ++i) {
    double diff = a.mean[i] - b.mean[row[static_cast<std::size_t>(i)]];
    if (i == 2) diff = sylva::wrapAngle(diff);
    d.max_mean = std::max(d.max_mean, std::abs(diff));
    if (i < 3) d.max_robot_mean = std::max(d.max_robot_mean, std::abs(diff));
  }
  double max_p = 0.0;
  for (int j = 0; j < n; ++j) {
    const int bj = row[static_cast<std::size_t>(j)];
    for (int i = 0; i < n; ++i) {
      d.max_cov = std::max(d.max_cov, std::abs(a.cov(i, j) - b.cov(row[static_cast<std::size_t>(i)], bj)));
      max_p = std::max(max_p, std::abs(a.cov(i, j)));
    }
  }
  d.max_cov_relative = max_p > 0.0 ? d.max_cov / max_p : d.max_cov;
  return d;
}

/// Only the means (O(n)): for checking every timed run cheaply.
inline double maxMeanDifference(const Eigen::VectorXd& a,
                                const std::vector<sylva::Id>& ids_a,
                                const Eigen::VectorXd& b,
                                const std::vector<sylva::Id>& ids_b) {
  if (a.size() != b.size() || ids_a != ids_b) return HUGE_VAL;  // same order expected here
  double worst = std::abs(sylva::wrapAngle(a[2] - b[2]));
  for (Eigen::Index i = 0; i < a.size(); ++i)
    if (i != 2) worst = std::max(worst, std::abs(a[i] - b[i]));
  return worst;
}

}  // namespace sylva_peers
