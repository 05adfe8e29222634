#pragma once
/// @file
/// Value types the filter hands out for gating and data association: the linearization of
/// a measurement model at the current estimate, and an innovation with its covariance.

#include <atomic>
#include <cstdint>

#include <Eigen/Cholesky>

#include "sylva/core/error.hpp"
#include "sylva/core/types.hpp"

namespace sylva {

namespace detail {
/// A number never handed out before in this program: a filter takes a new one whenever its
/// state changes, so a linearization made at another state (or of another filter) is told
/// apart from one made at this state.
inline std::uint64_t nextRevision() {
  static std::atomic<std::uint64_t> counter{0};
  return ++counter;
}
}  // namespace detail

/// h(x) at the current estimate, the two non-zero blocks of H and where they sit in the state.
/// `RobotDim` is the filter's robot block, which is larger than the model's robot when the
/// model sees the robot through its pose view (a car with bias states, say).
template <typename Model, int RobotDim = Model::Robot::kDim>
struct Linearization {
  static constexpr int kDim = Model::kDim;
  static constexpr int kRobotDim = RobotDim;
  static constexpr int kLandmarkDim = Model::Landmark::kDim;
  Vec<kDim> z_hat;
  Mat<kDim, kRobotDim> J_z_x;     ///< w.r.t. the robot block (offset 0)
  Mat<kDim, kLandmarkDim> J_z_l;  ///< w.r.t. the landmark block
  int landmark_offset = 0;        ///< first row of the landmark block in the state
  std::uint64_t revision = 0;     ///< the filter's `revision()` it was made at
};

/// Innovation nu = z - z_hat (through the model's residual) and S = H P H^T + R.
template <int M>
struct Innovation {
  Vec<M> nu;
  Mat<M, M> S;
  /// Normalized innovation squared nu^T S^-1 nu (eq. 2.46), the Mahalanobis distance^2 of
  /// eq. 2.40.
  /// Throws kNotPositiveDefinite when S is not positive definite (a negative "NIS" would pass
  /// any gate).
  double nis() const {
    const Eigen::LLT<Mat<M, M>> llt(S);
    if (llt.info() != Eigen::Success || !S.allFinite())
      fail(ErrorCode::kNotPositiveDefinite, "Innovation::nis: the innovation covariance S is not positive definite");
    return nu.dot(llt.solve(nu));
  }
};

}  // namespace sylva
