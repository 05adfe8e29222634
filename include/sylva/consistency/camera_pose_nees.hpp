#pragma once
/// @file
/// `cameraPoseNees`: the NEES of a `ConstantVelocity3D` camera's pose (position and
/// orientation, 6 degrees of freedom) against the true state.
///
/// The orientation is a unit quaternion q = (w, x, y, z), four numbers with three degrees of
/// freedom, so its 4x4 covariance is singular and x - x_hat is no error vector. The error is
/// taken in the tangent space instead:
///
///   e = [ t_true - t_hat,  2 vec(q_hat^* (x) q_true) ]
///
/// (the second part is the small rotation from the estimated to the true orientation, in
/// radians, in the estimated camera frame; q_true's sign is chosen to make it the short way
/// round), with covariance G P G^T, where P is the 7x7 covariance of [t, q] and
/// G = de/d[t_hat, q_hat] = [ -I 0; 0 2 d vec(q^* (x) q_true)/dq ]. e is linear in q_hat,
/// so G is exact. NEES = e^T (G P G^T)^-1 e ~ chi-square(6) for a consistent filter.
/// Throws like `nees` (kNotPositiveDefinite when G P G^T is not positive definite,
/// kNonFinite for NaN or Inf).
///
/// A camera on its manifold (OnManifold<ConstantVelocity3D>, covariance 12x12 on the tangent
/// [dr, dtheta, dv, domega]) has an error vector already: e = truth (-) estimate, whose pose
/// part is [t_true - t_hat, Log(q_hat^* (x) q_true)], with covariance the tangent's top-left
/// 6x6 block; `cameraPoseErrorOnManifold` and `cameraPoseNeesOnManifold` compute that.

#include "sylva/consistency/nees.hpp"
#include "sylva/core/error.hpp"
#include "sylva/core/quaternion.hpp"
#include "sylva/core/types.hpp"
#include "sylva/motion/pose_3d.hpp"

namespace sylva {

/// The camera pose's error e (6: position, then orientation) and its covariance G P G^T, as
/// described above; `cameraPoseNees` is e^T (G P G^T)^-1 e, and a sub-block of both gives the
/// NEES of the position or the orientation alone (3 dof each).
struct CameraPoseError {
  Vec<6> e;
  Mat<6, 6> S;
};

template <int = 0>  // compiled only where called (docs/build-time.md)
CameraPoseError cameraPoseError(const Vec<13>& estimate,
                                const Mat<13, 13>& covariance,
                                const Vec<13>& truth) {
  if (!estimate.allFinite() || !truth.allFinite())
    fail(ErrorCode::kNonFinite, "cameraPoseNees: the estimate or the true state is not finite");
  const auto conj = [](const Vec<4>& q) { return Vec<4>(q[0], -q[1], -q[2], -q[3]); };
  const Vec<4> q = estimate.segment<4>(Pose3D::kQuaternion);
  const double true_norm = truth.segment<4>(Pose3D::kQuaternion).norm();
  if (!(q.norm() > 1e-12) || !(true_norm > 1e-12))
    fail(ErrorCode::kDegenerateGeometry,
         "cameraPoseNees: an orientation quaternion has (near) zero norm");
  Vec<4> q_true = truth.segment<4>(Pose3D::kQuaternion) / true_norm;
  if (quaternionProduct<double>(conj(q), q_true)[0] < 0.0)
    q_true = -q_true;  // same rotation, the short way
  CameraPoseError out;
  out.e.head<3>() = truth.head<3>() - estimate.head<3>();
  out.e.tail<3>() = 2.0 * quaternionProduct<double>(conj(q), q_true).template tail<3>();
  Mat<6, 7> G = Mat<6, 7>::Zero();
  G.topLeftCorner<3, 3>() = -Mat<3, 3>::Identity();
  for (int i = 0; i < 4; ++i)
    G.block<3, 1>(3, 3 + i) =
        2.0 * quaternionProduct<double>(conj(Vec<4>::Unit(i)), q_true).template tail<3>();
  out.S = G * covariance.topLeftCorner<7, 7>() * G.transpose();
  return out;
}

/// The camera pose's error on the manifold: e = (truth (-) estimate)'s pose part, and the
/// tangent covariance's pose block (see the top of this file).
template <int = 0>  // compiled only where called (docs/build-time.md)
CameraPoseError cameraPoseErrorOnManifold(const Vec<13>& estimate,
                                          const Mat<12, 12>& covariance,
                                          const Vec<13>& truth) {
  if (!estimate.allFinite() || !truth.allFinite())
    fail(ErrorCode::kNonFinite, "cameraPoseNees: the estimate or the true state is not finite");
  const Vec<4> q = estimate.segment<4>(Pose3D::kQuaternion);
  const double true_norm = truth.segment<4>(Pose3D::kQuaternion).norm();
  if (!(q.norm() > 1e-12) || !(true_norm > 1e-12))
    fail(ErrorCode::kDegenerateGeometry,
         "cameraPoseNees: an orientation quaternion has (near) zero norm");
  CameraPoseError out;
  out.e.head<3>() = truth.head<3>() - estimate.head<3>();
  out.e.tail<3>() = rotationVectorFromQuaternion(
      quaternionProduct<double>(Vec<4>(q[0], -q[1], -q[2], -q[3]) / q.norm(),
                                Vec<4>(truth.segment<4>(Pose3D::kQuaternion) / true_norm)));
  out.S = covariance.topLeftCorner<6, 6>();
  return out;
}

template <int = 0>  // compiled only where called (docs/build-time.md)
double cameraPoseNeesOnManifold(const Vec<13>& estimate,
                                const Mat<12, 12>& covariance,
                                const Vec<13>& truth) {
  const CameraPoseError pose = cameraPoseErrorOnManifold(estimate, covariance, truth);
  return nees(pose.e, pose.S);
}

template <int = 0>  // compiled only where called (docs/build-time.md)
double cameraPoseNees(const Vec<13>& estimate,
                      const Mat<13, 13>& covariance,
                      const Vec<13>& truth) {
  const CameraPoseError pose = cameraPoseError(estimate, covariance, truth);
  return nees(pose.e, pose.S);
}

}  // namespace sylva
