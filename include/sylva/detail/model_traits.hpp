#pragma once
// IWYU pragma: private
/// @file
/// Compile-time detection of the optional parts of models, and the dispatch the filter uses:
/// the model's own residual (angle wrapping) if it has one, plain subtraction otherwise; a
/// parametrization's `normalize` if it has one; a robot's pose view and tangent. (Which
/// Jacobian a measurement model gets, analytic or automatic, is diff/evaluate.hpp.)

#include <type_traits>
#include <utility>

#include "sylva/core/jacobian_ref.hpp"
#include "sylva/core/types.hpp"

namespace sylva::detail {

/// A model written for `ModelRobot` sees a filter's robot `Robot` directly when the two are
/// the same type or `ModelRobot` is a base of `Robot`: `RangeBearing` is written for
/// `Pose2D`, so it serves `Unicycle2D`, `Odometry2D` and any robot whose state is the
/// planar pose. A model written for a robot *derived* from the filter's does not fit.
template <typename ModelRobot, typename Robot>
inline constexpr bool kRobotFitsDirectly =
    std::is_same_v<ModelRobot, Robot> || std::is_base_of_v<ModelRobot, Robot>;

/// A robot whose state holds more than a pose (biases, velocities) exposes the pose as a view:
/// `using Pose = Pose2D;` (the pose's own type) and
/// `static Vec<Pose::kDim> pose(const Vec<kDim>& x, JacobianRef<Pose::kDim, kDim> J = {})`.
/// Every model written for the pose type (or a base of it) then serves the robot: the filter
/// evaluates the model at pose(x) and chains the Jacobians.
template <typename Robot, typename = void>
struct HasPoseView : std::false_type {};
template <typename Robot>
struct HasPoseView<Robot, std::void_t<typename Robot::Pose>> : std::true_type {};

template <typename ModelRobot, typename Robot>
constexpr bool robotFitsThroughPose() {
  if constexpr (HasPoseView<Robot>::value) {
    return kRobotFitsDirectly<ModelRobot, typename Robot::Pose>;
  } else {
    return false;
  }
}

/// A model written for `ModelRobot` serves a filter whose robot is `Robot`: directly, or
/// through the robot's pose view.
template <typename ModelRobot, typename Robot>
inline constexpr bool kRobotFits =
    kRobotFitsDirectly<ModelRobot, Robot> || robotFitsThroughPose<ModelRobot, Robot>();

template <typename Model, typename = void>
struct HasAnalyticJacobians : std::false_type {};
template <typename Model>
struct HasAnalyticJacobians<
    Model,
    std::void_t<decltype(std::declval<const Model&>()(
        std::declval<const Vec<Model::Robot::kDim>&>(),
        std::declval<const Vec<Model::Landmark::kDim>&>(),
        std::declval<JacobianRef<Model::kDim, Model::Robot::kDim>>(),
        std::declval<JacobianRef<Model::kDim, Model::Landmark::kDim>>()))>> : std::true_type {};

template <typename Model, typename = void>
struct HasResidual : std::false_type {};
template <typename Model>
struct HasResidual<Model,
                   std::void_t<decltype(std::declval<const Model&>().residual(
                       std::declval<const Vec<Model::kDim>&>(),
                       std::declval<const Vec<Model::kDim>&>()))>> : std::true_type {};

/// A measurement model may declare which measurements it can make:
/// `static const char* measurementViolation(const Vec<kDim>& z)` returns nullptr for a
/// possible measurement and a short reason otherwise (TreeWidth: a width <= 0). The filter
/// refuses the others before it uses them.
template <typename Model, typename = void>
struct HasMeasurementDomain : std::false_type {};
template <typename Model>
struct HasMeasurementDomain<
    Model, std::void_t<decltype(Model::measurementViolation(std::declval<const Vec<Model::kDim>&>()))>>
    : std::true_type {};

template <typename Param, typename = void>
struct HasNormalize : std::false_type {};
template <typename Param>
struct HasNormalize<Param,
                    std::void_t<decltype(Param::normalize(
                        std::declval<Eigen::Ref<Vec<Param::kDim>>>()))>> : std::true_type {};

/// A parametrization may declare where its mean is meaningful:
/// `static const char* domainViolation(const Vec<kDim>& l)` returns nullptr inside the
/// domain and a short reason outside it (a tree radius <= 0). The filter rejects an update
/// whose posterior would leave the domain.
template <typename Param, typename = void>
struct HasDomain : std::false_type {};
template <typename Param>
struct HasDomain<Param,
                 std::void_t<decltype(Param::domainViolation(std::declval<const Vec<Param::kDim>&>()))>>
    : std::true_type {};

template <typename Robot, typename = void>
struct HasNormalizationJacobian : std::false_type {};
template <typename Robot>
struct HasNormalizationJacobian<
    Robot,
    std::void_t<decltype(Robot::normalizationJacobian(std::declval<const Vec<Robot::kDim>&>()))>>
    : std::true_type {};

/// A robot may provide the transition Jacobian of first-estimates linearization as
/// `firstEstimatesJacobian(from, to)` (every Pose2D robot; static) or, when it depends on the
/// step length and the model's settings, `firstEstimatesJacobian(from, to, dt) const`
/// (ConstantVelocity3D).
template <typename Robot, typename = void>
struct HasTwoPointFirstEstimatesJacobian : std::false_type {};
template <typename Robot>
struct HasTwoPointFirstEstimatesJacobian<
    Robot,
    std::void_t<decltype(std::declval<const Robot&>().firstEstimatesJacobian(std::declval<const Vec<Robot::kDim>&>(),
                                                                             std::declval<const Vec<Robot::kDim>&>()))>>
    : std::true_type {};
template <typename Robot, typename = void>
struct HasTimedFirstEstimatesJacobian : std::false_type {};
template <typename Robot>
struct HasTimedFirstEstimatesJacobian<
    Robot,
    std::void_t<decltype(std::declval<const Robot&>().firstEstimatesJacobian(std::declval<const Vec<Robot::kDim>&>(),
                                                                             std::declval<const Vec<Robot::kDim>&>(), 0.0))>>
    : std::true_type {};
template <typename Robot>
struct HasFirstEstimatesJacobian
    : std::bool_constant<HasTwoPointFirstEstimatesJacobian<Robot>::value || HasTimedFirstEstimatesJacobian<Robot>::value> {};

/// A state type that declares how the gauge of monocular SLAM moves it (core/gauge.hpp):
/// `gaugeDirections(x)`, static for a landmark, a const member for a robot.
template <typename T, typename = void>
struct HasGaugeDirections : std::false_type {};
template <typename T>
struct HasGaugeDirections<
    T,
    std::void_t<decltype(std::declval<const T&>().gaugeDirections(std::declval<const Vec<T::kDim>&>()))>>
    : std::true_type {};

/// The first-estimates transition Jacobian from the prediction `from` = x_{k|k-1} to the new
/// prediction `to` = x_{k+1|k} over `dt` seconds, through whichever form the robot has.
template <typename Robot>
Mat<Robot::kDim, Robot::kDim> firstEstimatesJacobian(const Robot& robot,
                                                     const Vec<Robot::kDim>& from,
                                                     const Vec<Robot::kDim>& to,
                                                     double dt) {
  if constexpr (HasTimedFirstEstimatesJacobian<Robot>::value) {
    return robot.firstEstimatesJacobian(from, to, dt);
  } else {
    (void)dt;
    return robot.firstEstimatesJacobian(from, to);
  }
}

/// The planar frame of the invariant EKF (LinearizationPoint::kInvariant): a robot declares
/// `static constexpr int kPlanarPosition` and `kPlanarHeading` (the state indices of its world
/// position [x, y] and of its heading), a landmark `kPlanarPosition` (its world position). The
/// entries not named are left out of the group: the invariant error is additive in them.
template <typename T, typename = void>
struct HasPlanarPosition : std::false_type {};
template <typename T>
struct HasPlanarPosition<T, std::void_t<decltype(T::kPlanarPosition)>> : std::true_type {};
template <typename T, typename = void>
struct HasPlanarHeading : std::false_type {};
template <typename T>
struct HasPlanarHeading<T, std::void_t<decltype(T::kPlanarHeading)>> : std::true_type {};

/// The robot a conversion is written for: its `Robot` when it names one, else the filter's
/// own (a conversion that ignores the robot need not name one).
template <typename Conversion, typename Robot, typename = void>
struct ConversionRobot {
  using type = Robot;
};
template <typename Conversion, typename Robot>
struct ConversionRobot<Conversion, Robot, std::void_t<typename Conversion::Robot>> {
  using type = typename Conversion::Robot;
};
template <typename Conversion, typename Robot>
using ConversionRobotT = typename ConversionRobot<Conversion, Robot>::type;

/// out = f(view, J_out_view) for a function written for `ModelRobot`, evaluated for a filter
/// whose robot is `Robot`: the view is the robot state itself when ModelRobot fits directly,
/// else the pose view Robot::pose(x), and J_out_x = J_out_view J_pose_x. Serves inverse
/// models (`Ekf::add`) and conversions (`Ekf::reparametrize`).
template <typename ModelRobot, typename Robot, int Rows, typename F>
Vec<Rows> throughRobotView(const Vec<Robot::kDim>& x, Mat<Rows, Robot::kDim>& J_out_x, F&& f) {
  if constexpr (kRobotFitsDirectly<ModelRobot, Robot>) {
    return f(x, J_out_x);
  } else {
    constexpr int P = ModelRobot::kDim;
    Mat<P, Robot::kDim> J_pose;
    const Vec<P> view = Robot::pose(x, J_pose);
    Mat<Rows, P> J_out_view;
    const Vec<Rows> out = f(view, J_out_view);
    J_out_x = J_out_view * J_pose;
    return out;
  }
}

/// A new landmark from its first measurement, l = g(view of x, z), for a filter whose robot
/// is `Robot`; J_l_x is chained through the pose view as in evaluateOn.
template <typename Robot, typename InverseModel>
Vec<InverseModel::Landmark::kDim> initializeOn(const InverseModel& inverse,
                                              const Vec<Robot::kDim>& x,
                                              const Vec<InverseModel::kMeasurementDim>& z,
                                              Mat<InverseModel::Landmark::kDim, Robot::kDim>& J_l_x,
                                              Mat<InverseModel::Landmark::kDim, InverseModel::kMeasurementDim>& J_l_z) {
  return throughRobotView<typename InverseModel::Robot, Robot>(
      x, J_l_x, [&](const auto& view, auto& J_l_view) { return inverse(view, z, J_l_view, J_l_z); });
}

/// The innovation z - z_hat, through the model's own `residual` when it has one.
template <typename Model>
Vec<Model::kDim> residual(const Model& model, const Vec<Model::kDim>& z, const Vec<Model::kDim>& z_hat) {
  if constexpr (HasResidual<Model>::value) {
    return model.residual(z, z_hat);
  } else {
    return z - z_hat;
  }
}

template <typename Param, typename = void>
struct HasDifference : std::false_type {};
template <typename Param>
struct HasDifference<Param,
                     std::void_t<decltype(Param::difference(std::declval<const Vec<Param::kDim>&>(),
                                                            std::declval<const Vec<Param::kDim>&>()))>>
    : std::true_type {};

/// a - b through the type's own `difference` (angles wrapped) when it has one.
template <typename Param>
Vec<Param::kDim> difference(const Vec<Param::kDim>& a, const Vec<Param::kDim>& b) {
  if constexpr (HasDifference<Param>::value) {
    return Param::difference(a, b);
  } else {
    return a - b;
  }
}

/// Brings a block back to its canonical range (angles wrapped, ...) if the type says how.
template <typename Param, typename Block>
void normalize(Block&& block) {
  if constexpr (HasNormalize<Param>::value) Param::normalize(block);
}

/// A robot whose state lives on a manifold declares `kTangentDim` (< kDim) and `plus`,
/// `minus`, `plusJacobian`, `minusJacobian` (motion/on_manifold.hpp): the filter keeps its
/// covariance on the tangent and chains every model's Jacobian through them.
template <typename Robot, typename = void>
struct HasTangent : std::false_type {};
template <typename Robot>
struct HasTangent<Robot, std::void_t<decltype(Robot::kTangentDim)>> : std::true_type {};

/// The robot's rows in the covariance: its tangent dimension, or kDim for a vector state.
template <typename Robot>
constexpr int tangentDim() {
  if constexpr (HasTangent<Robot>::value) {
    return Robot::kTangentDim;
  } else {
    return Robot::kDim;
  }
}

/// y (-) x for the robot: `minus` on a manifold, the wrapped difference of a vector state.
template <typename Robot>
Vec<tangentDim<Robot>()> robotMinus(const Vec<Robot::kDim>& y, const Vec<Robot::kDim>& x) {
  if constexpr (HasTangent<Robot>::value) {
    return Robot::minus(y, x);
  } else {
    return difference<Robot>(y, x);
  }
}

/// x (+) d for the robot: `plus` on a manifold, x + d (normalized) for a vector state.
template <typename Robot>
Vec<Robot::kDim> robotPlus(const Vec<Robot::kDim>& x, const Vec<tangentDim<Robot>()>& d) {
  if constexpr (HasTangent<Robot>::value) {
    return Robot::plus(x, d);
  } else {
    Vec<Robot::kDim> out = x + d;
    normalize<Robot>(out);
    return out;
  }
}

/// J (rows x kDim, w.r.t. the robot's state entries at x) as a Jacobian w.r.t. its tangent:
/// J plusJacobian(x) on a manifold, J itself for a vector state.
template <typename Robot, int Rows>
Mat<Rows, tangentDim<Robot>()> onTangent(const Mat<Rows, Robot::kDim>& J, const Vec<Robot::kDim>& x) {
  if constexpr (HasTangent<Robot>::value) {
    return J * Robot::plusJacobian(x);
  } else {
    (void)x;
    return J;
  }
}

}  // namespace sylva::detail
