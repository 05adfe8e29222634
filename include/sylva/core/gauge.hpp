#pragma once
/// @file
/// The gauge of monocular SLAM with vertical trunks: the transformations of the whole world
/// that no measurement of a camera can see. Moving the world (3), turning it about the
/// vertical (1) and scaling it about the origin (1) leave every image unchanged. Tilting it
/// does not, once trunks are known to stand vertical: the width of a trunk's base ellipse
/// changes with the tilt of the base circle (to first order for a camera pitched up or down,
/// to second order for one whose optical axis is horizontal), so the tilt is not part of the
/// gauge. (Point measurements alone would leave the tilt unobservable too; the gauge here is
/// what every camera model of sylva shares.)
///
/// A state type opts in to LinearizationPoint::kObservabilityConstrained by declaring the
/// directions in which these transformations move its state, one column each, in the order
///
///   [ translation x, y, z (world frame), rotation about world z, scale ]
///
/// i.e. the derivative at the identity of the transformation applied to the state: for a
/// world point p they are [ I, e_z x p, p ]. A landmark declares
/// `static Mat<kDim, kGaugeDim> gaugeDirections(const Vec<kDim>& l)`, a robot
/// `Mat<kDim, kGaugeDim> gaugeDirections(const State& x) const`. The tests check each against
/// numerical differentiation of the transformation, and that every camera model's Jacobian
/// annihilates them (tests/filter/observability_constrained.test.cpp).

namespace sylva {

/// Columns of a gauge direction matrix: translation (3), rotation about world z, scale.
inline constexpr int kGaugeDim = 5;

}  // namespace sylva
