#pragma once
/// @file
/// `InverseDepthTreeWidth`: the tree-width measurement z = [u, v, w] (pixels, exactly as
/// `TreeWidth`: centre of the image ellipse of the trunk's base circle and its horizontal
/// extent) of an `InverseDepthRadius` (IDR) tree seen by a pinhole camera at
/// a `Pose3D`; and `InverseDepthRadiusInitialization`, the inverse model that starts an IDR tree
/// from its first [u, v, w], radius included. Beyond the tree-width thesis, whose trees
/// start as inverse-depth points and get a radius only once their position is known (Sec.
/// 3.5, Fig. 3.3; Ch. 5 asks for "a parametrization that carries the radius from the first
/// observation").
///
/// The model, through homogeneity. With the notation of tree_width.hpp, TreeWidth depends on
/// the tree only through the dual conic
///
///   D_C = r^2 (I - n n^T) - C C^T,   C = R^T (c - t),   n = R^T e3,
///
/// which is homogeneous of degree 2 in (C, r), and u = cx + fx d13 / d33,
/// v = cy + fy d23 / d33, w = 2 fx sqrt(d13^2 - d11 d33) / (-d33) are ratios of its entries,
/// invariant under (C, r) -> (lambda C, lambda r). For the IDR tree c = a + m / rho,
/// r = kappa / rho (a the anchor, m = m(theta, phi)); with lambda = rho
///
///   rho (c - t) = rho (a - t) + m,   rho r = kappa,
///
/// so, with x_0 the camera state with its position set to 0 (same quaternion, velocities),
///
///   h_IDR(x, l) = TreeWidth(x_0, l'),   l' = [ c', kappa ],   c' = rho (a - t) + m.
///
/// There is no division by rho: the model is defined and smooth at rho = 0, a tree at
/// infinity seen with angular size kappa (as `PinholePoint<InverseDepth>` projects a point
/// at infinity to its vanishing point).
///
/// Validity. TreeWidth's checks apply to the scaled tree l': finite input, kappa > 0, the
/// camera outside the trunk (|c'_xy| > kappa), the whole base circle in front of the camera,
/// an image ellipse of non-zero width. For rho > 0 they are the checks of the Euclidean tree
/// (each is invariant under a positive scale). rho < 0 is not rejected by itself: a far
/// tree's estimate crosses zero while it settles (the prior rho0 = 0.1 +- 0.5 covers
/// negative values), and for a small |rho| the scaled tree c' ~ m is still in front of the
/// camera, so the model continues smoothly through rho = 0. A negative lambda reflects the
/// tree through the camera centre, though: when the tree a + m / rho (behind its anchor) is
/// in front of the camera, c' is behind it and TreeWidth rejects it (kDegenerateGeometry).
/// Errors are TreeWidth's, rethrown with the same code and a message starting with
/// "InverseDepthTreeWidth:" (lengths in them are those of the scaled tree, i.e. times rho).
///
/// Jacobians, by the chain rule from TreeWidth's J' = [J'_x (3x7), J'_c (3x3), J'_r (3x1)]
/// at (x_0, l'): c' depends on the camera position as -rho I and not on q (and x_0's
/// position is the constant 0, so TreeWidth's delta c' - 0 is the one the chain needs):
///
///   J_z_x = [ J'_c (-rho I),  J'_x(:, q),  0 (velocities) ]
///   J_z_l = [ J'_c rho,  J'_c dm/dtheta,  J'_c dm/dphi,  J'_c (a - t),  J'_r ]
///
/// with dm/dtheta = [-cos(phi) sin(theta), cos(phi) cos(theta), 0] and
/// dm/dphi = [-sin(phi) cos(theta), -sin(phi) sin(theta), cos(phi)]. Tests compare them with
/// central differences and with automatic differentiation of `predict<T>`.
///
/// The initialization (`InverseDepthRadiusInitialization`, the inverse model for
/// `Ekf::add`). The "measurement" is z = [u, v, w, rho0] with covariance
/// diag(R_uvw, sigma_rho^2): the width measurement and, as in `InverseDepthInitialization`
/// (Civera, Davison, Montiel 2008), a prior inverse depth. The landmark is
///
///   l[0..5] = InverseDepthInitialization(x, [u, v, rho0])  (anchor t, ray through (u, v),
///                                                           rho0; with its Jacobians)
///   l[6]    = kappa solving  w(TreeWidth(x_0, [m(theta, phi), kappa])) = w.
///
/// Seen from the anchor (t = a) the scaled tree is [m, kappa] whatever rho0 is: the width
/// fixes kappa and not the depth, and kappa does not depend on rho0 nor on the camera
/// position. kappa = `InverseTreeWidth::radius`(x_0, m, w) (the exact smaller root of that
/// file's quadratic, for the tree at unit depth), then validated by the forward model.
/// Its Jacobian is the implicit function theorem's, as in InverseTreeWidth: with f the
/// forward width at (x_0, [m, kappa]) and J_w_k = df/dkappa > 0,
///
///   dkappa/dq     = -(J'_w_q + J'_w_c dm/d(theta, phi) d(theta, phi)/dq) / J_w_k
///   dkappa/d(u,v) = -(J'_w_c dm/d(theta, phi) d(theta, phi)/d(u, v)) / J_w_k
///   dkappa/dw     = 1 / J_w_k,   dkappa/drho0 = dkappa/dt = dkappa/dvelocities = 0,
///
/// d(theta, phi)/dq and d(theta, phi)/d(u, v) being rows 3-4 of InverseDepthInitialization's
/// Jacobians. The new landmark predicts exactly w from the same camera. It predicts (u, v)
/// only approximately: the ray is taken through the measured ellipse centre, while the
/// centre of an ellipse is not the image of the circle's centre (tree_width.hpp); they
/// differ by an amount of second order in kappa (of order fx kappa^2, a fraction of a pixel
/// for a 0.25 m trunk 5 m away), which the filter's pixel noise covers and the first updates
/// remove.
///
/// Errors of the initialization: NaN or Inf in the camera state or in z (kNonFinite); a
/// quaternion of (near) zero norm, w <= 0, rho0 < 0, a vertical ray, or a width that no
/// radius reproduces in valid geometry (e.g. a trunk so wide the camera would be inside it)
/// -> kDegenerateGeometry, with a message starting with "InverseDepthRadiusInitialization:".
/// Nothing is written before all checks pass.
///
/// No allocation on the success path of either model (fixed-size Eigen types only).

#include <cmath>
#include <sstream>
#include <string>

#include "sylva/core/error.hpp"
#include "sylva/core/jacobian_ref.hpp"
#include "sylva/core/scalar.hpp"
#include "sylva/core/types.hpp"
#include "sylva/landmarks/inverse_depth.hpp"
#include "sylva/landmarks/inverse_depth_radius.hpp"
#include "sylva/measurements/inverse_depth_initialization.hpp"
#include "sylva/measurements/inverse_tree_width.hpp"
#include "sylva/measurements/pinhole_camera.hpp"
#include "sylva/measurements/pinhole_point.hpp"
#include "sylva/measurements/tree_width.hpp"
#include "sylva/motion/pose_3d.hpp"
#include "sylva/noise/gaussian.hpp"

namespace sylva {

namespace detail {

/// The sentence of a sylva::Error without the "sylva: <code>: " that `Error` puts in front,
/// for a model that rethrows an inner model's error under its own name.
inline std::string errorReason(const Error& e) {
  std::string what = e.what();
  const std::string prefix = std::string("sylva: ") + toString(e.code()) + ": ";
  if (what.compare(0, prefix.size(), prefix) == 0) what.erase(0, prefix.size());
  return what;
}

}  // namespace detail

struct InverseDepthTreeWidth {
  using Robot = Pose3D;
  using Landmark = InverseDepthRadius;
  static constexpr int kDim = 3;  ///< [u_px, v_px, width_px]
  static constexpr const char* kName = "InverseDepthTreeWidth";

  /// Throws (see `PinholeCamera::validate`) for invalid intrinsics.
  explicit InverseDepthTreeWidth(const PinholeCamera& camera) : forward_(camera) {}

  /// A width <= 0 pixels is no width a trunk can have: the filter refuses it (as
  /// InverseTreeWidth does) instead of fusing it into a shrinking radius.
  static const char* measurementViolation(const Vec<3>& z) {
    return z[2] > 0.0 ? nullptr : "the measured width must be > 0 pixels";
  }

  const PinholeCamera& camera() const { return forward_.camera(); }

  /// Predicted [u, v, w] (pixels), generic in the scalar for automatic differentiation:
  /// TreeWidth::predict<T> of the scaled tree (see the file comment).
  template <typename T>
  Vec<3, T> predict(const Vec<7, T>& camera, const Vec<7, T>& l) const {
    checkInputs(camera, l);
    Vec<7, T> camera_0 = camera;
    camera_0.template head<3>().setZero();
    Vec<4, T> tree_0;
    tree_0.template head<3>() = l[5] * Vec<3, T>(l.template head<3>() - camera.template head<3>()) +
                                InverseDepth::direction<T>(l[3], l[4]);
    tree_0[3] = l[6];
    try {
      return forward_.template predict<T>(camera_0, tree_0);
    } catch (const Error& e) {
      rethrow(e, scalarValue(l[5]));
    }
  }

  /// Prediction with the analytic Jacobians J_z_x (3x7) and J_z_l (3x7).
  template <typename Tag = void>  // compiled only where called (core/deferred.hpp)
  Vec<3> operator()(const Vec<7>& camera,
                    const Vec<7>& l,
                    JacobianArg<3, 7, Tag> J_z_x = {},
                    JacobianArg<3, 7, Tag> J_z_l = {}) const {
    checkInputs(camera, l);
    const double rho = l[5];
    const Vec<3> anchor_from_camera = l.head<3>() - camera.head<3>();  // a - t
    Vec<7> camera_0 = camera;
    camera_0.head<3>().setZero();
    Vec<4> tree_0;
    tree_0 << rho * anchor_from_camera + InverseDepth::direction<double>(l[3], l[4]), l[6];
    const bool jacobians = J_z_x || J_z_l;
    Mat<3, 7> J0_x;  // J'_x at (x_0, l')
    Mat<3, 4> J0_l;   // [J'_c, J'_r]
    Vec<3> z;
    try {
      if (!jacobians) return forward_(camera_0, tree_0);
      z = forward_(camera_0, tree_0, J_z_x ? JacobianRef<3, 7>(J0_x) : JacobianRef<3, 7>(), J0_l);
    } catch (const Error& e) {
      rethrow(e, rho);
    }
    const Mat<3, 3> J0_c = J0_l.leftCols<3>();
    if (J_z_x) {
      auto J = *J_z_x;
      J.setZero();
      J.template leftCols<3>() = -rho * J0_c;               // dc'/dt = -rho I
      J.template middleCols<4>(3) = J0_x.middleCols<4>(3);  // c' does not depend on q
    }
    if (J_z_l) {
      auto J = *J_z_l;
      J.template leftCols<3>() = rho * J0_c;  // dc'/da = rho I
      J.template middleCols<2>(3) = J0_c * InverseDepth::directionJacobian(l[3], l[4]);
      J.col(5) = J0_c * anchor_from_camera;  // dc'/drho = a - t
      J.col(6) = J0_l.col(3);                // d/dkappa
    }
    return z;
  }

 private:
  template <typename T>
  static void checkInputs(const Vec<7, T>& camera, const Vec<7, T>& l) {
    for (int i = 0; i < 7; ++i) {
      if (!std::isfinite(scalarValue(camera[i])))
        fail(ErrorCode::kNonFinite, "InverseDepthTreeWidth: the camera state is not finite");
    }
    for (int i = 0; i < 7; ++i) {
      if (!std::isfinite(scalarValue(l[i])))
        fail(ErrorCode::kNonFinite, "InverseDepthTreeWidth: the IDR landmark is not finite");
    }
    const double kappa = scalarValue(l[6]);
    if (!(kappa > 0.0)) {
      std::ostringstream os;
      os << "InverseDepthTreeWidth: kappa = radius * inverse depth " << kappa
         << " must be > 0 (a trunk of positive radius)";
      fail(ErrorCode::kDegenerateGeometry, os.str());
    }
  }

  /// TreeWidth's error on the scaled tree, under this model's name, with the same code.
  [[noreturn]] static void rethrow(const Error& e, double rho) {
    std::ostringstream os;
    os << "InverseDepthTreeWidth: " << detail::errorReason(e)
       << " [evaluated on the tree scaled by its inverse depth rho = " << rho
       << " 1/m: lengths are multiplied by rho";
    if (rho < 0.0) os << "; rho < 0 puts the tree behind its anchor";
    os << "]";
    fail(e.code(), os.str());
  }

  TreeWidth forward_;
};

struct InverseDepthRadiusInitialization {
  using Robot = Pose3D;
  using Landmark = InverseDepthRadius;
  static constexpr int kMeasurementDim = 4;  ///< [u_px, v_px, width_px, rho0_per_m]
  static constexpr const char* kName = "InverseDepthRadiusInitialization";

  /// Throws for invalid intrinsics, a non-finite or non-positive prior inverse depth (1/m)
  /// or standard deviation (1/m), as `InverseDepthInitialization` does (Civera et al.'s
  /// defaults: depths from about 1 m to beyond infinity in the 95% interval).
  explicit InverseDepthRadiusInitialization(const PinholeCamera& camera,
                                            double initial_inverse_depth = 0.1,
                                            double inverse_depth_sigma = 0.5)
      : inverse_depth_(makeInverseDepth(camera, initial_inverse_depth, inverse_depth_sigma)),
        width_(camera),
        inverse_width_(camera) {}

  const PinholeCamera& camera() const { return inverse_depth_.camera(); }
  double initialInverseDepth() const { return inverse_depth_.initialInverseDepth(); }
  double inverseDepthSigma() const { return inverse_depth_.inverseDepthSigma(); }

  /// z = [u, v, w, rho0] for the tree-width measurement [u, v, w].
  Vec<4> measurement(const Vec<3>& uvw) const {
    return Vec<4>(uvw[0], uvw[1], uvw[2], inverse_depth_.initialInverseDepth());
  }

  /// The [u, v, w] noise `uvw_noise` (any 3x3 covariance) with sigma_rho^2 appended.
  template <int = 0>  // compiled only where called (docs/build-time.md)
  Gaussian<4> noise(const Gaussian<3>& uvw_noise) const {
    Mat<4, 4> covariance = Mat<4, 4>::Zero();
    covariance.topLeftCorner<3, 3>() = uvw_noise.covariance();
    const double sigma_rho = inverse_depth_.inverseDepthSigma();
    covariance(3, 3) = sigma_rho * sigma_rho;
    return Gaussian<4>::covariance(covariance);
  }

  /// The landmark [t, theta, phi, rho0, kappa], generic in the scalar for automatic
  /// differentiation: `InverseDepthInitialization::initialize` of [u, v, rho0] and kappa =
  /// `InverseTreeWidth::radius` of the tree at unit depth seen from the camera at the origin,
  /// the two pieces operator() is made of. No checks: operator() validates the input and the
  /// geometry and returns the same landmark.
  template <typename T>
  Vec<7, T> initialize(const Vec<7, T>& camera, const Vec<4, T>& z) const {
    const Vec<6, T> l6 = inverse_depth_.initialize<T>(camera, Vec<3, T>(z[0], z[1], z[3]));
    Vec<7, T> camera_0 = camera;
    camera_0.template head<3>().setZero();
    const Vec<3, T> m = InverseDepth::direction<T>(l6[3], l6[4]);
    Vec<7, T> l;
    l << l6, inverse_width_.radius<T>(camera_0, m, z[2]);
    return l;
  }

  /// The landmark [t, theta, phi, rho0, kappa] with J_l_x (7x7) and J_l_z (7x4).
  template <typename Tag = void>  // compiled only where called (core/deferred.hpp)
  Vec<7> operator()(const Vec<7>& camera,
                    const Vec<4>& z,
                    JacobianArg<7, 7, Tag> J_l_x = {},
                    JacobianArg<7, 4, Tag> J_l_z = {}) const {
    detail::PinholePointMath::checkCamera(camera, kName);
    if (!z.allFinite())
      fail(ErrorCode::kNonFinite, std::string(kName) + ": the measurement is not finite");
    if (!(z[2] > 0.0)) {
      std::ostringstream os;
      os << kName << ": the measured width must be > 0 pixels, got " << z[2];
      fail(ErrorCode::kDegenerateGeometry, os.str());
    }
    if (z[3] < 0.0) {
      std::ostringstream os;
      os << kName << ": the prior inverse depth z[3] = " << z[3] << " 1/m must be >= 0";
      fail(ErrorCode::kDegenerateGeometry, os.str());
    }
    // The ray and the prior depth: l[0..5] with their Jacobians.
    const Vec<3> z_ray(z[0], z[1], z[3]);
    Mat<6, 7> J6_x;  // of [t, theta, phi, rho0] w.r.t. the camera
    Mat<6, 3> J6_z;   // ... w.r.t. [u, v, rho0]
    Vec<6> l6;
    try {
      l6 = inverse_depth_(camera,
                          z_ray,
                          J_l_x ? JacobianRef<6, 7>(J6_x) : JacobianRef<6, 7>(),
                          J_l_z ? JacobianRef<6, 3>(J6_z) : JacobianRef<6, 3>());
    } catch (const Error& e) {
      fail(e.code(), std::string(kName) + ": " + detail::errorReason(e));
    }
    // kappa: the radius of the tree at unit depth along m seen from the camera at the origin.
    Vec<7> camera_0 = camera;
    camera_0.head<3>().setZero();
    const Vec<3> m = InverseDepth::direction<double>(l6[3], l6[4]);
    double kappa = 0.0;
    try {
      kappa = inverse_width_.radius<double>(camera_0, m, z[2]);
    } catch (const Error& e) {
      std::ostringstream os;
      os << kName << ": no trunk size kappa reproduces the width " << z[2] << " px ("
         << detail::errorReason(e) << ")";
      fail(e.code(), os.str());
    }
    if (!std::isfinite(kappa) || !(kappa > 0.0)) {
      std::ostringstream os;
      os << kName << ": no positive trunk size kappa reproduces the width " << z[2] << " px";
      fail(ErrorCode::kDegenerateGeometry, os.str());
    }
    // The forward model validates the geometry at the solved kappa (camera inside the trunk,
    // base circle crossing the image plane, ...) and gives the Jacobians for the implicit
    // function theorem.
    Vec<4> tree_0;
    tree_0 << m, kappa;
    Mat<3, 7> J0_x;
    Mat<3, 4> J0_l;
    Vec<3> z_hat;
    try {
      z_hat =
          width_(camera_0, tree_0, J_l_x ? JacobianRef<3, 7>(J0_x) : JacobianRef<3, 7>(), J0_l);
    } catch (const Error& e) {
      std::ostringstream os;
      os << kName << ": at the solved kappa = " << kappa
         << " (radius / depth) the geometry is invalid: " << detail::errorReason(e);
      fail(e.code(), os.str());
    }
    const double J_w_k = J0_l(2, 3);
    if (!(J_w_k > 0.0) || !(std::abs(z_hat[2] - z[2]) <= 1e-6 * z[2] + 1e-9)) {
      std::ostringstream os;
      os << kName << ": the width " << z[2] << " px does not determine the trunk size here";
      fail(ErrorCode::kDegenerateGeometry, os.str());
    }
    Vec<7> l;
    l << l6, kappa;
    if (!J_l_x && !J_l_z) return l;

    // d width / d (theta, phi) through the scaled base centre c' = m(theta, phi).
    const Mat<1, 2> J_w_angles =
        J0_l.block<1, 3>(2, 0) * InverseDepth::directionJacobian(l6[3], l6[4]);
    if (J_l_x) {
      auto J = *J_l_x;
      J.template topRows<6>() = J6_x;
      J.row(6).setZero();
      J.template block<1, 4>(6, 3) = -(J0_x.block<1, 4>(2, 3) + J_w_angles * J6_x.block<2, 4>(3, 3)) / J_w_k;
    }
    if (J_l_z) {
      auto J = *J_l_z;
      J.setZero();
      J.template block<6, 2>(0, 0) = J6_z.leftCols<2>();  // u, v
      J.template block<6, 1>(0, 3) = J6_z.col(2);         // rho0
      J.template block<1, 2>(6, 0) = -(J_w_angles * J6_z.block<2, 2>(3, 0)) / J_w_k;
      J(6, 2) = 1.0 / J_w_k;
    }
    return l;
  }

 private:
  static InverseDepthInitialization makeInverseDepth(const PinholeCamera& camera,
                                                     double rho0,
                                                     double sigma) {
    try {
      return InverseDepthInitialization(camera, rho0, sigma);
    } catch (const Error& e) {
      fail(e.code(), std::string(kName) + ": " + detail::errorReason(e));
    }
  }

  InverseDepthInitialization inverse_depth_;
  TreeWidth width_;
  InverseTreeWidth inverse_width_;
};

}  // namespace sylva
