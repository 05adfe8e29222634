#pragma once
/// @file
/// The joint compatibility test of one association hypothesis (Neira & Tardos 2001, Sec. III):
/// `jointNis` and `jointlyCompatible`. `associateJcbb` searches over hypotheses with the same
/// statistic computed incrementally; these functions evaluate one hypothesis from scratch,
/// for checking a pairing from another source or inspecting what JCBB decided.
///
/// A hypothesis pairs measurement i with landmark j_i (or leaves it unpaired). Over its k
/// pairings, stack the innovations and build the joint innovation covariance
///
///   nu_H = [ z_1 (-) h_j1(x); ...; z_k (-) h_jk(x) ]                      (k d)
///   S_H  = H_H P H_H^T + blockdiag(R, ..., R),  block (a, b) = H_ja P H_jb^T (+ R if a = b)
///   D^2_H = nu_H^T S_H^-1 nu_H
///
/// The off-diagonal blocks are what individual compatibility (eq. 2.40 of the multisensor
/// thesis) ignores: all innovations share the robot's error, so they are correlated. H is
/// jointly compatible when D^2_H < chi2_{k d, p}. The empty hypothesis has D^2 = 0.
///
/// Cost: k linearizations, k (k + 1) / 2 cross-covariance blocks (each independent of the
/// state size) and one Cholesky factorization of the k d x k d matrix S_H: O(k^3 d^3).
///
/// Errors: hypothesis and measurements of different lengths or a gate probability outside
/// (0, 1) -> kInvalidArgument; a non-finite measurement -> kNonFinite; a paired id not in the
/// filter -> kUnknownId; S_H not positive definite -> kNotPositiveDefinite. Two measurements
/// paired with the same landmark are allowed here (independent observations of one landmark).

#include <optional>
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

/// D^2_H of the hypothesis `pairing` (pairing[i] = landmark of measurement i or nullopt).
template <class EkfT, class Model>
double jointNis(const EkfT& ekf,
                const Model& model,
                const std::vector<Vec<Model::kDim>>& measurements,
                const Gaussian<Model::kDim>& noise,
                const std::vector<std::optional<Id>>& pairing) {
  constexpr int M = Model::kDim;
  constexpr const char* kWho = "jointNis";
  if (pairing.size() != measurements.size()) {
    std::ostringstream os;
    os << kWho << ": the hypothesis has " << pairing.size() << " entries for "
       << measurements.size() << " measurements";
    fail(ErrorCode::kInvalidArgument, os.str());
  }
  detail::checkMeasurements(measurements, kWho);

  std::vector<Linearization<Model, EkfT::kRobotDim>> lins;
  std::vector<std::size_t> paired;
  for (std::size_t i = 0; i < pairing.size(); ++i) {
    if (!pairing[i]) continue;
    if (!ekf.contains(*pairing[i])) {
      std::ostringstream os;
      os << kWho << ": measurement " << i << " is paired with landmark id " << *pairing[i]
         << ", which is not in the filter";
      fail(ErrorCode::kUnknownId, os.str());
    }
    lins.push_back(ekf.linearize(model, *pairing[i]));
    paired.push_back(i);
  }
  const int k = static_cast<int>(paired.size());
  if (k == 0) return 0.0;

  Eigen::MatrixXd S(k * M, k * M);
  Eigen::VectorXd nu(k * M);
  for (int a = 0; a < k; ++a) {
    const auto ia = static_cast<std::size_t>(a);
    nu.segment<M>(a * M) = detail::residual(model, measurements[paired[ia]], lins[ia].z_hat);
    for (int b = 0; b <= a; ++b) {
      const Mat<M, M> block = ekf.crossCovariance(lins[ia], lins[static_cast<std::size_t>(b)]);
      S.block<M, M>(a * M, b * M) = block;
      S.block<M, M>(b * M, a * M) = block.transpose();
    }
    S.block<M, M>(a * M, a * M) += noise.covariance();
  }
  S = (0.5 * (S + S.transpose())).eval();
  const Eigen::LLT<Eigen::MatrixXd> llt(S);
  if (llt.info() != Eigen::Success || !S.allFinite())
    fail(ErrorCode::kNotPositiveDefinite,
         std::string(kWho) + ": joint innovation covariance is not positive definite");
  return llt.matrixL().solve(nu).squaredNorm();
}

/// True when D^2_H < chi2_{k d, p} for the k pairings of `pairing` (always true for k = 0).
template <class EkfT, class Model>
bool jointlyCompatible(const EkfT& ekf,
                       const Model& model,
                       const std::vector<Vec<Model::kDim>>& measurements,
                       const Gaussian<Model::kDim>& noise,
                       const std::vector<std::optional<Id>>& pairing,
                       double gate_probability = 0.99) {
  detail::checkGateProbability(gate_probability, "jointlyCompatible");
  const double d2 = jointNis(ekf, model, measurements, noise, pairing);
  int k = 0;
  for (const auto& p : pairing) k += p ? 1 : 0;
  if (k == 0) return true;
  return d2 < chiSquareGate(Model::kDim * k, gate_probability);
}

}  // namespace sylva
