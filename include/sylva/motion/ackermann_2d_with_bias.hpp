#pragma once
/// @file
/// `Ackermann2DWithBias`: the car of `Ackermann2D` with two more states that the filter
/// estimates online, an encoder speed scale error and a steering offset:
///
///   state    [x, y, theta, k, b]   (m, m, rad, -, rad)
///   control  [v_e, alpha]          encoder speed (m/s) and steering angle (rad), as measured
///   motion   the pose moves as Ackermann2D under [v_e (1 + k), alpha + b];
///            k' = k + dt w_k,  b' = b + dt w_b       (random walks)
///   noise    [n_v, n_alpha, w_k, w_b]: additive noise on the measured control, and the
///            random-walk rates of the two biases, all held constant over the step.
///
/// A random walk of spectral density q (units^2 / s) over a step of dt needs Var(w) = q / dt,
/// so that the bias variance grows by q dt whatever the step length.
///
/// Measurement models written for the planar pose (`RangeBearing`, `RangeBearingDiameter`,
/// their inverses) serve this robot through its pose view (`using Pose = Pose2D`, `pose(x)`):
/// the filter evaluates them at [x, y, theta] and chains the Jacobians. The invariant EKF
/// applies (kPlanarPosition, kPlanarHeading); the two biases stay additive. First-estimates
/// Jacobians do not exist for it (the biases couple the heading to the estimate).

#include <cmath>

#include "sylva/core/angles.hpp"
#include "sylva/core/deferred.hpp"
#include "sylva/core/jacobian_ref.hpp"
#include "sylva/core/types.hpp"
#include "sylva/motion/ackermann_2d.hpp"
#include "sylva/motion/pose_2d.hpp"

namespace sylva {

struct Ackermann2DWithBias : Pose2DWithExtras<5> {
  // State [x, y, theta, k (speed scale error), b (steering offset, rad)]; kDim, State,
  // Pose, pose(), normalize() and difference() come from Pose2DWithExtras.
  static constexpr int kControlDim = 2;  ///< [v_e (m/s), alpha (rad)], as measured
  static constexpr int kNoiseDim = 4;    ///< [n_v, n_alpha, w_k, w_b]
  static constexpr int kPlanarPosition = 0;
  static constexpr int kPlanarHeading = 2;
  static constexpr const char* kName = "Ackermann2DWithBias";
  using Control = Vec<2>;

  explicit Ackermann2DWithBias(double wheelbase_m, double encoder_offset_m = 0.0)
      : car_(wheelbase_m, encoder_offset_m) {}
  const Ackermann2D& car() const { return car_; }

  /// Propagates `x` over `dt` under the measured control `u`.
  template <typename Tag = void>  // compiled only where called (core/deferred.hpp)
  State operator()(const detail::Deferred<State, Tag>& x,
                   const Control& u,
                   double dt,
                   JacobianArg<5, 5, Tag> J_x = {},
                   JacobianArg<5, 4, Tag> J_n = {}) const {
    const double scale = 1.0 + x[3];
    const Vec<2> corrected(u[0] * scale, u[1] + x[4]);
    detail::Deferred<Mat<3, 3>, Tag> J_pose;
    detail::Deferred<Mat<3, 2>, Tag> J_control;  // d pose' / d [v, alpha] at the corrected control
    detail::Deferred<State, Tag> next;
    next.template head<3>() = car_(Vec<3>(x.template head<3>()), corrected, dt, J_pose, J_control);
    next[3] = x[3];
    next[4] = x[4];
    if (J_x) {
      (*J_x).setIdentity();
      (*J_x).template topLeftCorner<3, 3>() = J_pose;
      (*J_x).template block<3, 1>(0, 3) = J_control.col(0) * u[0];  // d v / d k = v_e
      (*J_x).template block<3, 1>(0, 4) = J_control.col(1);         // d alpha / d b = 1
    }
    if (J_n) {
      (*J_n).setZero();
      (*J_n).template block<3, 1>(0, 0) = J_control.col(0) * scale;  // d v / d n_v = 1 + k
      (*J_n).template block<3, 1>(0, 1) = J_control.col(1);
      (*J_n)(3, 2) = dt;
      (*J_n)(4, 3) = dt;
    }
    return next;
  }

  /// The motion with noise `n`, generic in the scalar (what J_x and J_n are derivatives of).
  template <typename T>
  Vec<5, T> propagate(const Vec<5, T>& x, const Vec<2, T>& u, const Vec<4, T>& n, double dt) const {
    const Vec<2, T> corrected((u[0] + n[0]) * (T(1.0) + x[3]), u[1] + n[1] + x[4]);
    const Vec<3, T> pose = car_.propagate<T>(Vec<3, T>(x.template head<3>()), corrected, Vec<2, T>::Zero(), dt);
    Vec<5, T> next;
    next << pose, x[3] + T(dt) * n[2], x[4] + T(dt) * n[3];
    return next;
  }

 private:
  Ackermann2D car_;
};

}  // namespace sylva
