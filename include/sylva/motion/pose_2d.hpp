#pragma once
/// @file
/// `Pose2D`: what every planar robot whose state is the pose [x, y, theta] shares (the base
/// of `Unicycle2D` and `Odometry2D`): the state type, theta kept wrapped to (-pi, pi]
/// (`normalize`), and the difference of two states with the angle wrapped (`difference`,
/// used for errors, NEES and numerical Jacobians). A robot derives from it and adds its
/// control, noise and `operator()`.

#include <Eigen/Core>

#include "sylva/core/angles.hpp"
#include "sylva/core/types.hpp"

namespace sylva {

struct Pose2D {
  static constexpr int kDim = 3;  ///< [x, y, theta]
  using State = Vec<3>;

  /// Brings a state back to its canonical range (theta in (-pi, pi]).
  static void normalize(Eigen::Ref<State> x) { x[2] = wrapAngle(x[2]); }

  /// Difference of two states with the angle wrapped, for errors and NEES.
  static State difference(const State& a, const State& b) {
    State d = a - b;
    d[2] = wrapAngle(d[2]);
    return d;
  }
};

}  // namespace sylva
