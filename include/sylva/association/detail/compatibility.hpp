#pragma once
// IWYU pragma: private
/// @file
/// Internals shared by the association algorithms: input validation and the individual
/// compatibility table.
///
/// Individual compatibility (multisensor thesis eq. 2.40, Neira & Tardos 2001 eq. 6) of
/// measurement i with landmark j:
///
///   nu_ij = z_i (-) h_j(x),   S_j = H_j P H_j^T + R,   D^2_ij = nu_ij^T S_j^-1 nu_ij < chi2(d, p)
///
/// (The thesis prints Sigma_i where the inverse is meant.) S_j does not depend on the
/// measurement, so the table linearizes each candidate once and factors each S_j once:
/// O(c) linearizations and Cholesky factors plus O(m c) small solves for m measurements and
/// c candidates, independent of the state size because H_j has only two non-zero blocks.

#include <algorithm>
#include <sstream>
#include <string>
#include <unordered_set>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Core>

#include "sylva/consistency/chi_square.hpp"
#include "sylva/core/error.hpp"
#include "sylva/core/types.hpp"
#include "sylva/detail/model_traits.hpp"
#include "sylva/filter/linearization.hpp"
#include "sylva/noise/gaussian.hpp"

namespace sylva::detail {

/// Throws kInvalidArgument unless 0 < p < 1 (NaN fails too).
inline void checkGateProbability(double p, const char* who) {
  if (!(p > 0.0 && p < 1.0)) {
    std::ostringstream os;
    os << who << ": gate_probability = " << p << " must lie strictly between 0 and 1";
    fail(ErrorCode::kInvalidArgument, os.str());
  }
}

/// Every measurement finite (kNonFinite).
template <int M>
void checkMeasurements(const std::vector<Vec<M>>& measurements, const char* who) {
  for (std::size_t i = 0; i < measurements.size(); ++i) {
    if (!measurements[i].allFinite()) {
      std::ostringstream os;
      os << who << ": measurement " << i << " is not finite";
      fail(ErrorCode::kNonFinite, os.str());
    }
  }
}

/// Every candidate is in the filter (kUnknownId) and appears once (kInvalidArgument).
template <typename EkfT>
void checkCandidates(const EkfT& ekf, const std::vector<Id>& candidates, const char* who) {
  std::unordered_set<Id> seen;
  seen.reserve(candidates.size());
  for (const Id id : candidates) {
    if (!ekf.contains(id)) {
      std::ostringstream os;
      os << who << ": candidate landmark id " << id << " is not in the filter";
      fail(ErrorCode::kUnknownId, os.str());
    }
    if (!seen.insert(id).second) {
      std::ostringstream os;
      os << who << ": candidate landmark id " << id << " is listed more than once";
      fail(ErrorCode::kInvalidArgument, os.str());
    }
  }
}

/// The individual compatibility of every (measurement, candidate) pair.
template <typename Model, int RobotDim = Model::Robot::kDim>
struct IndividualCompatibility {
  static constexpr int kDim = Model::kDim;
  int measurement_count = 0;
  int candidate_count = 0;
  double gate = 0.0;                         ///< chi2(kDim, p)
  std::vector<Linearization<Model, RobotDim>> lins;  ///< one per candidate
  std::vector<Vec<kDim>> residuals;          ///< nu_ij at [i * candidate_count + j]
  Eigen::MatrixXd nis;                       ///< D^2_ij, measurement_count x candidate_count
  std::vector<std::vector<int>> compatible;  ///< per measurement: gated j by increasing D^2

  const Vec<kDim>& residual(int i, int j) const {
    return residuals[static_cast<std::size_t>(i * candidate_count + j)];
  }
};

/// Builds the table. Inputs must already be validated. A candidate of the wrong landmark
/// type makes `ekf.linearize` throw kWrongLandmarkType; an S_j that is not positive
/// definite throws kNotPositiveDefinite.
template <typename EkfT, typename Model>
IndividualCompatibility<Model, EkfT::kRobotDim> individualCompatibility(const EkfT& ekf,
                                                       const Model& model,
                                                       const std::vector<Vec<Model::kDim>>& z,
                                                       const Gaussian<Model::kDim>& noise,
                                                       const std::vector<Id>& candidates,
                                                       double gate_probability,
                                                       const char* who) {
  constexpr int M = Model::kDim;
  IndividualCompatibility<Model, EkfT::kRobotDim> ic;
  ic.measurement_count = static_cast<int>(z.size());
  ic.candidate_count = static_cast<int>(candidates.size());
  ic.gate = chiSquareGate(M, gate_probability);
  ic.lins.reserve(candidates.size());
  ic.residuals.resize(z.size() * candidates.size());
  ic.nis.resize(ic.measurement_count, ic.candidate_count);
  ic.compatible.assign(z.size(), {});

  for (int j = 0; j < ic.candidate_count; ++j) {
    ic.lins.push_back(ekf.linearize(model, candidates[static_cast<std::size_t>(j)]));
    const Linearization<Model, EkfT::kRobotDim>& lin = ic.lins.back();
    Mat<M, M> S = ekf.crossCovariance(lin, lin) + noise.covariance();
    S = (0.5 * (S + S.transpose())).eval();
    const Eigen::LLT<Mat<M, M>> llt(S);
    if (llt.info() != Eigen::Success || !S.allFinite()) {
      std::ostringstream os;
      os << who << ": innovation covariance of landmark " << candidates[static_cast<std::size_t>(j)]
         << " is not positive definite";
      fail(ErrorCode::kNotPositiveDefinite, os.str());
    }
    for (int i = 0; i < ic.measurement_count; ++i) {
      const Vec<M> nu = residual(model, z[static_cast<std::size_t>(i)], lin.z_hat);
      ic.residuals[static_cast<std::size_t>(i * ic.candidate_count + j)] = nu;
      const Vec<M> v = llt.matrixL().solve(nu);
      const double d2 = v.squaredNorm();
      ic.nis(i, j) = d2;
      if (d2 < ic.gate) ic.compatible[static_cast<std::size_t>(i)].push_back(j);
    }
  }
  for (int i = 0; i < ic.measurement_count; ++i) {
    std::vector<int>& list = ic.compatible[static_cast<std::size_t>(i)];
    std::stable_sort(
        list.begin(), list.end(), [&](int a, int b) { return ic.nis(i, a) < ic.nis(i, b); });
  }
  return ic;
}

}  // namespace sylva::detail
