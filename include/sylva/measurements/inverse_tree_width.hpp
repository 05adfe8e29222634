#pragma once
/// @file
/// `InverseTreeWidth`: the trunk radius of a tree whose base centre is known, from the width
/// of its base ellipse in one image (tree-width thesis, Sec. 3.3, eq. 3.12-3.17, and its
/// Jacobian, eq. 3.27-3.32). Used as the measurement-aided conversion XYZ -> XYZ-R
/// (`Ekf::reparametrize(id, conversion, z, noise)`, the last step of the life cycle of
/// Fig. 3.3): the new landmark is [x, y, z, r(camera, xyz, w)].
///
/// The thesis builds an approximate ellipse with the measured width and the shape of the
/// predicted one and maps it back through H^-1 (3.12-3.16), assuming the radius does not
/// change the ellipse's orientation. Here the same idea is solved exactly, without H^-1. In
/// the notation of tree_width.hpp the dual image conic's entries are affine in s = r^2:
///
///   d11 = s a11 - C1^2,  d13 = s a13 - C1 C3,  d33 = s a33 - C3^2,
///   a11 = n2^2 + n3^2,   a13 = -n1 n3,         a33 = n1^2 + n2^2,
///
/// and the width satisfies (w / 2 fx)^2 d33^2 = d13^2 - d11 d33 (from eq. A.21 / 3.11). The
/// right-hand side is k s^2 + b s with k = a13^2 - a11 a33 (= -n2^2 for a unit n) and
/// b = a11 C3^2 + a33 C1^2 - 2 a13 C1 C3, so with W = w / (2 fx)
///
///   (W^2 a33^2 - k) s^2 - (2 W^2 a33 C3^2 + b) s + W^2 C3^4 = 0.
///
/// Both roots are positive; the width grows from 0 at s = 0 to infinity where d33 -> 0 (the
/// ellipse opens into a parabola), and at that point the left side equals -d13^2 <= 0, so
/// the smaller root is the ellipse and the larger one a hyperbola. It is taken in the
/// cancellation-free form s = 2 c / (b' + sqrt(b'^2 - 4 a c)), which also covers a = 0 (a
/// camera looking straight down).
///
/// Jacobian. As the thesis does (eq. 3.29-3.32), it comes from the forward model's: with
/// w = f(x, c, r) and J_w_r = dw/dr > 0,
///
///   dr/dx = -J_w_x / J_w_r,   dr/dc = -J_w_c / J_w_r,   dr/dw = 1 / J_w_r,
///
/// exact here because r solves f(x, c, r) = w exactly (implicit function theorem). The
/// image position (u, v) of z is not used: dr/du = dr/dv = 0. Tests compare this with
/// central differences of `radius`.
///
/// Errors: non-finite input (kNonFinite); w <= 0; the base centre not in front of the camera;
/// a width that no radius reproduces in valid geometry (the camera would be inside the
/// trunk, or the base circle would cross the image plane) -> kDegenerateGeometry with the
/// forward model's reason.

#include <cmath>
#include <sstream>
#include <string>

#include "sylva/core/error.hpp"
#include "sylva/core/jacobian_ref.hpp"
#include "sylva/core/quaternion.hpp"
#include "sylva/core/scalar.hpp"
#include "sylva/core/types.hpp"
#include "sylva/landmarks/point3.hpp"
#include "sylva/landmarks/tree_xyzr.hpp"
#include "sylva/measurements/pinhole_camera.hpp"
#include "sylva/measurements/tree_width.hpp"
#include "sylva/motion/pose_3d.hpp"

namespace sylva {

struct InverseTreeWidth {
  using Robot = Pose3D;
  using From = Point3;
  using To = TreeXYZR;
  static constexpr int kMeasurementDim = 3;  ///< the TreeWidth measurement [u, v, w]; w is used
  static constexpr const char* kName = "InverseTreeWidth";

  /// Throws (see `PinholeCamera::validate`) for invalid intrinsics.
  explicit InverseTreeWidth(const PinholeCamera& camera) : forward_(camera) {}

  const PinholeCamera& camera() const { return forward_.camera(); }

  /// The radius (m) for which a trunk with base centre `base` has image width `width_px`
  /// seen from `camera`. Generic in the scalar; checks only what the closed form needs
  /// (use operator() for the full validation).
  template <typename T>
  T radius(const Vec<7, T>& camera, const Vec<3, T>& base, const T& width_px) const {
    using std::sqrt;
    const Vec<4, T> q = camera.template segment<4>(Pose3D::kQuaternion) / camera.template segment<4>(Pose3D::kQuaternion).norm();
    const Mat<3, 3, T> Rt = rotationMatrix<T>(q).transpose();
    const Vec<3, T> n = Rt.col(2);
    const Vec<3, T> C = Rt * Vec<3, T>(base - camera.template head<3>());
    if (!(scalarValue(C[2]) > 0.0))
      fail(ErrorCode::kDegenerateGeometry, "InverseTreeWidth: the tree's base centre is not in front of the camera");
    const T a11 = n[1] * n[1] + n[2] * n[2];
    const T a13 = -n[0] * n[2];
    const T a33 = n[0] * n[0] + n[1] * n[1];
    const T k = a13 * a13 - a11 * a33;
    const T b = a11 * C[2] * C[2] + a33 * C[0] * C[0] - T(2.0) * a13 * C[0] * C[2];
    const T W = width_px / T(2.0 * forward_.camera().fx);
    const T W2 = W * W;
    const T C3_2 = C[2] * C[2];
    const T qa = W2 * a33 * a33 - k;
    const T qb = T(2.0) * W2 * a33 * C3_2 + b;
    const T qc = W2 * C3_2 * C3_2;
    T disc = qb * qb - T(4.0) * qa * qc;
    if (scalarValue(disc) < 0.0) {
      // Round-off only: the derivation guarantees a real root (see the file comment).
      if (scalarValue(disc) < -1e-9 * scalarValue(qb * qb))
        fail(ErrorCode::kDegenerateGeometry, "InverseTreeWidth: no radius reproduces this width");
      disc = T(0.0);
    }
    const T s = T(2.0) * qc / (qb + sqrt(disc));
    return sqrt(s);
  }

  /// The XYZ-R landmark [base, radius(camera, base, w)], generic in the scalar for automatic
  /// differentiation. No checks beyond `radius`'s: operator() validates and returns the same.
  template <typename T>
  Vec<4, T> convert(const Vec<7, T>& camera, const Vec<3, T>& base, const Vec<3, T>& z) const {
    Vec<4, T> tree;
    tree << base, radius<T>(camera, base, z[2]);
    return tree;
  }

  /// The XYZ-R landmark [base, r] with J_to_x (4x7), J_to_l (4x3) and J_to_z (4x3).
  template <typename Tag = void>  // compiled only where called (core/deferred.hpp)
  Vec<4> operator()(const Vec<7>& camera,
                    const Vec<3>& base,
                    const Vec<3>& z,
                    JacobianArg<4, 7, Tag> J_to_x = {},
                    JacobianArg<4, 3, Tag> J_to_l = {},
                    JacobianArg<4, 3, Tag> J_to_z = {}) const {
    if (!camera.allFinite()) fail(ErrorCode::kNonFinite, "InverseTreeWidth: the camera state is not finite");
    if (!base.allFinite()) fail(ErrorCode::kNonFinite, "InverseTreeWidth: the tree's base centre is not finite");
    if (!z.allFinite()) fail(ErrorCode::kNonFinite, "InverseTreeWidth: the measurement is not finite");
    if (!(z[2] > 0.0)) {
      std::ostringstream os;
      os << "InverseTreeWidth: the measured width must be > 0 pixels, got " << z[2];
      fail(ErrorCode::kDegenerateGeometry, os.str());
    }
    if (!(camera.segment<4>(Pose3D::kQuaternion).norm() > TreeWidth::kMinQuaternionNorm))
      fail(ErrorCode::kDegenerateGeometry, "InverseTreeWidth: the orientation quaternion has (near) zero norm");
    const double r = radius<double>(camera, base, z[2]);
    if (!std::isfinite(r) || !(r > 0.0))
      fail(ErrorCode::kDegenerateGeometry, "InverseTreeWidth: no positive radius reproduces this width");
    Vec<4> tree;
    tree << base, r;
    // The forward model validates the geometry at the solved radius (camera inside the
    // trunk, base circle crossing the image plane, ...) and gives the Jacobian.
    Mat<3, 7> J_z_x;
    Mat<3, 4> J_z_l;
    Vec<3> z_hat;
    try {
      z_hat = forward_(camera, tree, J_z_x, J_z_l);
    } catch (const Error& e) {
      fail(e.code(), std::string("InverseTreeWidth: at the solved radius ") + std::to_string(r) +
                         " m the geometry is invalid (" + e.what() + ")");
    }
    const double J_w_r = J_z_l(2, 3);
    if (!(J_w_r > 0.0) || std::abs(z_hat[2] - z[2]) > 1e-6 * z[2] + 1e-9)
      fail(ErrorCode::kDegenerateGeometry, "InverseTreeWidth: the width does not determine the radius here");
    if (J_to_x) {
      auto J = *J_to_x;
      J.setZero();
      J.row(3) = -J_z_x.row(2) / J_w_r;  // eq. 3.30-3.32
    }
    if (J_to_l) {
      auto J = *J_to_l;
      J.setZero();
      J.template topRows<3>().setIdentity();
      J.row(3) = -J_z_l.block<1, 3>(2, 0) / J_w_r;
    }
    if (J_to_z) {
      auto J = *J_to_z;
      J.setZero();
      J(3, 2) = 1.0 / J_w_r;
    }
    return tree;
  }

 private:
  TreeWidth forward_;
};

}  // namespace sylva
