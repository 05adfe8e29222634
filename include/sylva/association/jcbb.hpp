#pragma once
/// @file
/// `associateJcbb`: joint compatibility branch and bound (Neira & Tardos 2001, "Data
/// association in stochastic mapping using the joint compatibility test", IEEE Trans.
/// Robotics and Automation 17(6), 890-897; the JCBB of the multisensor thesis, Sec. 2.2.2).
///
/// Problem. Pair m measurements with c candidate landmarks; a hypothesis H gives each
/// measurement one landmark or none, and uses each landmark at most once. JCBB returns the
/// hypothesis with the most pairings among those that are jointly compatible, and among
/// those with equally many pairings the one with the smallest joint NIS:
///
///   individual gate (eq. 2.40):  D^2_ij = nu_ij^T S_j^-1 nu_ij < chi2_{d, p}
///   joint gate:                  D^2_H  = nu_H^T S_H^-1 nu_H  < chi2_{k d, p}
///
/// with d = Model::kDim, k the number of pairings of H, nu_H the stacked innovations and
/// S_H = H_H P H_H^T + blockdiag(R) the joint innovation covariance whose off-diagonal blocks
/// H_ja P H_jb^T carry the correlation of all innovations through the robot (see
/// joint_compatibility.hpp). Nearest neighbour decides each pairing on D^2_ij alone; when the
/// robot is uncertain relative to the spacing of the landmarks every measurement may be
/// individually closest to a neighbour, while the pattern of the innovations, which the
/// joint test sees, reveals the wrong hypothesis.
///
/// Search. Depth-first over the measurements in their given order (the interpretation tree).
/// At level i the children are: each individually compatible, still unused candidate in
/// order of increasing D^2_ij, kept only if the extended hypothesis passes the joint gate;
/// then "measurement i unpaired". As in the original algorithm, a hypothesis is therefore
/// reached only if each of its partial hypotheses (its pairings taken in measurement order)
/// passed its own joint gate; the order of `measurements` can matter in rare borderline
/// cases. A subtree is cut when it cannot beat the best leaf so far:
///
///   bound = pairings(H) + min(measurements in [i, m) that still have an unused
///                             individually compatible candidate,
///                             candidates compatible with any measurement - pairings(H))
///   cut if bound < pairings(best), or bound = pairings(best) and D^2_H >= D^2_best.
///
/// The second cut is valid because D^2_H never decreases when a pairing is added (the new
/// term is a squared norm), so the smallest-NIS rule is exact, not a heuristic.
///
/// Joint NIS per node: incremental. The search keeps the lower Cholesky factor L of S_H and
/// y = L^-1 nu_H for the hypothesis on the current path. Appending pairing (i, j) with
/// cross block B = [H_j1 P H_j^T; ...; H_jk P H_j^T] and own block D = H_j P H_j^T + R:
///
///   X = L^-1 B,   L_22 = chol(D - X^T X),   y_new = L_22^-1 (nu_ij - X^T y),
///   D^2_{H + (i, j)} = D^2_H + |y_new|^2,   L <- [L 0; X^T L_22],  y <- [y; y_new].
///
/// This costs one triangular solve, O((k d)^2 d), instead of an O((k d)^3) refactorization.
/// All blocks H_a P H_b^T between candidates that gate with some measurement are computed
/// once before the search (each is independent of the state size).
///
/// Complexity. Setup: c linearizations, m c individual tests, r^2 / 2 cross blocks for the
/// r <= c candidates that gate with some measurement. Search: exponential in m in the worst
/// case (every measurement compatible with every candidate and no hypothesis jointly
/// compatible), O((k d)^2 d + m) per node. With a gate that separates landmarks the tree
/// stays small; it grows quickly when the robot's uncertainty spans several landmarks *and*
/// some measurements are clutter that gates individually, because the bound cannot tell in
/// advance that the clutter will never pair.
///
/// Errors: gate_probability outside (0, 1) -> kInvalidArgument; a non-finite measurement
/// -> kNonFinite; a candidate id not in the filter -> kUnknownId; a candidate listed twice
/// -> kInvalidArgument; a candidate of another parametrization than `Model::Landmark` ->
/// kWrongLandmarkType (from the filter); an innovation covariance S_j that is not positive
/// definite -> kNotPositiveDefinite. The filter is never changed.

#include <algorithm>
#include <optional>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Core>

#include "sylva/association/compatibility_table.hpp"
#include "sylva/consistency/chi_square.hpp"
#include "sylva/core/types.hpp"
#include "sylva/noise/gaussian.hpp"

namespace sylva {
namespace detail {

/// The branch-and-bound search over one individual compatibility table.
template <class Model, int RobotDim>
class JcbbSearch {
 public:
  static constexpr int kDim = Model::kDim;

  template <class EkfT>
  JcbbSearch(const EkfT& ekf,
             const CompatibilityTable<Model, RobotDim>& ic)
      : ic_(ic), m_(ic.measurement_count) {
    // Candidates that gate with at least one measurement, and their cross blocks.
    relevant_.assign(static_cast<std::size_t>(ic.candidate_count), -1);
    std::vector<int> members;
    for (const auto& list : ic.compatible)
      for (const int j : list)
        if (relevant_[static_cast<std::size_t>(j)] < 0) {
          relevant_[static_cast<std::size_t>(j)] = static_cast<int>(members.size());
          members.push_back(j);
        }
    relevant_count_ = static_cast<int>(members.size());
    cross_.resize(relevant_count_ * kDim, relevant_count_ * kDim);
    for (int a = 0; a < relevant_count_; ++a) {
      const auto& lin_a = ic.lins[static_cast<std::size_t>(members[static_cast<std::size_t>(a)])];
      for (int b = 0; b <= a; ++b) {
        const auto& lin_b = ic.lins[static_cast<std::size_t>(members[static_cast<std::size_t>(b)])];
        const Mat<kDim, kDim> block = ekf.crossCovariance(lin_a, lin_b);
        cross_.template block<kDim, kDim>(a * kDim, b * kDim) = block;
        cross_.template block<kDim, kDim>(b * kDim, a * kDim) = block.transpose();
      }
    }
    int gated_measurements = 0;
    for (const auto& list : ic.compatible) gated_measurements += list.empty() ? 0 : 1;
    const int max_pairings = std::min(gated_measurements, relevant_count_);
    gate_.assign(static_cast<std::size_t>(max_pairings) + 1, 0.0);
    for (int k = 1; k <= max_pairings; ++k)
      gate_[static_cast<std::size_t>(k)] = chiSquareGate(kDim * k, ic.gate_probability);

    L_.setZero(max_pairings * kDim, max_pairings * kDim);
    y_.setZero(max_pairings * kDim);
    X_.setZero(max_pairings * kDim, kDim);
    path_.assign(static_cast<std::size_t>(m_), -1);
    best_ = path_;
    paired_candidates_.assign(static_cast<std::size_t>(max_pairings), -1);
    used_.assign(static_cast<std::size_t>(ic.candidate_count), 0);
    gated_by_.assign(static_cast<std::size_t>(ic.candidate_count), {});
    available_.assign(static_cast<std::size_t>(m_), 0);
    for (int i = 0; i < m_; ++i) {
      const auto& list = ic.compatible[static_cast<std::size_t>(i)];
      available_[static_cast<std::size_t>(i)] = static_cast<int>(list.size());
      for (const int j : list) gated_by_[static_cast<std::size_t>(j)].push_back(i);
    }
  }

  /// Candidate index per measurement (-1: unpaired) of the best hypothesis.
  const std::vector<int>& run() {
    descend(0, 0, 0.0);
    return best_;
  }

 private:
  void descend(int i, int pairings, double nis) {
    int achievable = 0;  // later measurements that still have an unused compatible candidate
    for (int r = i; r < m_; ++r) achievable += available_[static_cast<std::size_t>(r)] > 0 ? 1 : 0;
    const int bound = pairings + std::min(achievable, relevant_count_ - pairings);
    if (bound < best_pairings_) return;
    if (bound == best_pairings_ && nis >= best_nis_) return;
    if (i == m_) {  // a leaf that passed the bound is strictly better than the best so far
      best_ = path_;
      best_pairings_ = pairings;
      best_nis_ = nis;
      return;
    }
    for (const int j : ic_.compatible[static_cast<std::size_t>(i)]) {
      if (used_[static_cast<std::size_t>(j)]) continue;
      double extended_nis = 0.0;
      if (!extend(i, j, pairings, nis, extended_nis)) continue;
      use(j, true);
      path_[static_cast<std::size_t>(i)] = j;
      paired_candidates_[static_cast<std::size_t>(pairings)] = j;
      descend(i + 1, pairings + 1, extended_nis);
      use(j, false);
      path_[static_cast<std::size_t>(i)] = -1;
    }
    descend(i + 1, pairings, nis);
  }

  /// Marks candidate j used (or free again) and updates the measurements it gates with.
  void use(int j, bool taken) {
    used_[static_cast<std::size_t>(j)] = taken ? 1 : 0;
    for (const int r : gated_by_[static_cast<std::size_t>(j)])
      available_[static_cast<std::size_t>(r)] += taken ? -1 : 1;
  }

  /// Joint test of the current hypothesis (k pairings, factor in the top-left k d block of
  /// L_) extended by (i, j). On success writes the new block row of L_ and of y_.
  bool extend(int i, int j, int k, double nis, double& extended_nis) {
    const int n = k * kDim;
    const int col = relevant_[static_cast<std::size_t>(j)] * kDim;
    auto X = X_.topRows(n);
    for (int a = 0; a < k; ++a) {
      const int row =
          relevant_[static_cast<std::size_t>(paired_candidates_[static_cast<std::size_t>(a)])] *
          kDim;
      X.template middleRows<kDim>(a * kDim) = cross_.template block<kDim, kDim>(row, col);
    }
    Mat<kDim, kDim> D = cross_.template block<kDim, kDim>(col, col) + ic_.noiseOf(i);
    Vec<kDim> w = ic_.residual(i, j);
    if (n > 0) {
      L_.topLeftCorner(n, n).template triangularView<Eigen::Lower>().solveInPlace(X);
      D.noalias() -= X.transpose() * X;
      w.noalias() -= X.transpose() * y_.head(n);
    }
    D = (0.5 * (D + D.transpose())).eval();
    const Eigen::LLT<Mat<kDim, kDim>> llt(D);
    if (llt.info() != Eigen::Success) return false;
    const Vec<kDim> v = llt.matrixL().solve(w);
    extended_nis = nis + v.squaredNorm();
    if (!(extended_nis < gate_[static_cast<std::size_t>(k) + 1])) return false;
    L_.block(n, 0, kDim, n) = X.transpose();
    L_.template block<kDim, kDim>(n, n) = llt.matrixL();
    y_.template segment<kDim>(n) = v;
    return true;
  }

  const CompatibilityTable<Model, RobotDim>& ic_;
  int m_;
  std::vector<int> relevant_;  ///< candidate -> block index in cross_, -1 if it never gates
  int relevant_count_ = 0;
  Eigen::MatrixXd cross_;     ///< H_a P H_b^T between relevant candidates
  std::vector<double> gate_;  ///< gate_[k] = chi2(k d, p)
  Eigen::MatrixXd L_;         ///< Cholesky factor of S_H along the current path
  Eigen::VectorXd y_;         ///< L^-1 nu_H along the current path
  Eigen::Matrix<double, Eigen::Dynamic, kDim> X_;
  std::vector<int> path_;               ///< candidate per measurement on the current path
  std::vector<int> paired_candidates_;  ///< candidate of the a-th pairing on the path
  std::vector<char> used_;
  std::vector<std::vector<int>> gated_by_;  ///< per candidate: measurements it gates with
  std::vector<int> available_;              ///< per measurement: unused candidates it gates with
  std::vector<int> best_;
  int best_pairings_ = 0;
  double best_nis_ = 0.0;
};

}  // namespace detail

/// JCBB on a compatibility table built at the filter's current estimate (the same filter).
template <class EkfT, class Model>
std::vector<std::optional<Id>> associateJcbb(const EkfT& ekf, const CompatibilityTable<Model, EkfT::kRobotDim>& ic) {
  std::vector<std::optional<Id>> pairing(static_cast<std::size_t>(ic.measurement_count), std::nullopt);
  if (ic.measurement_count == 0 || ic.candidate_count == 0) return pairing;
  detail::JcbbSearch<Model, EkfT::kRobotDim> search(ekf, ic);
  const std::vector<int>& best = search.run();
  for (std::size_t i = 0; i < best.size(); ++i)
    if (best[i] >= 0) pairing[i] = ic.candidates[static_cast<std::size_t>(best[i])];
  return pairing;
}

/// One noise for every measurement.
template <class EkfT, class Model>
std::vector<std::optional<Id>> associateJcbb(const EkfT& ekf,
                                             const Model& model,
                                             const std::vector<Vec<Model::kDim>>& measurements,
                                             const Gaussian<Model::kDim>& noise,
                                             const std::vector<Id>& candidates,
                                             double gate_probability = 0.99) {
  return associateJcbb(ekf, detail::buildCompatibilityTable(ekf, model, measurements, {noise.covariance()}, candidates,
                                                            gate_probability, "associateJcbb"));
}

/// One noise per measurement (`noises[i]` for `measurements[i]`; kInvalidArgument when the
/// sizes differ): the individual gates use S_ij = H_j P H_j^T + R_i and the joint test
/// blockdiag(R_i) of the paired measurements.
template <class EkfT, class Model>
std::vector<std::optional<Id>> associateJcbb(const EkfT& ekf,
                                             const Model& model,
                                             const std::vector<Vec<Model::kDim>>& measurements,
                                             const std::vector<Gaussian<Model::kDim>>& noises,
                                             const std::vector<Id>& candidates,
                                             double gate_probability = 0.99) {
  constexpr const char* kWho = "associateJcbb";
  return associateJcbb(ekf, detail::buildCompatibilityTable(ekf, model, measurements,
                                                            detail::noiseCovariances(noises, measurements.size(), kWho),
                                                            candidates, gate_probability, kWho));
}

}  // namespace sylva
