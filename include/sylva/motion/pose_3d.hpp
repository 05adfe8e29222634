#pragma once
/// @file
/// `Pose3D`: the pose of a camera (or any body) in 3D, the state every camera model is written
/// against:
///
///   x = [ t (3), q (4: w, x, y, z) ]
///
/// the body's position in the world and its orientation (body -> world). The quaternion need
/// not be unit: the camera models use R(q / |q|) and carry the normalization in their
/// Jacobians, so they serve an additive filter (whose quaternion drifts off the sphere between
/// renormalizations) and a filter on the manifold alike.
///
/// A robot with more states than its pose (`ConstantVelocity3D`: velocities; a robot with
/// biases) exposes this pose as a view, `using Pose = Pose3D;` and
/// `static Vec<7> pose(const State& x, JacobianRef<7, kDim> J = {})`, and the filter evaluates
/// every model written for Pose3D at pose(x), chaining J (detail/model_traits.hpp).

#include "sylva/core/types.hpp"

namespace sylva {

struct Pose3D {
  static constexpr int kDim = 7;
  static constexpr int kPosition = 0;    ///< index of t
  static constexpr int kQuaternion = 3;  ///< index of q's w entry
  static constexpr const char* kName = "Pose3D";
  using State = Vec<7>;
};

}  // namespace sylva
