#pragma once
/// @file
/// `detail::CompressedRegion`: the bookkeeping of the compressed EKF (Guivant and Nebot,
/// "Optimization of the simultaneous localization and map-building algorithm for real time
/// implementation", IEEE T-RA 17(3):242-257, 2001; cited by the multisensor thesis as [72]),
/// the kernel under `BasicEkf::setCompression` (filter/compression.hpp).
///
/// The state splits into an active part A, its first a coordinates (the robot and the
/// landmarks near it; the filter keeps them there), and a passive part B, the rest. While
/// every prediction moves only A and every update observes only A, the exact EKF changes the
/// rest in a way that folds into three accumulators of A's size:
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
/// and, with S = L L^T, G = L^-1 H_A phi (phi before the update) and W = K_A L = P_AA H_A^T L^-T
/// (the symmetric form's gain factor):
///
///   phi   <- J phi                          (predict)
///   theta <- theta + G^T L^-1 nu            (update)
///   psi   <- psi + G^T G
///   phi   <- phi - W G
///
/// (derived here from the update equations above, by induction over the local steps; the
/// paper's accumulators are the same up to how S^-1 is factored; psi stays positive
/// semi-definite by construction). A local step costs O(m a^2) here on top of the active
/// block's own O(m a^2) update, whatever the size of B; `globalUpdate` brings B up to date in
/// O(n^2 a), once, when the region changes. The result is the plain EKF's, up to round-off.
///
/// Scaled accumulators. The recurrences hold for any starting value phi_0 of phi, with P_AB0
/// replaced by phi_0^-1 P_AB0: nothing above uses phi = I at the start. That choice matters for
/// round-off. With phi_0 = I, psi collects H_A^T S^-1 H_A, which grows like 1/sigma^2 in the
/// directions a precise sensor pins down, while the stored rows V = P_BA0 are small in just
/// those directions: V psi V^T then comes out of cancellations between terms many orders of
/// magnitude larger than itself, and over a whole circle-world run at N = 2000 the state
/// drifted from the plain filter's several orders of magnitude further than round-off moves the
/// plain filter itself. So the first update of a region (`stageScale`, `commitScale`) takes
/// phi_0 = R, a Cholesky factor of P_AA (R R^T = P_AA): it multiplies phi (I, or I with the
/// region's predictions applied to its robot rows) by R on the right, while psi and theta are
/// still zero, and replaces the stored rows by V' = V R^-T. For a static A, R^T psi R = I -
/// R^-1 P_AA,posterior R^-T lies between 0 and I, and V' V'^T = P_BA P_AA^-1 P_AB <= P_BB:
/// every accumulator is then on the scale of the covariance. Any invertible R gives the same
/// estimates, so R is taken from P_AA plus a tiny multiple of I (a semi-definite P_AA, e.g. a
/// robot whose pose is known exactly, still has a factor), and from I if even that fails. Until
/// the region's next global update, the stored rows against A hold V', which the reads of B
/// below correct like V (they only ever see them through the accumulators).
///
/// A landmark that enters the state during a region joins A (`extend`): its stored
/// cross-covariance with B is zero, and its rows of phi, J_new phi_robot, carry the
/// dependence on B that it inherits from the robot.
///
/// The caller keeps x_A and P_AA up to date with the usual update equations, and leaves every
/// entry that involves B alone between `begin` and `globalUpdate`. Every change here is split
/// so that whatever can allocate comes first and changes nothing (`stageUpdate`,
/// `stageExtend`), and the commit cannot fail.

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <algorithm>
#include <cmath>

#include "sylva/core/parallel.hpp"
#include "sylva/core/types.hpp"
#include "sylva/detail/lower_rank_update.hpp"
#include "sylva/detail/workspace.hpp"

namespace sylva::detail {

/// A template only so that a translation unit that includes the filter but never compresses
/// compiles none of this (its members are instantiated on first use); use `CompressedRegion`.
template <typename = void>
class BasicCompressedRegion {
 public:
  /// Enters a region whose active part is the first `a` coordinates: phi = I, psi = 0,
  /// theta = 0. `stageBegin` allocates and changes nothing; `commitBegin` cannot fail.
  void stageBegin(int a) {
    resizeWorkspace(staged_phi_, a, a);
    resizeWorkspace(staged_psi_, a, a);
    resizeWorkspace(staged_theta_, a, 1);
    staged_phi_.setIdentity();
    staged_psi_.setZero();
    staged_theta_.setZero();
  }
  void commitBegin() {
    phi_.swap(staged_phi_);
    psi_.swap(staged_psi_);
    theta_.swap(staged_theta_);
    steps_ = 0;
    scaled_ = false;
  }
  void begin(int a) {
    stageBegin(a);
    commitBegin();
  }

  /// The size a of the active part.
  int activeDim() const { return static_cast<int>(phi_.rows()); }
  /// Local steps (predictions and updates) since `begin` or the last global update: while
  /// there are none, the stored state is up to date.
  long steps() const { return steps_; }
  /// Whether the accumulators (and the stored rows against A) are scaled by R: from the
  /// region's first scaled update (`commitScale`) to its next global update.
  bool scaled() const { return scaled_; }

  /// Stages the rescaling of the file comment ("Scaled accumulators") before the region's
  /// first update: R from the active block `P_AA` (its lower triangle is read), phi R, and the
  /// stored rows V' = V R^-T from `V` (the (n - a) x a block below A). Allowed only while no
  /// update has touched psi and theta since `begin` or the last global update (predictions
  /// may have: they only move phi). Workspaces only: the region is unchanged. Returns phi R,
  /// the phi the update being staged must use.
  template <typename ActiveBlock, typename StoredRows>
  const Eigen::MatrixXd& stageScale(const ActiveBlock& P_AA, const StoredRows& V) {
    const int a = activeDim();
    resizeWorkspace(scale_factor_, a, a);
    resizeWorkspace(staged_phi_, a, a);
    resizeWorkspace(scaled_rows_, V.rows(), a);
    if (scale_llt_.rows() != a) scale_llt_ = Eigen::LLT<Eigen::MatrixXd>(a);
    // R R^T = P_AA + tol I: tol makes a semi-definite P_AA factorizable (a known robot pose)
    // and changes no estimate (any invertible R does).
    scale_factor_ = P_AA.template selfadjointView<Eigen::Lower>();
    const double tol = 1e-12 * std::max(scale_factor_.diagonal().cwiseAbs().maxCoeff(), 1e-300);
    scale_factor_.diagonal().array() += tol;
    scale_llt_.compute(scale_factor_);
    if (scale_llt_.info() == Eigen::Success && scale_llt_.matrixLLT().allFinite()) {
      scale_factor_ = scale_llt_.matrixL();
    } else {
      scale_factor_.setIdentity();  // an indefinite P_AA: the unscaled accumulators
    }
    staged_phi_.noalias() = phi_ * scale_factor_.template triangularView<Eigen::Lower>();
    scaled_rows_ = V;
    scale_factor_.transpose().template triangularView<Eigen::Upper>().template solveInPlace<Eigen::OnTheRight>(
        scaled_rows_);  // V' R^T = V
    return staged_phi_;
  }
  /// Applies the staged rescaling: phi <- phi R, and the stored rows `V` (the block that was
  /// given to `stageScale`) <- V'. Allocates nothing.
  template <typename StoredRows>
  void commitScale(StoredRows&& V) {
    phi_.swap(staged_phi_);
    V = scaled_rows_;
    scaled_ = true;
  }


  /// A prediction that moves the robot's coordinates, the first R of A, by J and leaves the
  /// others where they are: phi <- J phi on those rows. Allocates nothing.
  template <int R>
  void predictRobot(const Mat<R, R>& J) {
    for (Eigen::Index j = 0; j < phi_.cols(); ++j) {
      const Vec<R> column = phi_.col(j).template head<R>();
      phi_.col(j).template head<R>() = J * column;
    }
    ++steps_;
  }

  /// (H_A phi)^T, a x cols, for the caller to fill before `stageUpdate` (the filter applies
  /// its H^T to phi^T). Grows its workspace, and phi^T's, if needed.
  Eigen::Map<Eigen::MatrixXd> hphiTransposed(int cols) {
    const int a = activeDim();
    return Eigen::Map<Eigen::MatrixXd>(grown(hphi_t_, static_cast<Eigen::Index>(a) * cols), a, cols);
  }
  /// phi^T (a x a), copied into a workspace, for the caller's H^T.
  Eigen::Map<Eigen::MatrixXd> phiTransposed() {
    const int a = activeDim();
    Eigen::Map<Eigen::MatrixXd> out(grown(phi_t_, static_cast<Eigen::Index>(a) * a), a, a);
    out = phi_.transpose();
    return out;
  }

  /// Computes an update's changes from (H_A phi)^T (`hphiTransposed`, filled), the Cholesky
  /// factor L of S, the innovation nu and the active block's gain: W = P_AA H_A^T L^-T (a x m,
  /// the symmetric form's) or, with `gain_is_k`, K_A = P_AA H_A^T S^-1 (the Joseph form's;
  /// K_A H_A phi = W G). `commitUpdate` applies them. Workspaces only: the region is unchanged.
  ///
  /// With G = L^-1 (H_A phi): psi += G^T G and phi -= W G (or K_A (H_A phi)). For a few rows
  /// (m <= kInPlaceRows, e.g. the scalar updates of a sequential fusion) these are m rank-one
  /// updates that `commitUpdate` applies in place, which allocate nothing. Staged as a x a
  /// products, each such update paid a GEMM call, the zeroing of its destination and two more
  /// passes over a x a: the local steps of a sequential fusion ran at about half the speed
  /// (bench/compressed_ekf.cpp, BM_WholeRunAgreement). More rows go through the staged products.
  template <typename LowerFactor, typename Nu, typename Gain>
  void stageUpdate(const LowerFactor& L, const Nu& nu, const Gain& gain, bool gain_is_k = false) {
    const int a = activeDim();
    const int m = static_cast<int>(nu.size());
    const Eigen::Index am = static_cast<Eigen::Index>(a) * m;
    Eigen::Map<Eigen::MatrixXd> Gt(hphi_t_.data(), a, m);
    const bool in_place = m <= kInPlaceRows;
    // phi -= left right^T, left and right a x m: (K_A, (H_A phi)^T) for the Joseph form,
    // (W, G^T) for the symmetric one.
    auto left = Eigen::Map<Eigen::MatrixXd>(grown(left_, am), a, m);
    left = gain;
    auto right = Eigen::Map<Eigen::MatrixXd>(grown(right_, am), a, m);
    if (gain_is_k) right = Gt;
    // G = L^-1 (H_A phi), kept transposed: G^T = (H_A phi)^T L^-T.
    L.transpose().template solveInPlace<Eigen::OnTheRight>(Gt);
    if (!gain_is_k) right = Gt;
    auto v = Eigen::Map<Eigen::VectorXd>(grown(v_, m), m);
    v = nu;
    L.solveInPlace(v);
    auto d_theta = Eigen::Map<Eigen::VectorXd>(grown(d_theta_, a), a);
    d_theta.noalias() = Gt * v;
    if (!in_place) {
      const Eigen::Index aa = static_cast<Eigen::Index>(a) * a;
      auto d_psi = Eigen::Map<Eigen::MatrixXd>(grown(d_psi_, aa), a, a);
      auto d_phi = Eigen::Map<Eigen::MatrixXd>(grown(d_phi_, aa), a, a);
      d_psi.noalias() = Gt * Gt.transpose();
      d_phi.noalias() = left * right.transpose();
    }
    staged_rows_ = m;
    in_place_ = in_place;
  }
  /// Applies the staged update. Allocates nothing.
  void commitUpdate() {
    const int a = activeDim();
    theta_ += Eigen::Map<const Eigen::VectorXd>(d_theta_.data(), a);
    if (in_place_) {
      const Eigen::Map<const Eigen::MatrixXd> Gt(hphi_t_.data(), a, staged_rows_);
      const Eigen::Map<const Eigen::MatrixXd> left(left_.data(), a, staged_rows_);
      const Eigen::Map<const Eigen::MatrixXd> right(right_.data(), a, staged_rows_);
      // Outer products of one column each: Eigen runs them column by column, in place.
      for (int c = 0; c < staged_rows_; ++c) {
        psi_.noalias() += Gt.col(c) * Gt.col(c).transpose();
        phi_.noalias() -= left.col(c) * right.col(c).transpose();
      }
    } else {
      psi_ += Eigen::Map<const Eigen::MatrixXd>(d_psi_.data(), a, a);
      phi_ -= Eigen::Map<const Eigen::MatrixXd>(d_phi_.data(), a, a);
    }
    ++steps_;
  }

  /// Stages A's growth by a landmark of d coordinates, appended to A, that depends on B only
  /// through the robot (its initialization reads the robot and a measurement): its rows of phi
  /// are J_robot phi_robot (J_robot: d x R), its stored cross-covariance with B is zero.
  /// Allocates the grown accumulators; `commitExtend` swaps them in.
  template <int R, typename JRobot>
  void stageExtend(const JRobot& J_robot) {
    const int a = activeDim();
    const auto d = J_robot.rows();
    resizeWorkspace(staged_phi_, a + d, a + d);
    resizeWorkspace(staged_psi_, a + d, a + d);
    resizeWorkspace(staged_theta_, a + d, 1);
    staged_phi_.setZero();
    staged_psi_.setZero();
    staged_theta_.setZero();
    staged_phi_.topLeftCorner(a, a) = phi_;
    staged_phi_.bottomLeftCorner(d, a).noalias() = J_robot * phi_.template topRows<R>();
    staged_psi_.topLeftCorner(a, a) = psi_;
    staged_theta_.head(a) = theta_;
  }
  /// Swaps in the staged accumulators. Allocates nothing.
  void commitExtend() {
    phi_.swap(staged_phi_);
    psi_.swap(staged_psi_);
    theta_.swap(staged_theta_);
    ++steps_;
  }

  /// Brings the passive part up to date, on the filter's storage: `P` holds the covariance in
  /// its lower triangle (n x n; its strictly upper part is neither read nor written) and `x`
  /// the mean, both with their A entries kept current by the caller. With V = P_BA0 (the
  /// stored (n - a) x a block below A):
  ///   x_B  += V theta
  ///   P_BB -= (V psi) V^T, on the lower triangle, through the filter's tiled kernel
  ///           (detail::subtractLowerProduct)
  ///   P_BA  = V phi^T.
  /// Everything is computed in workspaces before anything is written, so a failed allocation
  /// leaves P and x as they were. Then starts over in the same region.
  template <typename MatrixP, typename VectorX>
  void globalUpdate(MatrixP&& P, VectorX&& x, Parallel* parallel = nullptr) {
    const int a = activeDim();
    const Eigen::Index b = P.rows() - a;
    if (steps_ == 0) return;
    if (b > 0) {
      const auto V = P.block(a, 0, b, a);
      // P_BB -= (V psi) V^T directly, psi unfactored: a factor of psi (a pivoted LDLT, with
      // its round-off's negative pivots clamped, used before) missed V psi V^T at a loop
      // closure of the circle world by orders of magnitude more than the direct product.
      auto W = Eigen::Map<Eigen::MatrixXd>(grown(w_, b * a), b, a);
      W.noalias() = V * psi_;
      auto U = Eigen::Map<Eigen::MatrixXd>(grown(u_, b * a), b, a);
      U.noalias() = V * phi_.transpose();
      auto dx = Eigen::Map<Eigen::VectorXd>(grown(dx_, b), b);
      dx.noalias() = V * theta_;
      // Nothing below allocates.
      x.tail(b) += dx;
      subtractLowerProduct(P.bottomRightCorner(b, b), W, V, parallel);
      P.block(a, 0, b, a) = U;
    }
    phi_.setIdentity();
    psi_.setZero();
    theta_.setZero();
    steps_ = 0;
    scaled_ = false;
  }

  /// The current value of blocks that involve B, from the stored ones (for reads between
  /// global updates). `V_row` is the stored rows of B against A (rows x a) for a block of B:
  ///   x_B  = x_B0 + V theta,   P_BA = V phi^T,   P_BB' = P_BB'0 - V psi V'^T.
  template <typename V>
  auto passiveMeanCorrection(const V& V_rows) const { return V_rows * theta_; }
  template <typename V>
  auto passiveActiveBlock(const V& V_rows) const { return V_rows * phi_.transpose(); }
  template <typename V1, typename V2>
  auto passivePassiveCorrection(const V1& V_rows, const V2& V_cols) const {
    return V_rows * psi_ * V_cols.transpose();
  }

  /// The accumulators (for tests): phi (a x a), psi (a x a, symmetric), theta (a).
  const Eigen::MatrixXd& phi() const { return phi_; }
  const Eigen::MatrixXd& psi() const { return psi_; }
  const Eigen::VectorXd& theta() const { return theta_; }

 private:
  Eigen::MatrixXd phi_, psi_;
  Eigen::VectorXd theta_;
  long steps_ = 0;
  bool scaled_ = false;
  // Workspaces: they grow to the largest step (and state) seen and then stay.
  Eigen::VectorXd hphi_t_, phi_t_, v_, d_theta_, d_psi_, d_phi_;
  Eigen::MatrixXd staged_phi_, staged_psi_;
  Eigen::VectorXd staged_theta_;
  Eigen::VectorXd w_, u_, dx_;
  Eigen::MatrixXd scale_factor_, scaled_rows_;
  Eigen::LLT<Eigen::MatrixXd> scale_llt_;
  // What stageUpdate left for commitUpdate: its rows, the factors of phi's change (left_,
  // right_) and whether the changes are applied in place as rank-one updates (see stageUpdate).
  static constexpr int kInPlaceRows = 4;
  Eigen::VectorXd left_, right_;
  int staged_rows_ = 0;
  bool in_place_ = false;

  static double* grown(Eigen::VectorXd& buffer, Eigen::Index size) {
    growWorkspace(buffer, size);
    return buffer.data();
  }
};

using CompressedRegion = BasicCompressedRegion<>;

}  // namespace sylva::detail
