#pragma once
/// @file
/// `DenseReferenceEkf`: the textbook EKF-SLAM written with full dense matrices, exactly as
/// the equations read (multisensor thesis eq. 2.22-2.39): a dense n x n F, a dense m x n H,
/// K = P H^T S^-1 and P = (I - K H) P; augmentation by the full Jacobian of eq. 2.36.
/// It is O(n^3) per update and allocates freely: it exists to check `sylva::Ekf` against
/// (tests) and to be the naive baseline it is timed against (bench/). Models written for a
/// pose view (`Pose2D`, `Pose3D`) see the robot through it, as in the filter.

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/LU>

#include "sylva/core/types.hpp"
#include "sylva/detail/model_traits.hpp"
#include "sylva/diff/evaluate.hpp"

namespace sylva::testing {

template <typename Robot>
struct DenseReferenceEkf {
  static constexpr int kRobotDim = Robot::kDim;
  Robot robot;
  Eigen::VectorXd x;  ///< [robot, landmark blocks...]
  Eigen::MatrixXd P;  ///< full symmetric covariance

  int dim() const { return static_cast<int>(x.size()); }

  /// Sigma^- = F Sigma F^T + G Sigma_u G^T with F, G dense over the whole state (2.22-2.26).
  template <int U, int N>
  void predict(const Vec<U>& u, double dt, const Mat<N, N>& noise_covariance) {
    const int n = dim();
    Mat<kRobotDim, kRobotDim> F_r;
    Mat<kRobotDim, N> G_r;
    const Vec<kRobotDim> next = robot(x.template head<kRobotDim>().eval(), u, dt, F_r, G_r);
    Eigen::MatrixXd F = Eigen::MatrixXd::Identity(n, n);
    F.topLeftCorner(kRobotDim, kRobotDim) = F_r;
    Eigen::MatrixXd G = Eigen::MatrixXd::Zero(n, N);
    G.topRows(kRobotDim) = G_r;
    x.template head<kRobotDim>() = next;
    P = F * P * F.transpose() + G * noise_covariance * G.transpose();
  }

  /// Dense H (m x n) of `model` for the landmark block at `offset`.
  template <typename Model>
  Eigen::MatrixXd jacobian(const Model& model, int offset, Vec<Model::kDim>* z_hat = nullptr) const {
    constexpr int M = Model::kDim;
    constexpr int L = Model::Landmark::kDim;
    Mat<M, kRobotDim> J_x;
    Mat<M, L> J_l;
    const Vec<M> predicted = detail::evaluateOn<Robot>(model, x.template head<kRobotDim>().eval(),
                                                       x.template segment<L>(offset).eval(), J_x, J_l);
    if (z_hat) *z_hat = predicted;
    Eigen::MatrixXd H = Eigen::MatrixXd::Zero(M, dim());
    H.leftCols(kRobotDim) = J_x;
    H.middleCols(offset, L) = J_l;
    return H;
  }

  /// x += K nu, P = (I - K H) P with K = P H^T S^-1 (2.28-2.32).
  template <typename Model>
  void update(const Model& model, int offset, const Vec<Model::kDim>& z, const Mat<Model::kDim, Model::kDim>& R) {
    Vec<Model::kDim> z_hat;
    const Eigen::MatrixXd H = jacobian(model, offset, &z_hat);
    const Eigen::VectorXd nu = detail::residual(model, z, z_hat);
    updateLinear(H, nu, R);
  }

  /// The linear update for a given dense H and innovation (used for batches too).
  void updateLinear(const Eigen::MatrixXd& H, const Eigen::VectorXd& nu, const Eigen::MatrixXd& R) {
    const int n = dim();
    const Eigen::MatrixXd S = H * P * H.transpose() + R;
    const Eigen::MatrixXd K = P * H.transpose() * S.inverse();
    x += K * nu;
    P = (Eigen::MatrixXd::Identity(n, n) - K * H) * P;
  }

  /// Augmentation by the full Jacobian of eq. 2.35-2.36 (new block appended).
  template <typename Inverse>
  void add(const Inverse& inverse, const Vec<Inverse::kMeasurementDim>& z,
           const Mat<Inverse::kMeasurementDim, Inverse::kMeasurementDim>& R) {
    constexpr int L = Inverse::Landmark::kDim;
    constexpr int Z = Inverse::kMeasurementDim;
    const int n = dim();
    Mat<L, kRobotDim> J_l_x;
    Mat<L, Z> J_l_z;
    const Vec<L> l = detail::initializeOn<Robot>(inverse, x.template head<kRobotDim>().eval(), z, J_l_x, J_l_z);
    Eigen::MatrixXd P_star = Eigen::MatrixXd::Zero(n + Z, n + Z);  // (2.34)
    P_star.topLeftCorner(n, n) = P;
    P_star.bottomRightCorner(Z, Z) = R;
    Eigen::MatrixXd J = Eigen::MatrixXd::Zero(n + L, n + Z);  // (2.36)
    J.topLeftCorner(n, n).setIdentity();
    J.block(n, 0, L, kRobotDim) = J_l_x;
    J.block(n, n, L, Z) = J_l_z;
    P = J * P_star * J.transpose();  // (2.35)
    x.conservativeResize(n + L);
    x.tail(L) = l;
  }

  /// Mirrors what the filter does after an update for a robot with a normalization (the
  /// quaternion of ConstantVelocity3D): the robot block is renormalized and the covariance
  /// carried through `Robot::normalizationJacobian`. Call it after `update` or `add`.
  void renormalizeRobot() {
    static_assert(detail::HasNormalizationJacobian<Robot>::value, "this robot has no normalization to mirror");
    const Vec<kRobotDim> robot_state = x.template head<kRobotDim>();
    Eigen::MatrixXd J = Eigen::MatrixXd::Identity(dim(), dim());
    J.template topLeftCorner<kRobotDim, kRobotDim>() = Robot::normalizationJacobian(robot_state);
    P = J * P * J.transpose();
    Vec<kRobotDim> normalized = robot_state;
    Robot::normalize(normalized);
    x.template head<kRobotDim>() = normalized;
  }

  /// Deletes rows and columns [offset, offset + d).
  void remove(int offset, int d) {
    const int n = dim();
    Eigen::VectorXi keep(n - d);
    for (int i = 0, k = 0; i < n; ++i)
      if (i < offset || i >= offset + d) keep[k++] = i;
    x = x(keep).eval();
    P = P(keep, keep).eval();
  }

  /// Replaces the block at `offset` by `conversion` of it, moved to the end of the state,
  /// with the covariance carried through the full Jacobian.
  template <typename Conversion>
  void reparametrize(int offset, const Conversion& conversion) {
    constexpr int F = Conversion::From::kDim;
    constexpr int T = Conversion::To::kDim;
    const int n = dim();
    Mat<T, kRobotDim> J_x;
    Mat<T, F> J_l;
    const Vec<F> from = x.template segment<F>(offset);
    const Vec<T> y = detail::throughRobotView<detail::ConversionRobotT<Conversion, Robot>, Robot>(
        x.template head<kRobotDim>().eval(), J_x, [&](const auto& view, auto& J_view) { return conversion(view, from, J_view, J_l); });
    // Full Jacobian of [state without block; y] w.r.t. the old state.
    Eigen::MatrixXd J = Eigen::MatrixXd::Zero(n - F + T, n);
    for (int i = 0, r = 0; i < n; ++i)
      if (i < offset || i >= offset + F) J(r++, i) = 1.0;
    J.block(n - F, 0, T, kRobotDim) = J_x;
    J.block(n - F, offset, T, F) = J_l;
    P = J * P * J.transpose();
    Eigen::VectorXd next(n - F + T);
    for (int i = 0, r = 0; i < n; ++i)
      if (i < offset || i >= offset + F) next[r++] = x[i];
    next.tail(T) = y;
    x = next;
  }

  /// The same for a conversion that also takes a measurement z with covariance R: the new
  /// block's covariance gains J_z R J_z^T.
  template <typename Conversion>
  void reparametrize(int offset,
                     const Conversion& conversion,
                     const Vec<Conversion::kMeasurementDim>& z,
                     const Mat<Conversion::kMeasurementDim, Conversion::kMeasurementDim>& R) {
    constexpr int F = Conversion::From::kDim;
    constexpr int T = Conversion::To::kDim;
    constexpr int Z = Conversion::kMeasurementDim;
    const int n = dim();
    Mat<T, kRobotDim> J_x;
    Mat<T, F> J_l;
    Mat<T, Z> J_z;
    const Vec<F> from = x.template segment<F>(offset);
    const Vec<T> y = detail::throughRobotView<detail::ConversionRobotT<Conversion, Robot>, Robot>(
        x.template head<kRobotDim>().eval(), J_x,
        [&](const auto& view, auto& J_view) { return conversion(view, from, z, J_view, J_l, J_z); });
    // Full Jacobian of [state without block; y] w.r.t. [old state; z].
    Eigen::MatrixXd J = Eigen::MatrixXd::Zero(n - F + T, n + Z);
    for (int i = 0, r = 0; i < n; ++i)
      if (i < offset || i >= offset + F) J(r++, i) = 1.0;
    J.block(n - F, 0, T, kRobotDim) = J_x;
    J.block(n - F, offset, T, F) = J_l;
    J.block(n - F, n, T, Z) = J_z;
    Eigen::MatrixXd P_star = Eigen::MatrixXd::Zero(n + Z, n + Z);
    P_star.topLeftCorner(n, n) = P;
    P_star.bottomRightCorner(Z, Z) = R;
    P = J * P_star * J.transpose();
    Eigen::VectorXd next(n - F + T);
    for (int i = 0, r = 0; i < n; ++i)
      if (i < offset || i >= offset + F) next[r++] = x[i];
    next.tail(T) = y;
    x = next;
  }
};

}  // namespace sylva::testing
