#pragma once
/// @file
/// Where the filter linearizes its models (`BasicEkf::setLinearizationPoint`, filter/ekf.hpp)
/// and when its iterated update stops (`BasicEkf::setIteratedUpdate`). docs/filter.md describes
/// each policy and what it costs.

namespace sylva {

/// Where the filter evaluates the Jacobians of its motion and measurement models.
/// Predictions h(x) are always taken at the current estimate; only the Jacobians move.
/// See docs/filter.md ("First-estimates Jacobians").
enum class LinearizationPoint {
  /// The textbook EKF: every Jacobian at the latest estimate.
  kCurrentEstimate,
  /// First-estimates Jacobians (FEJ; Huang, Mourikis and Roumeliotis 2010): measurement
  /// Jacobians at each landmark's first estimate and the robot's latest prediction, the
  /// transition Jacobian at the latest two predictions. The linearized system then keeps the
  /// unobservable global pose unobservable, so heading confidence cannot come from
  /// linearization alone (the textbook EKF's known overconfidence). Needs a robot with
  /// `firstEstimatesJacobian(from, to)` (every `Pose2D` robot) or
  /// `firstEstimatesJacobian(from, to, dt)` (ConstantVelocity3D).
  kFirstEstimates,
  /// A diagnostic for simulations: predict and update linearized about the TRUE state, which
  /// the caller hands over (`setIdealRobot` before each predict and after it,
  /// `setIdealLandmark` for each landmark it updates). Jacobians are taken there, and so are
  /// the predictions, to first order: f(x_true) + F (x - x_true) and h(x_true) + H (x - x_true).
  /// The filter is then the Kalman filter of the system linearized along the true trajectory,
  /// free of linearization error however far the estimate strays; what inconsistency is left
  /// comes from the models (noise, measurement model error, gating). Taking only the Jacobians
  /// at the truth and the predictions at the estimate would not do: once the estimate strays
  /// along a weakly observable direction (monocular scale), the two stop agreeing and the
  /// filter diverges for that reason alone. add and reparametrize still use the estimate.
  /// Linearizing at a state that was not handed over is refused (kInvalidArgument).
  kIdeal,
  /// The iterated EKF (Bell and Cathey 1993; MRPT's kfIKF): each update takes Gauss-Newton
  /// steps, relinearizing the measurement models at the updated estimate until it stops moving
  /// (`IteratedUpdate`), then updates the covariance with the Jacobians of the last iterate.
  /// Worth most where one linearization is poor: a landmark whose depth is still a prior
  /// (inverse-depth initialization). The motion keeps the textbook Jacobian.
  kIterated,
  /// The right-invariant EKF of planar SLAM (Barrau and Bonnabel 2015, "An EKF-SLAM
  /// algorithm with consistency properties"): the error of the robot pose and of every
  /// landmark position lives in the group SE_{1+k}(2), eta = chi chi_hat^-1, where the
  /// linearized unobservable directions (a global translation and rotation) do not depend on
  /// the estimate, so no update can gain information along them. The covariance stays stored
  /// in the additive coordinates delta = T(x_hat) xi of the invariant error xi:
  ///   delta_theta = xi_theta,   delta_p = xi_p + xi_theta J p_hat   (J: +90 degree rotation)
  /// for the robot's position and each landmark's. Predict and the innovation are then the
  /// textbook ones: for a motion that is a rigid increment in the robot frame (every Pose2D
  /// robot) the textbook transition Jacobian is exactly T(x+) T(x)^-1, the invariant error
  /// propagating with the identity. The update differs: its correction xi = T(x_hat)^-1 K nu
  /// is applied through the group's exponential, p+ = R(xi_theta) p_hat + V(xi_theta) xi_p,
  /// and the covariance is carried to the new estimate, P+ = M P M^T with
  /// M = T(x+) T(x_hat)^-1 (a rank-2 correction, O(n^2)). Needs a robot that declares
  /// kPlanarPosition and kPlanarHeading (every Pose2D robot) and landmarks that all declare
  /// kPlanarPosition (Point2, TreeXYR); else setLinearizationPoint refuses it. See
  /// docs/filter.md ("Invariant EKF").
  kInvariant,
  /// Observability-constrained updates for monocular SLAM: every Jacobian at the latest
  /// estimate (as kCurrentEstimate), and after each update the covariance is carried from the
  /// gauge directions at the estimate the update linearized at (x-) to those at the new
  /// estimate (x+). N(x) is the n x 5 matrix of the directions in which moving, turning about
  /// the vertical and scaling the world move the state (core/gauge.hpp). The update's
  /// Jacobians satisfy H N(x-) = 0, so it adds no information along N(x-); without the
  /// transport the next update, which sees N(x+), would find information there that no
  /// measurement gave (the textbook EKF's over-confidence; Huang, Mourikis and Roumeliotis
  /// 2010). The transport is P+ <- T P+ T^T with T = I + (N(x+) - N(x-)) A, where
  /// A = (N_r^T N_r)^-1 N_r^T E_r reads the gauge part of a perturbation off the robot's
  /// coordinates (N_r: the robot's rows of N(x-), E_r: selects them; `setGaugeInverse` can
  /// make it the whole state's, GaugeInverse), so T N(x-) = N(x+) and
  /// the information along N(x+) after the update is what the prior held along N(x-). This
  /// keeps the invariant of Huang et al.'s observability-constrained EKF by moving the
  /// covariance instead of the Jacobians; a motion model that commutes with the gauge (as
  /// ConstantVelocity3D does) carries N(x) into N(f(x)) by its textbook Jacobian, so predict
  /// needs nothing. Where the robot's rows are degenerate (a camera at rest) A uses all of N,
  /// and where N^T N is singular too there is no transport. O(n^2) per update (a rank-10
  /// correction), no allocation once the workspace has grown. Needs a robot and landmark types
  /// that all declare `gaugeDirections` (ConstantVelocity3D; Point3, InverseDepth, TreeXYZR,
  /// InverseDepthRadius); else setLinearizationPoint refuses it. A consistent monocular
  /// filter keeps the map's position and scale uncertain: rules that judge a landmark's
  /// marginal uncertainty (TreeLifeCycle's) should judge it given the robot
  /// (landmarkCovarianceGivenRobot). See docs/filter.md ("Observability-constrained updates").
  kObservabilityConstrained,
};

/// When the iterated update (LinearizationPoint::kIterated) stops: after `max_iterations`
/// linearizations (the first at the prior estimate), or once no coordinate of the robot or of
/// an observed landmark moved by more than `tolerance` prior standard deviations in a step.
struct IteratedUpdate {
  int max_iterations = 10;
  double tolerance = 1e-3;
};

}  // namespace sylva
