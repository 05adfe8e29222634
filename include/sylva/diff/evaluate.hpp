#pragma once
// IWYU pragma: private
/// @file
/// How the filter evaluates a measurement model: with its analytic Jacobians if it has them,
/// by forward-mode automatic differentiation (`AutoDiff`) otherwise, and through the robot's
/// pose view when the model is written for the pose (detail/model_traits.hpp).

#include "sylva/core/jacobian_ref.hpp"
#include "sylva/core/types.hpp"
#include "sylva/detail/model_traits.hpp"
#include "sylva/diff/auto_diff.hpp"

namespace sylva::detail {

/// z_hat = h(robot, landmark) and, when requested, its two Jacobians.
template <typename Model>
Vec<Model::kDim> evaluate(const Model& model,
                          const Vec<Model::Robot::kDim>& robot,
                          const Vec<Model::Landmark::kDim>& landmark,
                          JacobianRef<Model::kDim, Model::Robot::kDim> J_z_x,
                          JacobianRef<Model::kDim, Model::Landmark::kDim> J_z_l) {
  if constexpr (HasAnalyticJacobians<Model>::value) {
    return model(robot, landmark, J_z_x, J_z_l);
  } else {
    return AutoDiff<Model>(model)(robot, landmark, J_z_x, J_z_l);
  }
}

/// z_hat = h(view of x, landmark) for a filter whose robot is `Robot`: the model sees the
/// robot state itself when its robot type fits directly, else the pose view Robot::pose(x),
/// and J_z_x = J_z_pose J_pose_x.
template <typename Robot, typename Model>
Vec<Model::kDim> evaluateOn(const Model& model,
                            const Vec<Robot::kDim>& x,
                            const Vec<Model::Landmark::kDim>& landmark,
                            JacobianRef<Model::kDim, Robot::kDim> J_z_x,
                            JacobianRef<Model::kDim, Model::Landmark::kDim> J_z_l) {
  if constexpr (kRobotFitsDirectly<typename Model::Robot, Robot>) {
    return evaluate(model, x, landmark, J_z_x, J_z_l);
  } else {
    constexpr int P = Model::Robot::kDim;
    if (!J_z_x) return evaluate(model, Vec<P>(Robot::pose(x)), landmark, {}, J_z_l);
    Mat<P, Robot::kDim> J_pose;
    const Vec<P> pose = Robot::pose(x, J_pose);
    Mat<Model::kDim, P> J_z_pose;
    const Vec<Model::kDim> z = evaluate(model, pose, landmark, J_z_pose, J_z_l);
    *J_z_x = J_z_pose * J_pose;
    return z;
  }
}

}  // namespace sylva::detail
