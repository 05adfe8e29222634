#pragma once
/// @file
/// `CompatibilityTable`: the individual compatibility of every (measurement, candidate) pair
/// at the filter's current estimate (multisensor thesis eq. 2.40; Neira & Tardos 2001 eq. 6):
///
///   nu_ij = z_i (-) h_j(x),   S_ij = H_j P H_j^T + R_i,   D^2_ij = nu_ij^T S_ij^-1 nu_ij < chi2(d, p)
///
/// (The thesis prints Sigma_i where the inverse is meant.) It is what nearest neighbour and
/// JCBB decide on, and it keeps what the rest of a SLAM step needs, so that each landmark is
/// linearized once per step: the linearization of every candidate (an `Ekf::update` can take
/// them instead of linearizing again), the innovations, the NIS matrix, and the smallest NIS
/// of each measurement for the new-landmark test.
///
/// Cost: c linearizations for c candidates, independent of the state size because H_j has
/// only two non-zero blocks; with one noise shared by all measurements one Cholesky factor
/// per candidate, with a noise per measurement one per pair; O(m c) small solves.
///
/// Errors: gate_probability outside (0, 1) -> kInvalidArgument; a non-finite measurement
/// -> kNonFinite; a candidate id not in the filter -> kUnknownId; a candidate listed twice
/// -> kInvalidArgument; a candidate of another parametrization than `Model::Landmark` ->
/// kWrongLandmarkType (from the filter); an S that is not positive definite ->
/// kNotPositiveDefinite; a noise list of another length than the measurements ->
/// kInvalidArgument. The filter is never changed.

#include <algorithm>
#include <limits>
#include <sstream>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Core>

#include "sylva/association/detail/compatibility.hpp"
#include "sylva/consistency/chi_square.hpp"
#include "sylva/core/error.hpp"
#include "sylva/core/types.hpp"
#include "sylva/detail/model_traits.hpp"
#include "sylva/filter/linearization.hpp"
#include "sylva/noise/gaussian.hpp"

namespace sylva {

template <typename Model, int RobotDim = Model::Robot::kDim>
struct CompatibilityTable {
  static constexpr int kDim = Model::kDim;
  using Lin = Linearization<Model, RobotDim>;

  std::vector<Id> candidates;
  int measurement_count = 0;
  int candidate_count = 0;
  double gate_probability = 0.0;
  double gate = 0.0;                          ///< chi2(kDim, gate_probability)
  std::vector<Lin> lins;                      ///< one per candidate, at the current estimate
  std::vector<Mat<kDim, kDim>> HPHt;          ///< H_j P H_j^T, one per candidate
  std::vector<Mat<kDim, kDim>> noise;         ///< R_i: one for all measurements, or one each
  std::vector<Vec<kDim>> residuals;           ///< nu_ij at [i * candidate_count + j]
  Eigen::MatrixXd nis;                        ///< D^2_ij, measurement_count x candidate_count
  std::vector<std::vector<int>> compatible;   ///< per measurement: gated j by increasing D^2

  const Vec<kDim>& residual(int i, int j) const {
    return residuals[static_cast<std::size_t>(i * candidate_count + j)];
  }
  const Mat<kDim, kDim>& noiseOf(int i) const { return noise[noise.size() == 1 ? 0 : static_cast<std::size_t>(i)]; }

  /// nu_ij and S_ij, formed exactly as `Ekf::innovation` forms them.
  Innovation<kDim> innovation(int i, int j) const {
    Innovation<kDim> out;
    out.nu = residual(i, j);
    out.S = HPHt[static_cast<std::size_t>(j)] + noiseOf(i);
    out.S = (0.5 * (out.S + out.S.transpose())).eval();
    return out;
  }

  /// The smallest NIS of measurement i over all candidates (gated or not), each computed as
  /// `Ekf::innovation(...).nis()` computes it: the number `smallestNis` gives, without
  /// linearizing again. +infinity without candidates.
  double smallestNis(int i) const {
    double smallest = std::numeric_limits<double>::infinity();
    for (int j = 0; j < candidate_count; ++j) smallest = std::min(smallest, innovation(i, j).nis());
    return smallest;
  }
};

namespace detail {

/// The covariance of each noise; kInvalidArgument unless there is one per measurement.
template <int M>
std::vector<Mat<M, M>> noiseCovariances(const std::vector<Gaussian<M>>& noises, std::size_t count, const char* who) {
  if (noises.size() != count) {
    std::ostringstream os;
    os << who << ": " << noises.size() << " noises for " << count
       << " measurements (one each, or one Gaussian for all)";
    fail(ErrorCode::kInvalidArgument, os.str());
  }
  std::vector<Mat<M, M>> R;
  R.reserve(noises.size());
  for (const Gaussian<M>& g : noises) R.push_back(g.covariance());
  return R;
}

template <typename EkfT, typename Model>
CompatibilityTable<Model, EkfT::kRobotDim> buildCompatibilityTable(const EkfT& ekf,
                                                                   const Model& model,
                                                                   const std::vector<Vec<Model::kDim>>& z,
                                                                   std::vector<Mat<Model::kDim, Model::kDim>> noise,
                                                                   const std::vector<Id>& candidates,
                                                                   double gate_probability,
                                                                   const char* who) {
  constexpr int M = Model::kDim;
  checkGateProbability(gate_probability, who);
  checkMeasurements(z, who);
  checkCandidates(ekf, candidates, who);
  CompatibilityTable<Model, EkfT::kRobotDim> t;
  t.candidates = candidates;
  t.measurement_count = static_cast<int>(z.size());
  t.candidate_count = static_cast<int>(candidates.size());
  t.gate_probability = gate_probability;
  t.gate = chiSquareGate(M, gate_probability);
  t.noise = std::move(noise);
  t.lins.reserve(candidates.size());
  t.HPHt.reserve(candidates.size());
  t.residuals.resize(z.size() * candidates.size());
  t.nis.resize(t.measurement_count, t.candidate_count);
  t.compatible.assign(z.size(), {});

  const auto factor = [&](const Mat<M, M>& HPHt, const Mat<M, M>& R, int j) {
    Mat<M, M> S = HPHt + R;
    S = (0.5 * (S + S.transpose())).eval();
    Eigen::LLT<Mat<M, M>> llt(S);
    if (llt.info() != Eigen::Success || !S.allFinite()) {
      std::ostringstream os;
      os << who << ": innovation covariance of landmark " << candidates[static_cast<std::size_t>(j)]
         << " is not positive definite";
      fail(ErrorCode::kNotPositiveDefinite, os.str());
    }
    return llt;
  };
  const auto test = [&](int i, int j, const Eigen::LLT<Mat<M, M>>& llt) {
    const Vec<M> nu = residual(model, z[static_cast<std::size_t>(i)], t.lins[static_cast<std::size_t>(j)].z_hat);
    t.residuals[static_cast<std::size_t>(i * t.candidate_count + j)] = nu;
    const Vec<M> v = llt.matrixL().solve(nu);
    const double d2 = v.squaredNorm();
    t.nis(i, j) = d2;
    if (d2 < t.gate) t.compatible[static_cast<std::size_t>(i)].push_back(j);
  };
  const bool shared = t.noise.size() == 1;
  for (int j = 0; j < t.candidate_count; ++j) {
    t.lins.push_back(ekf.linearize(model, candidates[static_cast<std::size_t>(j)]));
    t.HPHt.push_back(ekf.crossCovariance(t.lins.back(), t.lins.back()));
    const Mat<M, M>& HPHt = t.HPHt.back();
    if (shared) {  // S_j is the same for every measurement: one factor
      const Eigen::LLT<Mat<M, M>> llt = factor(HPHt, t.noise[0], j);
      for (int i = 0; i < t.measurement_count; ++i) test(i, j, llt);
    } else {
      for (int i = 0; i < t.measurement_count; ++i) test(i, j, factor(HPHt, t.noiseOf(i), j));
    }
  }
  for (int i = 0; i < t.measurement_count; ++i) {
    std::vector<int>& list = t.compatible[static_cast<std::size_t>(i)];
    std::stable_sort(list.begin(), list.end(), [&](int a, int b) { return t.nis(i, a) < t.nis(i, b); });
  }
  return t;
}

}  // namespace detail

/// The table for measurements that share one noise.
template <typename EkfT, typename Model>
CompatibilityTable<Model, EkfT::kRobotDim> compatibilityTable(const EkfT& ekf,
                                                              const Model& model,
                                                              const std::vector<Vec<Model::kDim>>& measurements,
                                                              const Gaussian<Model::kDim>& noise,
                                                              const std::vector<Id>& candidates,
                                                              double gate_probability = 0.99) {
  return detail::buildCompatibilityTable(ekf, model, measurements, {noise.covariance()}, candidates, gate_probability,
                                         "compatibilityTable");
}

/// The table with one noise per measurement (`noises[i]` for `measurements[i]`).
template <typename EkfT, typename Model>
CompatibilityTable<Model, EkfT::kRobotDim> compatibilityTable(const EkfT& ekf,
                                                              const Model& model,
                                                              const std::vector<Vec<Model::kDim>>& measurements,
                                                              const std::vector<Gaussian<Model::kDim>>& noises,
                                                              const std::vector<Id>& candidates,
                                                              double gate_probability = 0.99) {
  constexpr const char* kWho = "compatibilityTable";
  return detail::buildCompatibilityTable(ekf, model, measurements, detail::noiseCovariances(noises, measurements.size(), kWho),
                                         candidates, gate_probability, kWho);
}

}  // namespace sylva
