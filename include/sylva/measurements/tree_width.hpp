#pragma once
/// @file
/// `TreeWidth`: the image of a tree trunk's base circle seen by a pinhole camera at a
/// `Pose3D` (any robot with a 3D pose view: `ConstantVelocity3D`, ...), for a `TreeXYZR` landmark (tree-width thesis, Sec. 3.2, 3.4 and
/// App. A.1-A.2). The measurement is z = [u, v, w] in pixels: the centre of the image
/// ellipse of the base circle and its horizontal extent (max u - min u).
///
/// Geometry. The base circle has centre c = (x, y, z) and radius r and lies in the plane
/// z = const (world z up). Its points are c + a e1 + b e2 with a^2 + b^2 = r^2, i.e. the
/// conic C_c = diag(1, 1, -r^2) in the plane coordinates (a, b, 1) (eq. 3.2). With the
/// camera at t = r_WC and R = R(q_WC) (camera -> world) the plane maps to the image by the
/// homography (eq. 3.1-3.4; the thesis' world has y up and selects T's columns x and z, ours
/// has z up and takes x and y)
///
///   H = K [ R^T e1,  R^T e2,  R^T (c - t) ],
///
/// and the image conic is C_e = H^-T C_c H^-1 (3.5). H is never inverted: the dual conic
/// (A.2-A.21) is pushed forward instead,
///
///   D = C_e^-1 ~ H C_c^-1 H^T ~ K D_C K^T,   D_C = r^2 (I - n n^T) - C C^T,
///
/// with n = R^T e3 (world up in the camera frame) and C = R^T (c - t) (the circle's centre in
/// the camera frame), because R^T e1 e1^T R + R^T e2 e2^T R = I - n n^T. The centre of an
/// ellipse is the pole of the line at infinity, (D_13 / D_33, D_23 / D_33), and its vertical
/// tangents u = const solve D_11 - 2 u D_13 + u^2 D_33 = 0. With d_ij the entries of D_C:
///
///   u = cx + fx d13 / d33,   v = cy + fy d23 / d33,   w = 2 fx sqrt(d13^2 - d11 d33) / (-d33)
///
///   d11 = r^2 (n2^2 + n3^2) - C1^2,   d13 = -r^2 n1 n3 - C1 C3,
///   d23 = -r^2 n2 n3 - C2 C3,         d33 = r^2 (n1^2 + n2^2) - C3^2.
///
/// (For unit n, 1 - n1^2 = n2^2 + n3^2 and 1 - n3^2 = n1^2 + n2^2; the squares-of-the-other-
/// components form stays exact when n is unit only to round-off.)
///
/// Jacobian (eq. 3.18-3.22, A.22-A.37, here derived again): the chain
/// z <- m = [d11, d13, d23, d33] <- p = [n, C, r] <- (camera, tree). The thesis' printed
/// matrices are not used; the tests compare this Jacobian with central differences and
/// with automatic differentiation.
///
///   dz/dm: du = fx/d33 dd13 - fx d13/d33^2 dd33, dv likewise with fy, d23,
///          dw = fx/s dd11 - 2 fx d13/(d33 s) dd13 + (fx d11/(d33 s) + 2 fx s/d33^2) dd33,
///          s = sqrt(d13^2 - d11 d33)
///   dC/dt = -R^T, dC/dc = R^T, dC/dq and dn/dq from d(R(q)^T v)/dq (see
///   `rotateTransposedJacobian` in core/quaternion.hpp).
///
/// The quaternion. The model uses R(q / |q|): the state's quaternion is normalized inside
/// the model, so h does not change along q and J_z_x includes the normalization's Jacobian
/// (I - q q^T / |q|^2) / |q|. J_z_x is taken w.r.t. the pose
/// [t, q]; the filter chains it through the robot's pose view.
///
/// Degenerate geometry throws `kDegenerateGeometry` with the reason: r <= 0; the camera
/// inside the trunk (horizontal distance from the camera to the trunk axis <= r); a point of
/// the base circle at camera depth <= 0 (behind the camera or crossing the image plane: the
/// minimum depth is C3 - r sqrt(n1^2 + n2^2), and it is > 0 exactly when the image conic is
/// an ellipse, d33 < 0); an image ellipse of zero width (the circle seen edge-on with the
/// horizon vertical in the image); a quaternion of norm < 1e-12. NaN or Inf in the input or
/// the prediction throws `kNonFinite`.

#include <cmath>
#include <sstream>

#include "sylva/core/error.hpp"
#include "sylva/core/jacobian_ref.hpp"
#include "sylva/core/quaternion.hpp"
#include "sylva/core/scalar.hpp"
#include "sylva/core/types.hpp"
#include "sylva/landmarks/tree_xyzr.hpp"
#include "sylva/measurements/pinhole_camera.hpp"
#include "sylva/motion/pose_3d.hpp"

namespace sylva {

struct TreeWidth {
  using Robot = Pose3D;
  using Landmark = TreeXYZR;
  static constexpr int kDim = 3;  ///< [u_px, v_px, width_px]
  static constexpr const char* kName = "TreeWidth";
  /// Below this norm the orientation quaternion is rejected.
  static constexpr double kMinQuaternionNorm = 1e-12;

  /// Throws (see `PinholeCamera::validate`) for invalid intrinsics.
  explicit TreeWidth(const PinholeCamera& camera) : camera_(camera) { camera_.validate(); }

  /// A width <= 0 pixels is no width a trunk can have: the filter refuses it (as
  /// InverseTreeWidth does) instead of fusing it into a shrinking radius.
  static const char* measurementViolation(const Vec<3>& z) {
    return z[2] > 0.0 ? nullptr : "the measured width must be > 0 pixels";
  }

  const PinholeCamera& camera() const { return camera_; }

  /// Predicted [u, v, w] (pixels), generic in the scalar for automatic differentiation.
  template <typename T>
  Vec<3, T> predict(const Vec<7, T>& camera, const Vec<4, T>& tree) const {
    using std::sqrt;
    checkInputs(camera, tree);
    const Vec<4, T> q = camera.template segment<4>(Pose3D::kQuaternion) / camera.template segment<4>(Pose3D::kQuaternion).norm();
    const Mat<3, 3, T> Rt = rotationMatrix<T>(q).transpose();
    const Vec<3, T> n = Rt.col(2);
    const Vec<3, T> C = Rt * Vec<3, T>(tree.template head<3>() - camera.template head<3>());
    const T r = tree[3];
    const T r2 = r * r;
    const T d11 = r2 * (n[1] * n[1] + n[2] * n[2]) - C[0] * C[0];
    const T d13 = -r2 * n[0] * n[2] - C[0] * C[2];
    const T d23 = -r2 * n[1] * n[2] - C[1] * C[2];
    const T d33 = r2 * (n[0] * n[0] + n[1] * n[1]) - C[2] * C[2];
    checkEllipse(scalarValue(r),
                 scalarValue(n[0]),
                 scalarValue(n[1]),
                 scalarValue(C[2]),
                 scalarValue(d11),
                 scalarValue(d13),
                 scalarValue(d33));
    Vec<3, T> z;
    z[0] = T(camera_.cx) + T(camera_.fx) * d13 / d33;
    z[1] = T(camera_.cy) + T(camera_.fy) * d23 / d33;
    z[2] = T(-2.0 * camera_.fx) * sqrt(d13 * d13 - d11 * d33) / d33;
    if (!std::isfinite(scalarValue(z[0])) || !std::isfinite(scalarValue(z[1])) ||
        !std::isfinite(scalarValue(z[2])))
      fail(ErrorCode::kNonFinite, "TreeWidth: the predicted measurement is not finite");
    return z;
  }

  /// Prediction with the analytic Jacobians J_z_x (3x7) and J_z_l (3x4).
  template <typename Tag = void>  // compiled only where called (core/deferred.hpp)
  Vec<3> operator()(const Vec<7>& camera,
                    const Vec<4>& tree,
                    JacobianArg<3, 7, Tag> J_z_x = {},
                    JacobianArg<3, 4, Tag> J_z_l = {}) const {
    const Vec<3> z = predict<double>(camera, tree);
    if (!J_z_x && !J_z_l) return z;
    const double q_norm = camera.segment<4>(Pose3D::kQuaternion).norm();
    const Vec<4> q = camera.segment<4>(Pose3D::kQuaternion) / q_norm;
    const Mat<3, 3> Rt = rotationMatrix<double>(q).transpose();
    const Vec<3> delta = tree.head<3>() - camera.head<3>();
    const Vec<3> n = Rt.col(2);
    const Vec<3> C = Rt * delta;
    const double r = tree[3];
    const double r2 = r * r;
    const double d11 = r2 * (n[1] * n[1] + n[2] * n[2]) - C[0] * C[0];
    const double d13 = -r2 * n[0] * n[2] - C[0] * C[2];
    const double d23 = -r2 * n[1] * n[2] - C[1] * C[2];
    const double d33 = r2 * (n[0] * n[0] + n[1] * n[1]) - C[2] * C[2];
    const double s = std::sqrt(d13 * d13 - d11 * d33);
    const double fx = camera_.fx;
    const double fy = camera_.fy;

    // dz / d[d11, d13, d23, d33]
    Mat<3, 4> J_z_m;
    J_z_m << 0.0, fx / d33, 0.0, -fx * d13 / (d33 * d33),  //
        0.0, 0.0, fy / d33, -fy * d23 / (d33 * d33),       //
        fx / s, -2.0 * fx * d13 / (d33 * s), 0.0, fx * d11 / (d33 * s) + 2.0 * fx * s / (d33 * d33);
    // d[d11, d13, d23, d33] / d[n (3), C (3), r]
    const double n23 = n[1] * n[1] + n[2] * n[2];  // 1 - n1^2
    const double n12 = n[0] * n[0] + n[1] * n[1];  // 1 - n3^2
    Mat<4, 7> J_m_p;
    J_m_p << 0.0, 2 * r2 * n[1], 2 * r2 * n[2], -2 * C[0], 0.0, 0.0, 2 * r * n23,  //
        -r2 * n[2], 0.0, -r2 * n[0], -C[2], 0.0, -C[0], -2 * r * n[0] * n[2],      //
        0.0, -r2 * n[2], -r2 * n[1], 0.0, -C[2], -C[1], -2 * r * n[1] * n[2],      //
        2 * r2 * n[0], 2 * r2 * n[1], 0.0, 0.0, 0.0, -2 * C[2], 2 * r * n12;
    const Mat<3, 7> J_z_p = J_z_m * J_m_p;

    if (J_z_x) {
      // d q_unit / d q = (I - q q^T) / |q|
      const Mat<4, 4> J_unit = (Mat<4, 4>::Identity() - q * q.transpose()) / q_norm;
      const Mat<3, 4> J_n_q = rotateTransposedJacobian(q, Vec<3>::UnitZ()) * J_unit;
      const Mat<3, 4> J_C_q = rotateTransposedJacobian(q, delta) * J_unit;
      auto J = *J_z_x;
      J.setZero();
      J.template leftCols<3>() = -J_z_p.middleCols<3>(3) * Rt;
      J.template middleCols<4>(3) = J_z_p.leftCols<3>() * J_n_q + J_z_p.middleCols<3>(3) * J_C_q;
    }
    if (J_z_l) {
      auto J = *J_z_l;
      J.template leftCols<3>() = J_z_p.middleCols<3>(3) * Rt;
      J.col(3) = J_z_p.col(6);
    }
    return z;
  }

 private:
  template <typename T>
  static void checkInputs(const Vec<7, T>& camera, const Vec<4, T>& tree) {
    for (int i = 0; i < 7; ++i) {
      if (!std::isfinite(scalarValue(camera[i])))
        fail(ErrorCode::kNonFinite, "TreeWidth: the camera state is not finite");
    }
    for (int i = 0; i < 4; ++i) {
      if (!std::isfinite(scalarValue(tree[i])))
        fail(ErrorCode::kNonFinite, "TreeWidth: the tree landmark is not finite");
    }
    const double r = scalarValue(tree[3]);
    if (!(r > 0.0)) {
      std::ostringstream os;
      os << "TreeWidth: trunk radius " << r << " m must be > 0";
      fail(ErrorCode::kDegenerateGeometry, os.str());
    }
    const double q_norm = std::sqrt(scalarValue(camera.template segment<4>(Pose3D::kQuaternion).squaredNorm()));
    if (!(q_norm >= kMinQuaternionNorm)) {
      std::ostringstream os;
      os << "TreeWidth: camera orientation quaternion has norm " << q_norm;
      fail(ErrorCode::kDegenerateGeometry, os.str());
    }
    const double dx = scalarValue(tree[0]) - scalarValue(camera[0]);
    const double dy = scalarValue(tree[1]) - scalarValue(camera[1]);
    const double horizontal = std::sqrt(dx * dx + dy * dy);
    if (!(horizontal > r)) {
      std::ostringstream os;
      os << "TreeWidth: camera inside the trunk (horizontal distance " << horizontal
         << " m to the trunk axis, radius " << r << " m)";
      fail(ErrorCode::kDegenerateGeometry, os.str());
    }
  }

  template <int = 0>  // compiled only where called (docs/build-time.md)
  static void checkEllipse(
      double r, double n1, double n2, double C3, double d11, double d13, double d33) {
    const double min_depth = C3 - r * std::sqrt(n1 * n1 + n2 * n2);
    if (!(min_depth > 0.0) || !(d33 < 0.0)) {
      std::ostringstream os;
      os << "TreeWidth: the trunk base circle is not entirely in front of the camera (minimum "
            "depth "
         << min_depth << " m): its image is not an ellipse";
      fail(ErrorCode::kDegenerateGeometry, os.str());
    }
    if (!(d13 * d13 - d11 * d33 > 0.0)) {
      fail(ErrorCode::kDegenerateGeometry,
           "TreeWidth: the image of the trunk base has zero width (circle seen edge-on with a "
           "vertical horizon)");
    }
  }

  PinholeCamera camera_;
};

}  // namespace sylva
