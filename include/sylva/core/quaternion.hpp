#pragma once
/// @file
/// Quaternion helpers on plain 4-vectors q = (w, x, y, z), generic in the scalar so models
/// built on them can be differentiated automatically. Hamilton product, active rotation:
/// p' = R(q) p = q (0, p) q*.

#include <cmath>

#include "sylva/core/scalar.hpp"
#include "sylva/core/types.hpp"

namespace sylva {

/// Hamilton product a * b.
template <typename T>
Vec<4, T> quaternionProduct(const Vec<4, T>& a, const Vec<4, T>& b) {
  Vec<4, T> c;
  c[0] = a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3];
  c[1] = a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2];
  c[2] = a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1];
  c[3] = a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0];
  return c;
}

/// Unit quaternion of the rotation vector theta (axis * angle, radians): the exponential map.
/// Below 1e-8 rad a Taylor expansion keeps value and derivatives finite.
template <typename T>
Vec<4, T> quaternionFromRotationVector(const Vec<3, T>& theta) {
  using std::cos;
  using std::sin;
  using std::sqrt;
  const T angle2 = theta.squaredNorm();
  Vec<4, T> q;
  if (scalarValue(angle2) < 1e-16) {
    q[0] = T(1.0) - angle2 / T(8.0);
    q.template tail<3>() = theta * (T(0.5) - angle2 / T(48.0));
  } else {
    const T angle = sqrt(angle2);
    q[0] = cos(angle / T(2.0));
    q.template tail<3>() = theta * (sin(angle / T(2.0)) / angle);
  }
  return q;
}

/// The rotation vector of a unit quaternion (Log, the inverse of
/// quaternionFromRotationVector), the short way round: the angle is at most pi. Generic in
/// the scalar; below 1e-8 rad the atan series is written in s^2 = |v|^2, so that automatic
/// differentiation at the identity never meets sqrt(0).
template <typename T>
Vec<3, T> rotationVectorFromQuaternion(const Vec<4, T>& q_in) {
  using std::sqrt;
  const Vec<4, T> q = scalarValue(q_in[0]) < 0.0 ? Vec<4, T>(-q_in) : q_in;
  const Vec<3, T> v = q.template tail<3>();
  const T s2 = v.squaredNorm();
  if (scalarValue(s2) < 1e-16) return (T(2.0) / q[0]) * v * (T(1.0) - s2 / (T(3.0) * q[0] * q[0]));  // atan series
  const T s = sqrt(s2);
  return (T(2.0) * atan2Generic(s, q[0]) / s) * v;
}

/// Rotation matrix of a unit quaternion (w, x, y, z).
template <typename T>
Mat<3, 3, T> rotationMatrix(const Vec<4, T>& q) {
  const T w = q[0], x = q[1], y = q[2], z = q[3];
  Mat<3, 3, T> R;
  R << T(1) - T(2) * (y * y + z * z), T(2) * (x * y - w * z), T(2) * (x * z + w * y),  //
      T(2) * (x * y + w * z), T(1) - T(2) * (x * x + z * z), T(2) * (y * z - w * x),    //
      T(2) * (x * z - w * y), T(2) * (y * z + w * x), T(1) - T(2) * (x * x + y * y);
  return R;
}

/// R_right(b), the matrix of right multiplication: a (x) b = R_right(b) a.
template <int = 0>  // compiled only where called (docs/build-time.md)
Mat<4, 4> quaternionRightMatrix(const Vec<4>& b) {
  Mat<4, 4> R;
  R << b[0], -b[1], -b[2], -b[3],  //
      b[1], b[0], b[3], -b[2],     //
      b[2], -b[3], b[0], b[1],     //
      b[3], b[2], -b[1], b[0];
  return R;
}

/// [a]x, the matrix of the cross product: skewSymmetric(a) b = a x b.
template <int = 0>  // compiled only where called (docs/build-time.md)
Mat<3, 3> skewSymmetric(const Vec<3>& a) {
  Mat<3, 3> S;
  S << 0.0, -a[2], a[1],  //
      a[2], 0.0, -a[0],   //
      -a[1], a[0], 0.0;
  return S;
}

/// d (R(q)^T v) / d q (3x4) at a unit quaternion q = (w, x, y, z), v held fixed, from the
/// extension R(q)^T v = v - 2 w (u x v) + 2 u x (u x v), u = (x, y, z). Off the unit sphere
/// this differs from other extensions only in the direction of q, which a model that
/// normalizes q removes with the normalization's Jacobian (I - q q^T) / |q|.
template <int = 0>  // compiled only where called (docs/build-time.md)
Mat<3, 4> rotateTransposedJacobian(const Vec<4>& q, const Vec<3>& v) {
  const double w = q[0];
  const Vec<3> u = q.tail<3>();
  Mat<3, 4> J;
  const Vec<3> u_cross_v(u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]);
  J.col(0) = -2.0 * u_cross_v;
  J.rightCols<3>() = 2.0 * w * skewSymmetric(v) +
                     2.0 * (u.dot(v) * Mat<3, 3>::Identity() + u * v.transpose() - 2.0 * v * u.transpose());
  return J;
}

}  // namespace sylva
