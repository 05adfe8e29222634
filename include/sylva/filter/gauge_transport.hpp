#pragma once
/// @file
/// The covariance transport of the observability-constrained update
/// (LinearizationPoint::kObservabilityConstrained, filter/ekf.hpp; docs/filter.md,
/// "Observability-constrained updates"): after an update linearized at x-, which gains no
/// information along the gauge directions N(x-), P+ <- T P+ T^T with T = I + dN A,
/// dN = N(x+) - N(x-) and A a left inverse of N (GaugeInverse), so T N(x-) = N(x+).
///
/// `detail::GaugeTransport<RobotDim>` holds the transport's workspace and runs it on the
/// filter's lower-triangle covariance. It is a template on the robot's covariance rows only,
/// so every filter with the same robot dimension compiles it once; the filter supplies the
/// directions N(x) (its robot's and landmarks' `gaugeDirections`, core/gauge.hpp).

#include <Eigen/Cholesky>
#include <Eigen/Core>

#include "sylva/core/deferred.hpp"
#include "sylva/core/gauge.hpp"
#include "sylva/core/types.hpp"
#include "sylva/detail/workspace.hpp"

namespace sylva {

/// Where the observability-constrained update (LinearizationPoint::kObservabilityConstrained)
/// reads the unobservable part of a correction: the left inverse A of the gauge directions N
/// in its covariance transport T = I + dN A.
enum class GaugeInverse {
  /// A = (N_r^T N_r)^-1 N_r^T on the robot's coordinates alone (the default): the landmarks'
  /// covariance moves with the robot's. Falls back to kWholeState for a camera at rest.
  kRobot,
  /// A = (N^T N)^-1 N^T over the whole state, every coordinate weighed alike.
  kWholeState,
};

namespace detail {

/// The transport's two steps, around the filter's covariance update: `prepare` before
/// anything of the filter is written (it only grows its own workspace), `carry` after. `Tag`
/// keeps the bodies dependent (core/deferred.hpp); every filter uses the default.
template <int RobotDim, typename Tag = void>
class GaugeTransport {
  using Matrix = Deferred<Mat<kGaugeDim, kGaugeDim>, Tag>;
  using Vector = Deferred<Vec<kGaugeDim>, Tag>;
  using Rows = Deferred<Eigen::Matrix<double, kGaugeDim, Eigen::Dynamic>, Tag>;

 public:
  /// N(x-)^T and dN^T = (N(x+) - N(x-))^T for an n-dimensional state, and the left inverse
  /// A = G N_a^T of the transport, G = (N_a^T N_a)^-1. `fill(scale, Nt)` writes N(x)^T (5 x n)
  /// at x = x- + scale * delta. N_a is the robot's rows of N (the gauge part of a perturbation
  /// read off the robot's coordinates; it has full rank while the camera moves), or all of N
  /// where the robot's rows are degenerate or `choice` asks for the whole state; with both
  /// degenerate, or a non-finite dN, there is no transport.
  template <typename Fill>
  void prepare(int n, GaugeInverse choice, Fill&& fill) {
    active_ = false;
    growWorkspace(workspace_, 3 * static_cast<Eigen::Index>(kGaugeDim) * n);
    auto Nt = block(0, n);
    auto dNt = block(1, n);
    fill(0.0, Nt);
    fill(1.0, dNt);
    dNt -= Nt;
    if (!dNt.allFinite()) return;
    const auto N_robot = Nt.template leftCols<RobotDim>();
    robot_only_ = choice == GaugeInverse::kRobot && invert(N_robot * N_robot.transpose());
    if (!robot_only_) {
      Matrix NtN = Matrix::Zero();
      for (int i = 0; i < n; ++i) NtN.noalias() += Nt.col(i) * Nt.col(i).transpose();
      if (!invert(NtN)) return;
    }
    active_ = true;
  }

  /// After the covariance update: P <- T P T^T on the lower triangle of `P` (the first n
  /// rows and columns of the filter's stored matrix), with `P_robot` its robot block:
  ///   B = P A^T,  C = A B,  B' = B + dN C / 2,  P <- P + dN B'^T + B' dN^T.
  /// O(n^2) (a rank-10 correction; B costs O(n) when A reads the robot alone), no
  /// allocation. Does nothing unless the last `prepare` found a transport.
  template <typename Stored>
  void carry(Stored& P, int n, const Mat<RobotDim, RobotDim>& P_robot) {
    if (!active_) return;
    active_ = false;
    const auto Nt = block(0, n);
    const auto dNt = block(1, n);
    auto Bt = block(2, n);
    // Bt = N_a^T P (5 x n) from the lower triangle.
    if (robot_only_) {
      const Mat<kGaugeDim, RobotDim> N_robot = Nt.template leftCols<RobotDim>();
      Bt.template leftCols<RobotDim>() = N_robot * P_robot;
      for (int j = RobotDim; j < n; ++j) {
        const Vec<RobotDim> p = P.row(j).template head<RobotDim>().transpose();  // P(robot, j)
        Bt.col(j) = N_robot * p;
      }
    } else {
      // Each stored P(i, j), i >= j, adds N_i P(i, j) to column j and, below the diagonal,
      // N_j P(i, j) to column i.
      Bt.setZero();
      for (int j = 0; j < n; ++j) {
        const auto col = P.col(j).segment(j, n - j);
        Bt.col(j).noalias() += Nt.middleCols(j, n - j) * col;
        Bt.middleCols(j + 1, n - j - 1).noalias() += Nt.col(j) * col.tail(n - j - 1).transpose();
      }
    }
    // B^T = G N_a^T P, and C = A P A^T = G N_a^T P N_a G.
    for (int j = 0; j < n; ++j) {
      const Vector b = inverse_ * Bt.col(j);
      Bt.col(j) = b;
    }
    Matrix NtB = Matrix::Zero();
    const int rows = robot_only_ ? RobotDim : n;
    for (int i = 0; i < rows; ++i) NtB.noalias() += Nt.col(i) * Bt.col(i).transpose();
    const Matrix C = inverse_ * NtB;
    const Matrix C_half = 0.25 * (C + C.transpose());
    for (int j = 0; j < n; ++j) {
      const Vector b = Bt.col(j) + C_half * dNt.col(j);
      Bt.col(j) = b;
    }
    for (int j = 0; j < n; ++j) {
      auto col = P.col(j).segment(j, n - j);
      col.noalias() += dNt.middleCols(j, n - j).transpose() * Bt.col(j);
      col.noalias() += Bt.middleCols(j, n - j).transpose() * dNt.col(j);
    }
  }

 /// Forgets a prepared transport (an update that failed after `prepare`).
  void cancel() { active_ = false; }

 private:
  /// Column block k (0: N(x-)^T, 1: dN^T, 2: B^T) of the workspace, 5 x n.
  Eigen::Map<Rows> block(int k, int n) {
    return Eigen::Map<Rows>(workspace_.data() + static_cast<Eigen::Index>(k) * kGaugeDim * n, kGaugeDim, n);
  }

  /// G = (N_a^T N_a)^-1 from N_a^T N_a, refused where its factor is near singular.
  bool invert(const Matrix& NtN) {
    const Eigen::LLT<Matrix> llt(NtN);
    if (llt.info() != Eigen::Success) return false;
    const Vector d = llt.matrixLLT().diagonal();
    if (!(d.minCoeff() > 1e-6 * d.maxCoeff())) return false;
    inverse_ = llt.solve(Matrix::Identity());
    return inverse_.allFinite();
  }

  Deferred<Eigen::VectorXd, Tag> workspace_;  ///< N(x-)^T, dN^T and B^T (3 x 5n)
  Matrix inverse_ = Matrix::Zero();           ///< G
  bool active_ = false;                       ///< the next `carry` transports
  bool robot_only_ = false;                   ///< A reads the robot's coordinates alone
};

}  // namespace detail
}  // namespace sylva
