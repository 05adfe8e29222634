#pragma once
/// @file
/// `detail::CompressedRegion`: the bookkeeping of the compressed EKF (Guivant and Nebot,
/// "Optimization of the simultaneous localization and map-building algorithm for real time
/// implementation", IEEE T-RA 17(3):242-257, 2001; cited by the multisensor thesis as [72]),
/// the kernel under the filter's compressed policy (issue 19, part 2; not yet used by
/// `BasicEkf`).
///
/// The state splits into an active part A (the robot and the landmarks near it) and a passive
/// part B. While every prediction moves only A and every update observes only A, the exact
/// EKF changes the rest in a way that folds into three accumulators of A's size:
///
///   predict (A moves by J):    P_AB <- J P_AB
///   update  (H = [H_A 0]):     x_B  <- x_B  + P_BA H_A^T S^-1 nu
///                              P_AB <- (I - K_A H_A) P_AB
///                              P_BB <- P_BB - P_BA H_A^T S^-1 H_A P_AB
///
/// so that, with P_AB0, P_BB0 and x_B0 the values when the region was entered,
///
///   P_AB = phi P_AB0,   x_B = x_B0 + P_BA0 theta,   P_BB = P_BB0 - P_BA0 psi P_AB0,
///
///   phi   <- J phi                                  (predict)
///   theta <- theta + (H_A phi)^T S^-1 nu            (update, with phi before it)
///   psi   <- psi + (H_A phi)^T S^-1 (H_A phi)
///   phi   <- phi - K_A (H_A phi)
///
/// (derived here from the update equations above, by induction over the local steps; the
/// paper's accumulators are the same up to how S^-1 is factored). A local step costs
/// O(m a^2) here on top of the active block's own O(m a^2) update, whatever the size of B;
/// `globalUpdate` brings B up to date in O(n^2 a), once, when the region changes. The result
/// is the plain EKF's, up to round-off.
///
/// The caller keeps x_A and P_AA up to date with the usual update equations, and leaves every
/// entry that involves B alone between `begin` and `globalUpdate`.

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "sylva/core/parallel.hpp"
#include "sylva/detail/lower_rank_update.hpp"

namespace sylva::detail {

class CompressedRegion {
 public:
  /// Enters a region: `active` lists the state coordinates of A (each once, in any order; the
  /// order is that of every A-sized argument below). Allocates the accumulators.
  void begin(std::vector<int> active) {
    active_ = std::move(active);
    const auto a = static_cast<Eigen::Index>(active_.size());
    phi_ = Eigen::MatrixXd::Identity(a, a);
    psi_ = Eigen::MatrixXd::Zero(a, a);
    theta_ = Eigen::VectorXd::Zero(a);
    steps_ = 0;
  }

  const std::vector<int>& active() const { return active_; }
  int activeDim() const { return static_cast<int>(active_.size()); }
  /// Local steps (predictions and updates) since `begin`.
  long steps() const { return steps_; }

  /// A prediction that moves the active coordinates [offset, offset + J.rows()) by the
  /// Jacobian J and leaves the others where they are: phi <- J phi on those rows.
  template <typename Derived>
  void predict(int offset, const Eigen::MatrixBase<Derived>& J) {
    const auto r = J.rows();
    auto rows = workspace(rows_, r, phi_.cols());
    rows.noalias() = J * phi_.middleRows(offset, r);
    phi_.middleRows(offset, r) = rows;
    ++steps_;
  }

  /// An update that observes only A: H_A (m x a, in the order of `active()`), the active
  /// block's gain K_A = P_AA H_A^T S^-1 (a x m), the Cholesky factor of S and the innovation
  /// nu. It reads neither P_AA nor x_A, so it may come before or after the active block's own
  /// update.
  template <typename DerivedH, typename DerivedK, typename DerivedNu>
  void update(const Eigen::MatrixBase<DerivedH>& H_A, const Eigen::MatrixBase<DerivedK>& K_A,
              const Eigen::LLT<Eigen::MatrixXd>& S_llt, const Eigen::MatrixBase<DerivedNu>& nu) {
    const auto m = H_A.rows();
    auto Hphi = workspace(Hphi_, m, phi_.cols());
    auto SinvHphi = workspace(SinvHphi_, m, phi_.cols());
    auto Sinv_nu = workspace(Sinv_nu_, m, 1).col(0);
    Hphi.noalias() = H_A * phi_;
    SinvHphi = Hphi;
    S_llt.solveInPlace(SinvHphi);
    Sinv_nu = nu;
    S_llt.solveInPlace(Sinv_nu);
    theta_.noalias() += Hphi.transpose() * Sinv_nu;
    psi_.noalias() += Hphi.transpose() * SinvHphi;
    phi_.noalias() -= K_A * Hphi;
    ++steps_;
  }

  /// Brings the passive part up to date, on the filter's storage: `P` holds the covariance in
  /// its lower triangle (its strictly upper part is neither read nor written) and `x` the
  /// mean, both with their A-only entries kept current by the caller. With V = P_BA0 (n x a,
  /// the rows of A zero):
  ///   x   += V theta
  ///   P_BB -= V psi V^T, as P -= W W^T with W = V Q sqrt(D) from psi = Q D Q^T (LDLT with
  ///          pivoting; psi is a sum of positive semi-definite terms, so D >= 0 but for
  ///          round-off, which is clamped), through the filter's tiled lower rank update
  ///   P_BA = V phi^T.
  /// Everything is computed in workspaces before anything is written, so a failed allocation
  /// leaves P and x as they were. Then starts over in the same region.
  template <typename MatrixP, typename VectorX>
  void globalUpdate(MatrixP& P, VectorX& x, Parallel* parallel = nullptr) {
    const Eigen::Index n = P.rows();
    const auto a = static_cast<Eigen::Index>(active_.size());
    in_active_.assign(static_cast<std::size_t>(n), 0);
    for (int i : active_) in_active_[static_cast<std::size_t>(i)] = 1;
    const auto lower = [&P](Eigen::Index i, Eigen::Index j) { return i >= j ? P(i, j) : P(j, i); };
    auto V = workspace(V_, n, a);
    for (Eigen::Index k = 0; k < a; ++k)
      for (Eigen::Index i = 0; i < n; ++i) V(i, k) = in_active_[static_cast<std::size_t>(i)] ? 0.0 : lower(i, active_[k]);
    psi_ldlt_.compute(psi_);
    auto QsqrtD = workspace(QsqrtD_, a, a);
    QsqrtD = psi_ldlt_.matrixL();
    QsqrtD = psi_ldlt_.transpositionsP().transpose() * QsqrtD;
    for (Eigen::Index k = 0; k < a; ++k) QsqrtD.col(k) *= std::sqrt(std::max(0.0, psi_ldlt_.vectorD()[k]));
    auto W = workspace(W_, n, a);
    W.noalias() = V * QsqrtD;
    auto U = workspace(U_, n, a);
    U.noalias() = V * phi_.transpose();
    auto dx = workspace(dx_, n, 1).col(0);
    dx.noalias() = V * theta_;
    // Nothing below allocates.
    x += dx;
    subtractLowerRankUpdate(P.topLeftCorner(n, n), W, parallel);
    for (Eigen::Index k = 0; k < a; ++k) {
      const Eigen::Index j = active_[k];
      for (Eigen::Index i = 0; i < n; ++i) {
        if (in_active_[static_cast<std::size_t>(i)]) continue;
        (i >= j ? P(i, j) : P(j, i)) = U(i, k);
      }
    }
    phi_.setIdentity();
    psi_.setZero();
    theta_.setZero();
    steps_ = 0;
  }

  /// The accumulators (for tests): phi (a x a), psi (a x a, symmetric), theta (a).
  const Eigen::MatrixXd& phi() const { return phi_; }
  const Eigen::MatrixXd& psi() const { return psi_; }
  const Eigen::VectorXd& theta() const { return theta_; }

 private:
  std::vector<int> active_;
  Eigen::MatrixXd phi_, psi_;
  Eigen::VectorXd theta_;
  long steps_ = 0;
  // Workspaces: they grow to the largest step (and state) seen and then stay.
  Eigen::MatrixXd rows_, Hphi_, SinvHphi_, Sinv_nu_;
  Eigen::MatrixXd V_, W_, U_, dx_, QsqrtD_;
  Eigen::LDLT<Eigen::MatrixXd> psi_ldlt_;
  std::vector<char> in_active_;

  /// The top rows x cols corner of `storage`, grown if it is smaller.
  static Eigen::Block<Eigen::MatrixXd> workspace(Eigen::MatrixXd& storage, Eigen::Index rows, Eigen::Index cols) {
    if (storage.rows() < rows || storage.cols() != cols) storage.resize(std::max(rows, storage.rows()), cols);
    return storage.topRows(rows);
  }
};

}  // namespace sylva::detail
