#pragma once
/// @file
/// `OnManifold<Robot>`: a robot whose state holds one unit quaternion (`Robot::kQuaternion`,
/// the index of its w entry), with that quaternion treated as what it is, a point of SO(3),
/// and every other entry as a vector. The state lives on SO(3) x R^(kDim - 4); its
/// perturbations on the minimal tangent, one entry fewer than the state:
///
///   x (+) d   = [ a + d_a,  q (x) Exp(d_theta),  b + d_b ]            (plus)
///   y (-) x   = [ a_y - a_x,  Log(q_x^* (x) q_y),  b_y - b_x ]       (minus)
///
/// where a and b are the entries before and after the quaternion, and Exp and Log map a
/// rotation vector (radians, axis times angle, in the body frame: a right perturbation) to a
/// unit quaternion and back. For ConstantVelocity3D the tangent is
/// [dr (3), dtheta (3), dv (3), domega (3)]: the camera's pose has 6 degrees of freedom, and
/// so has its covariance, instead of 7 entries made singular by a normalization Jacobian.
///
/// The filter (sylva::Ekf) keeps the robot's mean on the manifold and its covariance on the
/// tangent at the mean. It composes each update through plus, and chains every Jacobian a
/// model gives for the state's entries through
///
///   plusJacobian(x)  = d (x (+) d) / d d   at d = 0   (kDim x kTangentDim), and
///   minusJacobian(x) = d (y (-) x) / d y   at y = x   (kTangentDim x kDim),
///
/// so motion models, sensors, conversions and first-estimates Jacobians written for the
/// plain robot serve this one unchanged: H_tangent = H plusJacobian(x), and the motion's
/// F_tangent = minusJacobian(f(x)) F plusJacobian(x). Every model written for `Robot` fits
/// (OnManifold<Robot> derives from it). A state whose quaternion is not of unit norm (within
/// 1e-6) is off the group: the filter refuses it (kOutOfDomain) rather than renormalize it.
///
/// With q = (w, v): plusJacobian's quaternion block is 1/2 [-v^T; w I + [v]x] (the columns of
/// q (x) (0, dtheta / 2)), minusJacobian's is 2 [-v, w I - [v]x] (the vector part of
/// q^* (x) dq, doubled); their product is I.

#include <cmath>
#include <sstream>

#include "sylva/core/quaternion.hpp"
#include "sylva/core/types.hpp"

namespace sylva {

template <typename Robot_>
struct OnManifold : Robot_ {
  static_assert(Robot_::kQuaternion >= 0 && Robot_::kQuaternion + 4 <= Robot_::kDim,
                "OnManifold needs a robot with one unit quaternion at kQuaternion");
  using Base = Robot_;
  static constexpr int kDim = Robot_::kDim;
  static constexpr int kTangentDim = Robot_::kDim - 1;
  static constexpr int kQuaternion = Robot_::kQuaternion;
  using State = Vec<kDim>;
  using Tangent = Vec<kTangentDim>;

  OnManifold() = default;
  /// The plain robot's settings (a ConstantVelocity3D's velocity frame, say).
  explicit OnManifold(const Robot_& robot) : Robot_(robot) {}

  /// x (+) d (see the top of this file). The result's quaternion is of unit norm.
  static State plus(const State& x, const Tangent& d) {
    constexpr int q = kQuaternion;
    constexpr int after = kDim - q - 4;
    State out;
    out.template head<q>() = x.template head<q>() + d.template head<q>();
    const Vec<4> rotated = quaternionProduct<double>(Vec<4>(x.template segment<4>(q)),
                                                     quaternionFromRotationVector<double>(Vec<3>(d.template segment<3>(q))));
    out.template segment<4>(q) = rotated / rotated.norm();
    out.template tail<after>() = x.template tail<after>() + d.template tail<after>();
    return out;
  }

  /// y (-) x: the d with x (+) d = y, the rotation the short way round.
  static Tangent minus(const State& y, const State& x) {
    constexpr int q = kQuaternion;
    constexpr int after = kDim - q - 4;
    const Vec<4> qx = x.template segment<4>(q);
    const Vec<4> qx_conj(qx[0], -qx[1], -qx[2], -qx[3]);
    Tangent d;
    d.template head<q>() = y.template head<q>() - x.template head<q>();
    d.template segment<3>(q) = rotationVectorFromQuaternion(quaternionProduct<double>(qx_conj, Vec<4>(y.template segment<4>(q))));
    d.template tail<after>() = y.template tail<after>() - x.template tail<after>();
    return d;
  }

  /// d (x (+) d) / d d at d = 0.
  static Mat<kDim, kTangentDim> plusJacobian(const State& x) {
    constexpr int q = kQuaternion;
    Mat<kDim, kTangentDim> J = Mat<kDim, kTangentDim>::Zero();
    J.template topLeftCorner<q, q>().setIdentity();
    const Vec<4> qx = x.template segment<4>(q);
    const Vec<3> v = qx.tail<3>();
    J.template block<1, 3>(q, q) = -0.5 * v.transpose();
    J.template block<3, 3>(q + 1, q) = 0.5 * (qx[0] * Mat<3, 3>::Identity() + skewSymmetric(v));
    J.template bottomRightCorner<kDim - q - 4, kDim - q - 4>().setIdentity();
    return J;
  }

  /// d (y (-) x) / d y at y = x.
  static Mat<kTangentDim, kDim> minusJacobian(const State& x) {
    constexpr int q = kQuaternion;
    Mat<kTangentDim, kDim> J = Mat<kTangentDim, kDim>::Zero();
    J.template topLeftCorner<q, q>().setIdentity();
    const Vec<4> qx = x.template segment<4>(q);
    const Vec<3> v = qx.tail<3>();
    J.template block<3, 1>(q, q) = -2.0 * v;
    J.template block<3, 3>(q, q + 1) = 2.0 * (qx[0] * Mat<3, 3>::Identity() - skewSymmetric(v));
    J.template bottomRightCorner<kDim - q - 4, kDim - q - 4>().setIdentity();
    return J;
  }

  /// nullptr for a state on the group; else why it is not (its quaternion's norm is not 1).
  static const char* domainViolation(const State& x) {
    const double n = x.template segment<4>(kQuaternion).norm();
    if (std::abs(n - 1.0) <= 1e-6) return nullptr;
    return "the orientation quaternion is not of unit norm (a state off the group is refused, not renormalized)";
  }
};

}  // namespace sylva
