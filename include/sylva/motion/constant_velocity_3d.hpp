#pragma once
/// @file
/// `ConstantVelocity3D`: the free-moving camera of Davison's MonoSLAM and Civera et al.'s
/// inverse-depth SLAM (tree-width thesis Ch. 3), state (13)
///
///   x = [ r_WC (3), q_WC (4: w, x, y, z), v (3), omega_C (3) ]
///
/// position of the camera in the world, its orientation (camera -> world), its linear
/// velocity and its angular velocity in the camera frame. There is no control input; the
/// noise input n = [a (3), alpha_C (3)] is an unknown linear and angular acceleration,
/// constant over the step, which changes the velocities by impulses V = a dt and
/// Omega = alpha dt.
///
/// The linear velocity v is expressed in one of two frames (`velocity_frame`):
///
/// - `kWorld` (the default; MonoSLAM's model and the thesis's): v = v_W, and
///
///     r' = r + (v + V) dt,
///
///   so a camera that keeps its speed through a turn is accelerating, and the noise must
///   cover that centripetal acceleration for as long as the turn lasts.
/// - `kCamera`: v = v_C, the velocity seen from the camera, which stays constant for a camera
///   carried by a vehicle along an arc (it turns with the camera); the noise then only has to
///   cover changes of speed and of the direction of travel relative to the camera:
///
///     r' = r + R(q (x) exp((omega + Omega) dt / 2)) (v + V) dt
///
///   (the step taken along the orientation halfway through its rotation: the chord of an arc
///   to second order).
///
/// In both,
///
///   q'     = normalize( q * exp((omega + Omega) dt) )
///   v'     = v + V
///   omega' = omega + Omega
///
/// The quaternion is renormalized every step and the normalization is part of the function,
/// so its Jacobian (I - q q^T) / |q| is carried into the covariance.
///
/// Jacobians: `J_x` (13x13) and `J_n` (13x6), w.r.t. additive perturbations, computed by
/// forward-mode automatic differentiation of `propagate` (exact to round-off; checked against
/// central differences in tests/motion/constant_velocity_3d.test.cpp). Units: m, rad, s;
/// acceleration noise in m/s^2 and rad/s^2 (`Gaussian<6>::sigmas`).

#include <cmath>
#include <sstream>
#include <Eigen/Core>
#include <unsupported/Eigen/AutoDiff>

#include "sylva/core/error.hpp"
#include "sylva/core/gauge.hpp"
#include "sylva/core/jacobian_ref.hpp"
#include "sylva/core/quaternion.hpp"
#include "sylva/core/types.hpp"
#include "sylva/motion/pose_3d.hpp"

namespace sylva {

struct ConstantVelocity3D {
  /// The frame the state's linear velocity is expressed in (see the top of this file).
  enum class VelocityFrame { kWorld, kCamera };
  VelocityFrame velocity_frame = VelocityFrame::kWorld;

  static constexpr int kDim = 13;
  static constexpr int kControlDim = 0;
  static constexpr int kNoiseDim = 6;  ///< [linear acceleration (3), angular acceleration (3)]
  static constexpr int kPosition = Pose3D::kPosition;      ///< index of t
  static constexpr int kQuaternion = Pose3D::kQuaternion;  ///< index of q's w entry (OnManifold: the state on SO(3) x R^9)
  static constexpr int kVelocity = 7;                      ///< index of v
  static constexpr int kAngularVelocity = 10;              ///< index of omega_C
  static constexpr const char* kName = "ConstantVelocity3D";
  using State = Vec<13>;
  using Control = Vec<0>;
  using Pose = Pose3D;  ///< the pose view every camera model is written for

  /// The pose [r_WC, q_WC] of a state, and its Jacobian [I 0].
  static Vec<7> pose(const State& x, JacobianRef<7, 13> J = {}) {
    if (J) {
      (*J).setZero();
      (*J).template leftCols<7>().setIdentity();
    }
    return x.head<7>();
  }

  /// The motion with the noise input `n` (zero in the filter's mean prediction).
  template <typename T>
  Vec<13, T> propagate(const Vec<13, T>& x, const Vec<0, T>& /*u*/, const Vec<6, T>& n, double dt) const {
    const T step(dt);
    const Vec<3, T> v = x.template segment<3>(kVelocity) + n.template head<3>() * step;
    const Vec<3, T> omega = x.template segment<3>(kAngularVelocity) + n.template tail<3>() * step;
    Vec<13, T> next;
    if (velocity_frame == VelocityFrame::kWorld) {
      next.template head<3>() = x.template head<3>() + v * step;
    } else {
      // The camera-frame velocity turned into the world at the middle of the step's rotation.
      const Vec<4, T> mid =
          quaternionProduct<T>(x.template segment<4>(kQuaternion), quaternionFromRotationVector<T>(Vec<3, T>(omega * (step * T(0.5)))));
      next.template head<3>() = x.template head<3>() + rotationMatrix<T>(Vec<4, T>(mid / mid.norm())) * v * step;
    }
    const Vec<4, T> rotated =
        quaternionProduct<T>(x.template segment<4>(kQuaternion), quaternionFromRotationVector<T>(Vec<3, T>(omega * step)));
    next.template segment<4>(kQuaternion) = rotated / rotated.norm();
    next.template segment<3>(kVelocity) = v;
    next.template segment<3>(kAngularVelocity) = omega;
    return next;
  }

  /// Mean prediction over `dt` seconds, with J_x and J_n when requested.
  template <typename Tag = void>  // compiled only where called (core/deferred.hpp)
  State operator()(const State& x,
                   const Control& u,
                   double dt,
                   JacobianArg<13, 13, Tag> J_x = {},
                   JacobianArg<13, 6, Tag> J_n = {}) const {
    const double q_norm = x.segment<4>(kQuaternion).norm();
    if (!(q_norm > 1e-12)) {
      std::ostringstream os;
      os << "ConstantVelocity3D: orientation quaternion has norm " << q_norm;
      fail(std::isfinite(q_norm) ? ErrorCode::kDegenerateGeometry : ErrorCode::kNonFinite, os.str());
    }
    if (!J_x && !J_n) return propagate<double>(x, u, Vec<6>::Zero(), dt);
    using Dual = Eigen::AutoDiffScalar<Vec<19>>;
    Vec<13, Dual> x_dual;
    Vec<6, Dual> n_dual;
    for (int i = 0; i < 13; ++i) x_dual[i] = Dual(x[i], 19, i);
    for (int i = 0; i < 6; ++i) n_dual[i] = Dual(0.0, 19, 13 + i);
    const Vec<13, Dual> next = propagate<Dual>(x_dual, Vec<0, Dual>(), n_dual, dt);
    State out;
    for (int r = 0; r < 13; ++r) {
      out[r] = next[r].value();
      if (J_x) (*J_x).row(r) = next[r].derivatives().head<13>().transpose();
      if (J_n) (*J_n).row(r) = next[r].derivatives().tail<6>().transpose();
    }
    return out;
  }

  /// `x` (whose velocity is in the world frame, as the simulators give it) with its velocity in
  /// this model's frame.
  template <int = 0>  // compiled only where called (docs/build-time.md)
  State fromWorldVelocity(const State& x) const {
    if (velocity_frame == VelocityFrame::kWorld) return x;
    State out = x;
    out.segment<3>(kVelocity) = rotationMatrix<double>(Vec<4>(x.segment<4>(kQuaternion).normalized())).transpose() * x.segment<3>(kVelocity);
    return out;
  }

  /// How moving, turning (about world z) and scaling the world move the camera's state
  /// (core/gauge.hpp): the position like a point, the orientation by the turn on the left
  /// (dq = 1/2 (0, e_z) (x) q), the velocity with the scale and, in the world frame, with the
  /// turn; the angular velocity, in the camera frame, not at all.
  template <int = 0>  // compiled only where called (docs/build-time.md)
  Mat<13, kGaugeDim> gaugeDirections(const State& x) const {
    Mat<13, kGaugeDim> N = Mat<13, kGaugeDim>::Zero();
    N.topLeftCorner<3, 3>().setIdentity();
    N.block<3, 1>(0, 3) << -x[1], x[0], 0.0;
    N.block<4, 1>(kQuaternion, 3) = 0.5 * quaternionProduct<double>(Vec<4>(0.0, 0.0, 0.0, 1.0), Vec<4>(x.segment<4>(kQuaternion)));
    if (velocity_frame == VelocityFrame::kWorld) N.block<3, 1>(7, 3) << -x[8], x[7], 0.0;
    N.block<3, 1>(0, 4) = x.head<3>();
    N.block<3, 1>(kVelocity, 4) = x.segment<3>(kVelocity);
    return N;
  }

  /// Renormalizes the quaternion (after an update moved it off the unit sphere).
  static void normalize(Eigen::Ref<State> x) {
    const double q_norm = x.segment<4>(kQuaternion).norm();
    if (q_norm > 0.0) x.segment<4>(kQuaternion) /= q_norm;
  }

  /// Jacobian of `normalize` at x: identity but for the quaternion block (I - u u^T) / |q|,
  /// u = q / |q|. The filter applies it to the covariance when it renormalizes after an update.
  template <int = 0>  // compiled only where called (docs/build-time.md)
  static Mat<13, 13> normalizationJacobian(const State& x) {
    Mat<13, 13> N = Mat<13, 13>::Identity();
    const Vec<4> q = x.segment<4>(kQuaternion);
    const double q_norm = q.norm();
    if (q_norm > 0.0) {
      const Vec<4> u = q / q_norm;
      N.block<4, 4>(3, 3) = (Mat<4, 4>::Identity() - u * u.transpose()) / q_norm;
    }
    return N;
  }

  /// The transition Jacobian of first-estimates linearization (after Huang, Mourikis and
  /// Roumeliotis 2010, who give the planar case; the velocity rows follow Li and Mourikis 2013,
  /// "High-precision, consistent EKF-based visual-inertial odometry", IJRR 32(6), eq. 49-51),
  /// from the prediction `from` = x_{k|k-1} to the new prediction `to` = x_{k+1|k}.
  ///
  /// Monocular SLAM cannot observe seven directions of its state: where the map is (3), how it
  /// is turned (3) and its scale (1). In this state they are, for a translation tau, a small
  /// world-frame rotation phi and a scale change s,
  ///   dr = tau + phi x r + s r,   dq = 1/2 (0, phi) (x) q,   domega = 0,
  ///   dv = phi x v + s v (world frame)   or   dv = s v (camera frame: v turns with the camera).
  /// The textbook Jacobian at the posterior x_{k|k} carries them from the posterior to the new
  /// prediction; the measurement Jacobians of first-estimates linearization make them
  /// unobservable at the prediction x_{k|k-1} instead, and the two differ by the update, so
  /// the linearized system would "observe" them. This Jacobian carries each of the seven
  /// directions at `from` exactly into the same direction at `to`:
  ///   dr'/dr = I,   dr'/dv = J_v + d v^T / |v|^2,   dr'/dq = J_q - [d]x E(q),
  ///   dq'/dq = R_right(q^* (x) q'),   dq'/domega as the textbook Jacobian at `from`,
  ///   dv'/dv = I + Dv v^T / |v|^2,   domega'/domega = I,
  ///   dv'/dq = -[Dv]x E(q) in the world frame, 0 in the camera frame,
  /// with q, v, r of `from`, q' of `to`, J_v and J_q the textbook blocks at `from`,
  /// d = r' - f_r(from) and Dv = v' - v the parts of the step the update added, and
  /// E(q) dq = 2 vec(dq (x) q^*) the world-frame rotation of a quaternion change. (The scale
  /// terms need |v| > 0; for a camera at rest they are left out.) Without an update in
  /// between (from = x_{k|k}), d = Dv = 0 and it is the textbook Jacobian on the quaternion's
  /// tangent space.
  template <int = 0>  // compiled only where called (docs/build-time.md)
  Mat<13, 13> firstEstimatesJacobian(const State& from, const State& to, double dt) const {
    Mat<13, 13> F;
    const State predicted = (*this)(from, Control(), dt, F);  // the textbook blocks at `from`
    const Vec<4> q = from.segment<4>(kQuaternion).normalized();
    const Vec<4> q_to = to.segment<4>(kQuaternion).normalized();
    const Vec<4> q_conj(q[0], -q[1], -q[2], -q[3]);
    const Vec<3> v = from.segment<3>(kVelocity);
    const Vec<3> d = to.head<3>() - predicted.head<3>();
    const Vec<3> dv = to.segment<3>(kVelocity) - v;
    // E(q) = 2 rows 1..3 of R_right(q^*): dq (x) q^* = R_right(q^*) dq.
    const Mat<4, 4> right_conj = quaternionRightMatrix(q_conj);
    const Mat<3, 4> E = 2.0 * right_conj.bottomRows<3>();
    F.block<3, 4>(0, 3) -= skewSymmetric(d) * E;
    F.block<4, 4>(3, 3) = quaternionRightMatrix(quaternionProduct<double>(q_conj, q_to));
    if (velocity_frame == VelocityFrame::kWorld) F.block<3, 4>(7, 3) = -skewSymmetric(dv) * E;
    const double v2 = v.squaredNorm();
    if (v2 > 1e-18) {
      F.block<3, 3>(0, 7) += d * v.transpose() / v2;
      F.block<3, 3>(7, 7) += dv * v.transpose() / v2;
    }
    return F;
  }

  /// Plain difference (the quaternion is compared componentwise).
  static State difference(const State& a, const State& b) { return a - b; }
};

}  // namespace sylva
