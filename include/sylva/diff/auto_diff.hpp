#pragma once
/// @file
/// `AutoDiff<Model>`: gives a measurement model that only defines the Scalar-generic
/// prediction `predict<T>(robot, landmark)` the analytic signature
/// `operator()(robot, landmark, J_z_x, J_z_l)`, with both Jacobians computed by forward-mode
/// automatic differentiation (Eigen's AutoDiffScalar with a fixed-size derivative vector, so
/// nothing is allocated). `Ekf::update` applies this automatically to models without an
/// analytic Jacobian; wrap a model yourself to compare analytic and automatic Jacobians.

#include <Eigen/Core>
#include <unsupported/Eigen/AutoDiff>

#include "sylva/core/jacobian_ref.hpp"
#include "sylva/core/types.hpp"

namespace sylva {

template <typename Model_>
struct AutoDiff : Model_ {
  using Model = Model_;
  using Model_::Model_;
  AutoDiff() = default;
  explicit AutoDiff(const Model_& model) : Model_(model) {}

  static constexpr int kRobotDim = Model_::Robot::kDim;
  static constexpr int kLandmarkDim = Model_::Landmark::kDim;
  static constexpr int kInputDim = kRobotDim + kLandmarkDim;
  static constexpr int kOutputDim = Model_::kDim;
  using Derivatives = Eigen::Matrix<double, kInputDim, 1>;
  using Dual = Eigen::AutoDiffScalar<Derivatives>;

  Vec<kOutputDim> operator()(const Vec<kRobotDim>& robot,
                             const Vec<kLandmarkDim>& landmark,
                             JacobianRef<kOutputDim, kRobotDim> J_z_x = {},
                             JacobianRef<kOutputDim, kLandmarkDim> J_z_l = {}) const {
    if (!J_z_x && !J_z_l) return Model_::template predict<double>(robot, landmark);
    Vec<kRobotDim, Dual> robot_dual;
    Vec<kLandmarkDim, Dual> landmark_dual;
    for (int i = 0; i < kRobotDim; ++i) robot_dual[i] = Dual(robot[i], kInputDim, i);
    for (int i = 0; i < kLandmarkDim; ++i)
      landmark_dual[i] = Dual(landmark[i], kInputDim, kRobotDim + i);
    const Vec<kOutputDim, Dual> z_dual =
        Model_::template predict<Dual>(robot_dual, landmark_dual);
    Vec<kOutputDim> z;
    for (int r = 0; r < kOutputDim; ++r) {
      z[r] = z_dual[r].value();
      // A constant output has an empty derivative vector only for dynamic sizes; ours are fixed.
      if (J_z_x) (*J_z_x).row(r) = z_dual[r].derivatives().template head<kRobotDim>().transpose();
      if (J_z_l)
        (*J_z_l).row(r) = z_dual[r].derivatives().template tail<kLandmarkDim>().transpose();
    }
    return z;
  }
};

}  // namespace sylva
