#pragma once
/// @file
/// `associateNearestNeighbor`: individual compatibility nearest neighbour (ICNN), the data
/// association of the multisensor thesis (Sec. 2.2.2, "Data Association", eq. 2.40).
///
/// Measurement i and candidate landmark j are individually compatible when the squared
/// Mahalanobis distance of the innovation passes the chi-square gate
///
///   nu_ij = z_i (-) h_j(x)   (model residual: bearing differences wrapped)
///   S_j   = H_j P H_j^T + R
///   D^2_ij = nu_ij^T S_j^-1 nu_ij  <  chi2_{d, p}        d = Model::kDim, p = gate_probability
///
/// (eq. 2.40 prints the covariance where its inverse is meant; the gate is the chi-square
/// quantile the thesis mentions, `chiSquareGate(d, p)`).
///
/// Conflicts: textbook ICNN lets two measurements take the same landmark. Here each landmark
/// is used at most once, resolved greedily: all gated pairs are visited in order of
/// increasing D^2 (ties: lower measurement index, then earlier candidate) and a pair is
/// accepted when neither its measurement nor its landmark is taken yet. A measurement
/// whose nearest landmark went to a closer measurement therefore falls back to its next
/// nearest gated landmark, or stays unpaired (`std::nullopt`) if none is left.
///
/// Limits: every pairing is decided on its own, ignoring that all innovations share the
/// robot's error. When the robot's uncertainty is comparable to the spacing of the landmarks
/// ICNN can pair every measurement with a neighbouring landmark; `associateJcbb` tests the
/// pairings jointly and avoids this (see jcbb.hpp).
///
/// Complexity: c linearizations and c Cholesky factors of S_j (independent of the state
/// size), m c small solves, and a sort of at most m c gated pairs, for m measurements and
/// c candidates.
///
/// Errors: gate_probability outside (0, 1) -> kInvalidArgument; a non-finite measurement
/// -> kNonFinite; a candidate id not in the filter -> kUnknownId; a candidate listed twice
/// -> kInvalidArgument; a candidate of another parametrization than `Model::Landmark` ->
/// kWrongLandmarkType (from the filter); an innovation covariance S_j that is not positive
/// definite -> kNotPositiveDefinite. The filter is never changed.

#include <algorithm>
#include <optional>
#include <tuple>
#include <vector>

#include "sylva/association/compatibility_table.hpp"
#include "sylva/core/types.hpp"
#include "sylva/noise/gaussian.hpp"

namespace sylva {

/// Nearest neighbour on a compatibility table built at the filter's current estimate.
template <class Model, int RobotDim>
std::vector<std::optional<Id>> associateNearestNeighbor(const CompatibilityTable<Model, RobotDim>& ic) {
  std::vector<std::optional<Id>> pairing(static_cast<std::size_t>(ic.measurement_count), std::nullopt);
  struct Gated {
    double nis;
    int measurement;
    int candidate;
  };
  std::vector<Gated> gated;
  for (int i = 0; i < ic.measurement_count; ++i)
    for (const int j : ic.compatible[static_cast<std::size_t>(i)])
      gated.push_back(Gated{ic.nis(i, j), i, j});
  std::sort(gated.begin(), gated.end(), [](const Gated& a, const Gated& b) {
    return std::tie(a.nis, a.measurement, a.candidate) <
           std::tie(b.nis, b.measurement, b.candidate);
  });

  std::vector<char> landmark_taken(ic.candidates.size(), 0);
  for (const Gated& g : gated) {
    const auto i = static_cast<std::size_t>(g.measurement);
    const auto j = static_cast<std::size_t>(g.candidate);
    if (pairing[i] || landmark_taken[j]) continue;
    pairing[i] = ic.candidates[j];
    landmark_taken[j] = 1;
  }
  return pairing;
}

/// One noise for every measurement.
template <class EkfT, class Model>
std::vector<std::optional<Id>> associateNearestNeighbor(const EkfT& ekf,
                                                        const Model& model,
                                                        const std::vector<Vec<Model::kDim>>& measurements,
                                                        const Gaussian<Model::kDim>& noise,
                                                        const std::vector<Id>& candidates,
                                                        double gate_probability = 0.99) {
  return associateNearestNeighbor(detail::buildCompatibilityTable(ekf, model, measurements, {noise.covariance()},
                                                                  candidates, gate_probability,
                                                                  "associateNearestNeighbor"));
}

/// One noise per measurement (`noises[i]` for `measurements[i]`; kInvalidArgument when the
/// sizes differ): S_ij = H_j P H_j^T + R_i.
template <class EkfT, class Model>
std::vector<std::optional<Id>> associateNearestNeighbor(const EkfT& ekf,
                                                        const Model& model,
                                                        const std::vector<Vec<Model::kDim>>& measurements,
                                                        const std::vector<Gaussian<Model::kDim>>& noises,
                                                        const std::vector<Id>& candidates,
                                                        double gate_probability = 0.99) {
  constexpr const char* kWho = "associateNearestNeighbor";
  return associateNearestNeighbor(detail::buildCompatibilityTable(
      ekf, model, measurements, detail::noiseCovariances(noises, measurements.size(), kWho), candidates,
      gate_probability, kWho));
}

}  // namespace sylva
