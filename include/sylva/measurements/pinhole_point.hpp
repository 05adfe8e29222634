#pragma once
/// @file
/// `PinholePoint<Landmark>`: the pixel z = [u, v] at which a pinhole camera at a `Pose3D`
/// (any robot with a 3D pose view) sees a point landmark, for `Point3` (a world point) and `InverseDepth`
/// (Civera, Davison, Montiel 2008, "Inverse depth parametrization for monocular SLAM").
///
/// With the camera at t = r_WC and R = R(q / |q|) (camera -> world), the point in the camera
/// frame, or a vector along the ray to it, is
///
///   Point3:        h = R^T (p - t)
///   InverseDepth:  h = R^T (rho (a - t) + m(theta, phi))     (a the anchor, m as in
///                                                              landmarks/inverse_depth.hpp)
///
/// The second is the first multiplied by rho (p = a + m / rho): the projection only sees the
/// direction of h, so there is no division by rho and a point at infinity (rho = 0) projects
/// to its vanishing point. Projection (camera z forward, x right, y down; PinholeCamera):
///
///   u = cx + fx X / Z,   v = cy + fy Y / Z,   h = (X, Y, Z).
///
/// Jacobians (additive perturbations of the pose [t, q]):
///
///   dz/dh = [ fx / Z   0        -fx X / Z^2 ]
///           [ 0        fy / Z   -fy Y / Z^2 ]
///   Point3:        dh/dt = -R^T,   dh/dp = R^T
///   InverseDepth:  dh/dt = -rho R^T,  dh/da = rho R^T,  dh/dtheta = R^T dm/dtheta,
///                  dh/dphi = R^T dm/dphi,  dh/drho = R^T (a - t)
///   both:          dh/dq = D(q/|q|, w) (I - q q^T / |q|^2) / |q|
///
/// with w = p - t (resp. rho (a - t) + m) and D(q, w) = d(R(q)^T w)/dq from
/// `rotateTransposedJacobian`: as in TreeWidth, the model normalizes the state's
/// quaternion itself, so h does not change along q and the Jacobian carries the
/// normalization's.
///
/// Visibility: the model does not reject a point that projects outside the image; whether a
/// landmark is observable is the caller's decision (`PinholeCamera::contains`).
///
/// Errors (`sylva::Error`): NaN or Inf in the camera state or the landmark, or a non-finite
/// prediction -> kNonFinite. kDegenerateGeometry for a quaternion of norm < 1e-12 and a point
/// (or, for InverseDepth, the ray) behind the camera or on the
/// plane through its centre parallel to the image: Z <= 1e-6 max(|X|, |Y|, |Z|) (this also
/// covers a Point3 at the camera centre, h = 0). |X / Z| and |Y / Z| are therefore below 1e6.
/// An inverse depth rho < 0 is not rejected: a far point's estimate crosses zero while it
/// settles (the prior rho0 = 0.1 +- 0.5 covers negative values), and the ray h stays well
/// defined; refusing it would freeze the landmark for good. Only h's depth is checked.

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <type_traits>

#include "sylva/core/error.hpp"
#include "sylva/core/jacobian_ref.hpp"
#include "sylva/core/quaternion.hpp"
#include "sylva/core/scalar.hpp"
#include "sylva/core/types.hpp"
#include "sylva/landmarks/inverse_depth.hpp"
#include "sylva/landmarks/point3.hpp"
#include "sylva/measurements/pinhole_camera.hpp"
#include "sylva/motion/pose_3d.hpp"

namespace sylva {

namespace detail {

/// Shared pieces of the image-point models.
struct PinholePointMath {
  /// Below this norm the orientation quaternion is rejected.
  static constexpr double kMinQuaternionNorm = 1e-12;
  /// A point is in front of the camera when Z > kMinDepthRatio max(|X|, |Y|, |Z|), i.e. more
  /// than ~1e-6 rad in front of the plane through the camera centre parallel to the image.
  static constexpr double kMinDepthRatio = 1e-6;

  /// Throws kNonFinite for NaN/Inf in the camera state and kDegenerateGeometry for a
  /// (near) zero quaternion.
  template <typename T>
  static void checkCamera(const Vec<7, T>& camera, const char* who) {
    for (int i = 0; i < 7; ++i) {
      if (!std::isfinite(scalarValue(camera[i])))
        fail(ErrorCode::kNonFinite, std::string(who) + ": the camera state is not finite");
    }
    const double q_norm = std::sqrt(scalarValue(camera.template segment<4>(Pose3D::kQuaternion).squaredNorm()));
    if (!std::isfinite(q_norm))
      fail(ErrorCode::kNonFinite, std::string(who) + ": the quaternion's norm overflows");
    if (!(q_norm >= kMinQuaternionNorm)) {
      std::ostringstream os;
      os << who << ": the camera orientation quaternion has norm " << q_norm;
      fail(ErrorCode::kDegenerateGeometry, os.str());
    }
  }

  /// R(q / |q|)^T: world -> camera.
  template <typename T>
  static Mat<3, 3, T> worldToCamera(const Vec<7, T>& camera) {
    const Vec<4, T> q = camera.template segment<4>(Pose3D::kQuaternion) / camera.template segment<4>(Pose3D::kQuaternion).norm();
    return rotationMatrix<T>(q).transpose();
  }

  /// Pixel of the camera-frame vector h after the depth check; throws for a non-finite h or
  /// result.
  template <typename T>
  static Vec<2, T> project(const PinholeCamera& intrinsics, const Vec<3, T>& h, const char* who) {
    const double X = scalarValue(h[0]), Y = scalarValue(h[1]), Z = scalarValue(h[2]);
    if (!std::isfinite(X) || !std::isfinite(Y) || !std::isfinite(Z))
      fail(ErrorCode::kNonFinite, std::string(who) + ": the camera-frame point overflows");
    // max(|X|, |Y|, |Z|) as the length of h: free of overflow, within sqrt(3) of |h|.
    const double length = std::max(std::max(std::abs(X), std::abs(Y)), std::abs(Z));
    if (!(Z > kMinDepthRatio * length)) {
      std::ostringstream os;
      if (length == 0.0) {
        os << who << ": the point is at the camera centre";
      } else {
        os << who << ": the point is behind the camera or on the plane of its centre (depth " << Z
           << " for a ray of size " << length << ")";
      }
      fail(ErrorCode::kDegenerateGeometry, os.str());
    }
    const Vec<2, T> z = intrinsics.project<T>(h);
    if (!std::isfinite(scalarValue(z[0])) || !std::isfinite(scalarValue(z[1])))
      fail(ErrorCode::kNonFinite, std::string(who) + ": the predicted pixel is not finite");
    return z;
  }

  /// dz/dh (2x3) of the projection at h.
  template <int = 0>  // compiled only where called (docs/build-time.md)
  static Mat<2, 3> projectionJacobian(const PinholeCamera& intrinsics, const Vec<3>& h) {
    const double inv_z = 1.0 / h[2];
    Mat<2, 3> J;
    J << intrinsics.fx * inv_z, 0.0, -intrinsics.fx * h[0] * inv_z * inv_z,  //
        0.0, intrinsics.fy * inv_z, -intrinsics.fy * h[1] * inv_z * inv_z;
    return J;
  }

  /// d (R(q / |q|)^T w) / dq (3x4) for the stored (not necessarily unit) quaternion q.
  template <int = 0>  // compiled only where called (docs/build-time.md)
  static Mat<3, 4> rotateTransposedJacobianNormalized(const Vec<4>& q, const Vec<3>& w) {
    const double q_norm = q.norm();
    const Vec<4> q_unit = q / q_norm;
    const Mat<4, 4> J_unit = (Mat<4, 4>::Identity() - q_unit * q_unit.transpose()) / q_norm;
    return rotateTransposedJacobian(q_unit, w) * J_unit;
  }
};

}  // namespace detail

/// Image point of a landmark; specialized for `Point3` and `InverseDepth` below.
template <typename Landmark_>
struct PinholePoint {
  static_assert(!std::is_same_v<Landmark_, Landmark_>,
                "PinholePoint is defined for the landmark types Point3 and InverseDepth only");
};

/// Pixel of a world point: h = R^T (p - t).
template <>
struct PinholePoint<Point3> {
  using Robot = Pose3D;
  using Landmark = Point3;
  static constexpr int kDim = 2;  ///< [u_px, v_px]
  static constexpr const char* kName = "PinholePoint<Point3>";

  /// Throws (see `PinholeCamera::validate`) for invalid intrinsics.
  explicit PinholePoint(const PinholeCamera& camera) : camera_(camera) { camera_.validate(); }

  const PinholeCamera& camera() const { return camera_; }

  /// The camera-frame point R^T (p - t), generic in the scalar.
  template <typename T>
  static Vec<3, T> cameraPoint(const Vec<7, T>& camera, const Vec<3, T>& point) {
    return detail::PinholePointMath::worldToCamera<T>(camera) *
           Vec<3, T>(point - camera.template head<3>());
  }

  /// Predicted pixel [u, v], generic in the scalar for automatic differentiation.
  template <typename T>
  Vec<2, T> predict(const Vec<7, T>& camera, const Vec<3, T>& point) const {
    checkInputs(camera, point);
    return detail::PinholePointMath::project<T>(camera_, cameraPoint<T>(camera, point), kName);
  }

  /// Prediction with the analytic Jacobians J_z_x (2x7) and J_z_l (2x3).
  template <typename Tag = void>  // compiled only where called (core/deferred.hpp)
  Vec<2> operator()(const Vec<7>& camera,
                    const Vec<3>& point,
                    JacobianArg<2, 7, Tag> J_z_x = {},
                    JacobianArg<2, 3, Tag> J_z_l = {}) const {
    using Math = detail::PinholePointMath;
    checkInputs(camera, point);
    const Mat<3, 3> Rt = Math::worldToCamera<double>(camera);
    const Vec<3> w = point - camera.head<3>();
    const Vec<3> h = Rt * w;
    const Vec<2> z = Math::project<double>(camera_, h, kName);
    if (!J_z_x && !J_z_l) return z;
    const Mat<2, 3> J_z_h = Math::projectionJacobian(camera_, h);
    const Mat<2, 3> J_z_p = J_z_h * Rt;
    if (J_z_x) {
      auto J = *J_z_x;
      J.setZero();
      J.template leftCols<3>() = -J_z_p;
      J.template middleCols<4>(3) =
          J_z_h * Math::rotateTransposedJacobianNormalized(camera.segment<4>(Pose3D::kQuaternion), w);
    }
    if (J_z_l) *J_z_l = J_z_p;
    return z;
  }

 private:
  template <typename T>
  static void checkInputs(const Vec<7, T>& camera, const Vec<3, T>& point) {
    detail::PinholePointMath::checkCamera(camera, kName);
    for (int i = 0; i < 3; ++i) {
      if (!std::isfinite(scalarValue(point[i])))
        fail(ErrorCode::kNonFinite, std::string(kName) + ": the landmark is not finite");
    }
  }

  PinholeCamera camera_;
};

/// Pixel of an inverse-depth point: h = R^T (rho (a - t) + m(theta, phi)).
template <>
struct PinholePoint<InverseDepth> {
  using Robot = Pose3D;
  using Landmark = InverseDepth;
  static constexpr int kDim = 2;  ///< [u_px, v_px]
  static constexpr const char* kName = "PinholePoint<InverseDepth>";

  /// Throws (see `PinholeCamera::validate`) for invalid intrinsics.
  explicit PinholePoint(const PinholeCamera& camera) : camera_(camera) { camera_.validate(); }

  const PinholeCamera& camera() const { return camera_; }

  /// The camera-frame ray R^T (rho (a - t) + m), generic in the scalar: the point in the
  /// camera frame times rho (for rho > 0).
  template <typename T>
  static Vec<3, T> cameraRay(const Vec<7, T>& camera, const Vec<6, T>& l) {
    const Vec<3, T> w = l[5] * Vec<3, T>(l.template head<3>() - camera.template head<3>()) +
                        InverseDepth::direction<T>(l[3], l[4]);
    return detail::PinholePointMath::worldToCamera<T>(camera) * w;
  }

  /// Predicted pixel [u, v], generic in the scalar for automatic differentiation.
  template <typename T>
  Vec<2, T> predict(const Vec<7, T>& camera, const Vec<6, T>& l) const {
    checkInputs(camera, l);
    return detail::PinholePointMath::project<T>(camera_, cameraRay<T>(camera, l), kName);
  }

  /// Prediction with the analytic Jacobians J_z_x (2x7) and J_z_l (2x6).
  template <typename Tag = void>  // compiled only where called (core/deferred.hpp)
  Vec<2> operator()(const Vec<7>& camera,
                    const Vec<6>& l,
                    JacobianArg<2, 7, Tag> J_z_x = {},
                    JacobianArg<2, 6, Tag> J_z_l = {}) const {
    using Math = detail::PinholePointMath;
    checkInputs(camera, l);
    const Mat<3, 3> Rt = Math::worldToCamera<double>(camera);
    const double rho = l[5];
    const Vec<3> anchor_offset = l.head<3>() - camera.head<3>();  // a - t
    const Vec<3> w = rho * anchor_offset + InverseDepth::direction<double>(l[3], l[4]);
    const Vec<3> h = Rt * w;
    const Vec<2> z = Math::project<double>(camera_, h, kName);
    if (!J_z_x && !J_z_l) return z;
    const Mat<2, 3> J_z_h = Math::projectionJacobian(camera_, h);
    const Mat<2, 3> J_z_w = J_z_h * Rt;
    if (J_z_x) {
      auto J = *J_z_x;
      J.setZero();
      J.template leftCols<3>() = -rho * J_z_w;
      J.template middleCols<4>(3) =
          J_z_h * Math::rotateTransposedJacobianNormalized(camera.segment<4>(Pose3D::kQuaternion), w);
    }
    if (J_z_l) {
      auto J = *J_z_l;
      J.template leftCols<3>() = rho * J_z_w;
      J.template middleCols<2>(3) = J_z_w * InverseDepth::directionJacobian(l[3], l[4]);  // dm / d(theta, phi)
      J.col(5) = J_z_w * anchor_offset;
    }
    return z;
  }

 private:
  template <typename T>
  static void checkInputs(const Vec<7, T>& camera, const Vec<6, T>& l) {
    detail::PinholePointMath::checkCamera(camera, kName);
    for (int i = 0; i < 6; ++i) {
      if (!std::isfinite(scalarValue(l[i])))
        fail(ErrorCode::kNonFinite, std::string(kName) + ": the landmark is not finite");
    }
  }

  PinholeCamera camera_;
};

}  // namespace sylva
