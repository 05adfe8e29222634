#pragma once
/// @file
/// `ConstantVelocity3D`: the free-moving camera of Davison's MonoSLAM and Civera et al.'s
/// inverse-depth SLAM (tree-width thesis Ch. 3), state (13)
///
///   x = [ r_WC (3), q_WC (4: w, x, y, z), v_W (3), omega_C (3) ]
///
/// position of the camera in the world, its orientation (camera -> world), its linear
/// velocity in the world frame and its angular velocity in the camera frame. There is no
/// control input; the noise input n = [a_W (3), alpha_C (3)] is an unknown linear and
/// angular acceleration, constant over the step, which changes the velocities by impulses
/// V = a dt and Omega = alpha dt:
///
///   r'     = r + (v + V) dt
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
#include "sylva/core/jacobian_ref.hpp"
#include "sylva/core/quaternion.hpp"
#include "sylva/core/types.hpp"

namespace sylva {

struct ConstantVelocity3D {
  static constexpr int kDim = 13;
  static constexpr int kControlDim = 0;
  static constexpr int kNoiseDim = 6;  ///< [linear acceleration (3), angular acceleration (3)]
  static constexpr const char* kName = "ConstantVelocity3D";
  using State = Vec<13>;
  using Control = Vec<0>;

  /// The motion with the noise input `n` (zero in the filter's mean prediction).
  template <typename T>
  Vec<13, T> propagate(const Vec<13, T>& x, const Vec<0, T>& /*u*/, const Vec<6, T>& n, double dt) const {
    const T step(dt);
    const Vec<3, T> v = x.template segment<3>(7) + n.template head<3>() * step;
    const Vec<3, T> omega = x.template segment<3>(10) + n.template tail<3>() * step;
    Vec<13, T> next;
    next.template head<3>() = x.template head<3>() + v * step;
    const Vec<4, T> rotated =
        quaternionProduct<T>(x.template segment<4>(3), quaternionFromRotationVector<T>(Vec<3, T>(omega * step)));
    next.template segment<4>(3) = rotated / rotated.norm();
    next.template segment<3>(7) = v;
    next.template segment<3>(10) = omega;
    return next;
  }

  /// Mean prediction over `dt` seconds, with J_x and J_n when requested.
  State operator()(const State& x,
                   const Control& u,
                   double dt,
                   JacobianRef<13, 13> J_x = {},
                   JacobianRef<13, 6> J_n = {}) const {
    const double q_norm = x.segment<4>(3).norm();
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

  /// Renormalizes the quaternion (after an update moved it off the unit sphere).
  static void normalize(Eigen::Ref<State> x) {
    const double q_norm = x.segment<4>(3).norm();
    if (q_norm > 0.0) x.segment<4>(3) /= q_norm;
  }

  /// Jacobian of `normalize` at x: identity but for the quaternion block (I - u u^T) / |q|,
  /// u = q / |q|. The filter applies it to the covariance when it renormalizes after an update.
  static Mat<13, 13> normalizationJacobian(const State& x) {
    Mat<13, 13> N = Mat<13, 13>::Identity();
    const Vec<4> q = x.segment<4>(3);
    const double q_norm = q.norm();
    if (q_norm > 0.0) {
      const Vec<4> u = q / q_norm;
      N.block<4, 4>(3, 3) = (Mat<4, 4>::Identity() - u * u.transpose()) / q_norm;
    }
    return N;
  }

  /// Plain difference (the quaternion is compared componentwise).
  static State difference(const State& a, const State& b) { return a - b; }
};

}  // namespace sylva
