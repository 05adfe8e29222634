#pragma once
/// @file
/// `Odometry2D`: a planar robot driven by odometry increments. State [x, y, theta] in the
/// world frame (as `Unicycle2D`); the control is the measured increment u = [dx, dy, dtheta]
/// of the pose, expressed in the frame of the robot before the motion (metres, metres,
/// radians). The new pose is the composition of the old pose with the increment:
///
///   x'     = x + cos(theta) dx - sin(theta) dy
///   y'     = y + sin(theta) dx + cos(theta) dy
///   theta' = wrap(theta + dtheta)
///
/// The noise input is additive noise on the increment (3 components, in the same robot
/// frame), so the process noise of the robot block is J_n Sigma_u J_n^T: the increment's
/// covariance rotated into the world frame by theta. This is the prediction of MRPT's
/// `CRangeBearingKFSLAM2D` for a `CActionRobotMovement2D` whose pose change is a
/// `CPosePDFGaussian` (mean = the increment, covariance = Sigma_u); see bench/peers/README.md.
///
/// `dt` is not used: the increment already is the motion over the step (it must still be
/// finite and >= 0, as for every motion model of the filter).
///
/// Jacobians (additive perturbations; c = cos(theta), s = sin(theta)):
///
///   J_x (3x3) = [ 1  0  -s dx - c dy ]      J_n (3x3) = [ c  -s  0 ]
///               [ 0  1   c dx - s dy ]                  [ s   c  0 ]
///               [ 0  0        1      ]                  [ 0   0  1 ]
///
/// Common mistakes: an increment in the world frame (it is in the frame of the robot before
/// the motion); an increment accumulated over several steps from wheel odometry whose
/// covariance is then reused per step.

#include <cmath>

#include "sylva/core/angles.hpp"
#include "sylva/core/jacobian_ref.hpp"
#include "sylva/core/types.hpp"
#include "sylva/motion/pose_2d.hpp"

namespace sylva {

/// State [x, y, theta], normalize() and difference() come from Pose2D.
struct Odometry2D : Pose2D {
  static constexpr int kControlDim = 3;  ///< [dx, dy, dtheta] in the frame of the previous pose
  static constexpr int kNoiseDim = 3;    ///< additive noise on the increment
  static constexpr const char* kName = "Odometry2D";
  using Control = Vec<3>;

  /// Composes `x` with the increment `u` (`dt` is ignored, see the file comment).
  template <typename Tag = void>  // compiled only where called (core/deferred.hpp)
  State operator()(const State& x,
                   const Control& u,
                   double /*dt*/,
                   JacobianArg<3, 3, Tag> J_x = {},
                   JacobianArg<3, 3, Tag> J_n = {}) const {
    const double c = std::cos(x[2]);
    const double s = std::sin(x[2]);
    State next;
    next << x[0] + c * u[0] - s * u[1], x[1] + s * u[0] + c * u[1], wrapAngle(x[2] + u[2]);
    if (J_x) {
      *J_x << 1.0, 0.0, -s * u[0] - c * u[1],  //
          0.0, 1.0, c * u[0] - s * u[1],       //
          0.0, 0.0, 1.0;
    }
    if (J_n) {
      *J_n << c, -s, 0.0,  //
          s, c, 0.0,       //
          0.0, 0.0, 1.0;
    }
    return next;
  }

  /// The motion with noise `n` added to the increment, generic in the scalar (what J_n is
  /// the derivative of).
  template <typename T>
  Vec<3, T> propagate(const Vec<3, T>& x, const Vec<3, T>& u, const Vec<3, T>& n, double /*dt*/) const {
    using std::cos;
    using std::sin;
    const T dx = u[0] + n[0];
    const T dy = u[1] + n[1];
    const T c = cos(x[2]);
    const T s = sin(x[2]);
    Vec<3, T> next;
    next << x[0] + c * dx - s * dy, x[1] + s * dx + c * dy, wrapAngle(T(x[2] + u[2] + n[2]));
    return next;
  }
};

}  // namespace sylva
