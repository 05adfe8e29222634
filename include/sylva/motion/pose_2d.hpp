#pragma once
/// @file
/// `Pose2D`: what every planar robot whose state is the pose [x, y, theta] shares (the base
/// of `Unicycle2D` and `Odometry2D`): the state type, theta kept wrapped to (-pi, pi]
/// (`normalize`), and the difference of two states with the angle wrapped (`difference`,
/// used for errors, NEES and numerical Jacobians). A robot derives from it and adds its
/// control, noise and `operator()`.

#include <Eigen/Core>

#include "sylva/core/angles.hpp"
#include "sylva/core/deferred.hpp"
#include "sylva/core/jacobian_ref.hpp"
#include "sylva/core/types.hpp"

namespace sylva {

struct Pose2D {
  static constexpr int kDim = 3;  ///< [x, y, theta]
  static constexpr int kPlanarPosition = 0;  ///< [x, y] in the world (LinearizationPoint::kInvariant)
  static constexpr int kPlanarHeading = 2;   ///< theta
  using State = Vec<3>;

  /// Brings a state back to its canonical range (theta in (-pi, pi]).
  template <typename Tag = void>  // compiled only where called (core/deferred.hpp), as below
  static void normalize(Eigen::Ref<detail::Deferred<State, Tag>> x) {
    x[2] = wrapAngle(x[2]);
  }

  /// The state-transition Jacobian of first-estimates linearization (Huang, Mourikis and
  /// Roumeliotis 2010, "Observability-based rules for designing consistent EKF SLAM
  /// estimators", IJRR 29(5), eq. 34): for a motion x' = x (+) delta(u), a rigid increment in
  /// the robot frame, J_x = [ 1 0 -(y' - y) ; 0 1 (x' - x) ; 0 0 1 ]. First-estimates
  /// linearization evaluates it with `from` the prior of the previous step x_{k|k-1} and `to`
  /// the new prediction x_{k+1|k}, instead of the posterior x_{k|k}. Every planar robot of
  /// sylva moves that way; one that does not (a world-frame drift, say) must hide this.
  template <typename Tag = void>
  static Eigen::Matrix3d firstEstimatesJacobian(const detail::Deferred<State, Tag>& from, const State& to) {
    using Jacobian = detail::Deferred<Eigen::Matrix3d, Tag>;
    Jacobian J = Jacobian::Identity();
    J(0, 2) = -(to[1] - from[1]);
    J(1, 2) = to[0] - from[0];
    return J;
  }

  /// Difference of two states with the angle wrapped, for errors and NEES.
  template <typename Tag = void>
  static State difference(const detail::Deferred<State, Tag>& a, const State& b) {
    State d = a - b;
    d[2] = wrapAngle(d[2]);
    return d;
  }
};

/// What a planar robot whose state is the pose followed by more states, [x, y, theta, ...],
/// shares (the base of `Ackermann2DWithBias` and `Unicycle2DWithBias`): its pose view
/// (`using Pose = Pose2D`, `pose(x, J)`, the first three entries, so every planar sensor
/// model serves it), theta kept wrapped, and differences with the angle wrapped.
template <int Dim>
struct Pose2DWithExtras {
  static_assert(Dim > 3, "a state with extras holds more than the pose");
  static constexpr int kDim = Dim;
  using State = Vec<Dim>;
  using Pose = Pose2D;  ///< the pose view every planar sensor model is written for

  /// The pose [x, y, theta] of a state, and its Jacobian [I 0].
  static Vec<3> pose(const State& x, JacobianRef<3, Dim> J = {}) {
    if (J) {
      (*J).setZero();
      (*J).template leftCols<3>().setIdentity();
    }
    return x.template head<3>();
  }

  static void normalize(Eigen::Ref<State> x) { x[2] = wrapAngle(x[2]); }

  /// a - b with the heading wrapped.
  static State difference(const State& a, const State& b) {
    State d = a - b;
    d[2] = wrapAngle(d[2]);
    return d;
  }
};

}  // namespace sylva
