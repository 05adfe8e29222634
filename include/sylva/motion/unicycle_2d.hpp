#pragma once
/// @file
/// `Unicycle2D`: the differential-drive robot of the multisensor thesis (Amarasinghe 2008,
/// Sec. 2.1.2), state [x, y, theta] in the world frame, control [v, omega] (m/s, rad/s):
///
///   x'     = x + dt v cos(theta + dt omega / 2)        (2.12)
///   y'     = y + dt v sin(theta + dt omega / 2)        (2.13)
///   theta' = theta + dt omega                          (2.14)
///
/// The noise input is additive noise on the control [v, omega], so the process noise of the
/// robot block is J_n Sigma_u J_n^T (eq. 2.22, 2.27). theta is kept wrapped to (-pi, pi].
///
/// Jacobians: `J_x` (3x3) w.r.t. the state and `J_n` (3x2) w.r.t. the control noise, both
/// w.r.t. additive (Euclidean) perturbations.

#include <cmath>

#include "sylva/core/angles.hpp"
#include "sylva/core/jacobian_ref.hpp"
#include "sylva/core/types.hpp"
#include "sylva/motion/pose_2d.hpp"

namespace sylva {

/// State [x, y, theta], normalize() and difference() come from Pose2D.
struct Unicycle2D : Pose2D {
  static constexpr int kControlDim = 2;  ///< [v, omega]
  static constexpr int kNoiseDim = 2;    ///< additive noise on [v, omega]
  static constexpr const char* kName = "Unicycle2D";
  using Control = Vec<2>;

  /// Propagates `x` over `dt` seconds under control `u` (eq. 2.12-2.14).
  template <typename Tag = void>  // compiled only where called (core/deferred.hpp)
  State operator()(const State& x,
                   const Control& u,
                   double dt,
                   JacobianArg<3, 3, Tag> J_x = {},
                   JacobianArg<3, 2, Tag> J_n = {}) const {
    const double v = u[0];
    const double omega = u[1];
    const double heading = x[2] + 0.5 * dt * omega;
    const double c = std::cos(heading);
    const double s = std::sin(heading);
    State next;
    next << x[0] + dt * v * c, x[1] + dt * v * s, wrapAngle(x[2] + dt * omega);
    if (J_x) {
      *J_x << 1.0, 0.0, -dt * v * s,  //
          0.0, 1.0, dt * v * c,       //
          0.0, 0.0, 1.0;
    }
    if (J_n) {
      *J_n << dt * c, -0.5 * dt * dt * v * s,  //
          dt * s, 0.5 * dt * dt * v * c,       //
          0.0, dt;
    }
    return next;
  }

  /// The motion with noise `n` added to the control, generic in the scalar (what J_n is the
  /// derivative of).
  template <typename T>
  Vec<3, T> propagate(const Vec<3, T>& x, const Vec<2, T>& u, const Vec<2, T>& n, double dt) const {
    using std::cos;
    using std::sin;
    const T v = u[0] + n[0];
    const T omega = u[1] + n[1];
    const T heading = x[2] + T(0.5 * dt) * omega;
    Vec<3, T> next;
    next << x[0] + T(dt) * v * cos(heading), x[1] + T(dt) * v * sin(heading), wrapAngle(T(x[2] + T(dt) * omega));
    return next;
  }
};

}  // namespace sylva
