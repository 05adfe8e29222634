#pragma once
/// @file
/// `Unicycle2DWithBias`: the differential-drive robot of `Unicycle2D` driven by commands it
/// follows imperfectly, with three more states that the filter estimates online:
///
///   state    [x, y, theta, k_v, k_w, b_w]   (m, m, rad, -, -, rad/s)
///   control  [v_c, w_c]                      the commanded speed (m/s) and turn rate (rad/s)
///   motion   the pose moves as Unicycle2D under
///              v = v_c (1 + k_v),   w = w_c (1 + k_w) + m b_w,
///            m = 1 while the robot is commanded to move (u != 0) and 0 at a standstill
///            command (a stopped robot does not turn); k_v, k_w, b_w are random walks:
///              k_v' = k_v + dt e_v,  k_w' = k_w + dt e_w,  b_w' = b_w + dt e_b
///   noise    [n_v, n_w, e_v, e_w, e_b]: additive noise on the command (scaled by the gain, as
///            the command is) and the random-walk rates of the three states, all held constant
///            over the step.
///
/// k_v and k_w are scale errors (a robot that drives 4% farther than commanded has k_v =
/// 0.04) and b_w a turn-rate offset: a wheel-radius mismatch and an asymmetry between the
/// wheels. A random walk of spectral density q (units^2 / s) over a step of dt needs
/// Var(e) = q / dt, so that the variance grows by q dt whatever the step length.
///
/// Measurement models written for the planar pose (`RangeBearing`, its inverse, ...) serve
/// this robot through its pose view (`using Pose = Pose2D`, `pose(x)`). First-estimates and
/// invariant linearizations are not offered: the gains couple the motion to the estimate.

#include <Eigen/Core>

#include "sylva/core/angles.hpp"
#include "sylva/core/deferred.hpp"
#include "sylva/core/jacobian_ref.hpp"
#include "sylva/core/scalar.hpp"
#include "sylva/core/types.hpp"
#include "sylva/motion/pose_2d.hpp"
#include "sylva/motion/unicycle_2d.hpp"

namespace sylva {

struct Unicycle2DWithBias : Pose2DWithExtras<6> {
  // State [x, y, theta, k_v, k_w, b_w]; kDim, State, Pose, pose(), normalize() and
  // difference() come from Pose2DWithExtras.
  static constexpr int kControlDim = 2;  ///< [v_c (m/s), w_c (rad/s)], as commanded
  static constexpr int kNoiseDim = 5;    ///< [n_v, n_w, e_v, e_w, e_b]
  static constexpr const char* kName = "Unicycle2DWithBias";
  using Control = Vec<2>;

  /// 1 while the robot is commanded to move, 0 at a standstill command.
  static double moving(const Control& u) { return u[0] != 0.0 || u[1] != 0.0 ? 1.0 : 0.0; }

  /// Propagates `x` over `dt` under the command `u`.
  template <typename Tag = void>  // compiled only where called (core/deferred.hpp)
  State operator()(const detail::Deferred<State, Tag>& x,
                   const Control& u,
                   double dt,
                   JacobianArg<6, 6, Tag> J_x = {},
                   JacobianArg<6, 5, Tag> J_n = {}) const {
    const double m = moving(u);
    const Vec<2> actual(u[0] * (1.0 + x[3]), u[1] * (1.0 + x[4]) + m * x[5]);
    detail::Deferred<Mat<3, 3>, Tag> J_pose;
    detail::Deferred<Mat<3, 2>, Tag> J_control;  // d pose' / d [v, w] at the actual motion
    detail::Deferred<State, Tag> next;
    next.template head<3>() = unicycle_(Vec<3>(x.template head<3>()), actual, dt, J_pose, J_control);
    next.template tail<3>() = x.template tail<3>();
    if (J_x) {
      (*J_x).setIdentity();
      (*J_x).template topLeftCorner<3, 3>() = J_pose;
      (*J_x).template block<3, 1>(0, 3) = J_control.col(0) * u[0];  // d v / d k_v = v_c
      (*J_x).template block<3, 1>(0, 4) = J_control.col(1) * u[1];  // d w / d k_w = w_c
      (*J_x).template block<3, 1>(0, 5) = J_control.col(1) * m;     // d w / d b_w = m
    }
    if (J_n) {
      (*J_n).setZero();
      (*J_n).template block<3, 1>(0, 0) = J_control.col(0) * (1.0 + x[3]);
      (*J_n).template block<3, 1>(0, 1) = J_control.col(1) * (1.0 + x[4]);
      (*J_n).template bottomRightCorner<3, 3>() = dt * Mat<3, 3>::Identity();
    }
    return next;
  }

  /// The motion with noise `n`, generic in the scalar (what J_x and J_n are derivatives of).
  template <typename T>
  Vec<6, T> propagate(const Vec<6, T>& x, const Vec<2, T>& u, const Vec<5, T>& n, double dt) const {
    const T m(moving(Control(scalarValue(u[0]), scalarValue(u[1]))));
    const Vec<2, T> actual((u[0] + n[0]) * (T(1.0) + x[3]), (u[1] + n[1]) * (T(1.0) + x[4]) + m * x[5]);
    const Vec<3, T> pose = unicycle_.propagate<T>(Vec<3, T>(x.template head<3>()), actual, Vec<2, T>::Zero(), dt);
    Vec<6, T> next;
    next << pose, x[3] + T(dt) * n[2], x[4] + T(dt) * n[3], x[5] + T(dt) * n[4];
    return next;
  }

 private:
  Unicycle2D unicycle_;
};

}  // namespace sylva
