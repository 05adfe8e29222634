#pragma once
/// @file
/// `InverseDepthInitialization`: a new `InverseDepth` landmark from the first pixel at which
/// a camera at a `Pose3D` sees it, the inverse model for `Ekf::add` (Civera, Davison,
/// Montiel 2008, "Inverse depth parametrization for monocular SLAM", feature initialization).
///
/// A single image fixes the ray to the point but not its depth. As Civera et al. do, the
/// depth is given a prior, rho0 with standard deviation sigma_rho, chosen so that the 95%
/// interval [rho0 - 2 sigma_rho, rho0 + 2 sigma_rho] reaches from a near point to beyond
/// infinity (their values 0.1 1/m and 0.5 1/m: depths from about 1 m to infinity). The prior
/// enters as a third component of the "measurement",
///
///   z = [u, v, rho0],   R = diag(sigma_px^2, sigma_px^2, sigma_rho^2)
///
/// (`measurement(pixel)` and `noise(pixel_sigma)` build both), so the filter's ordinary
/// augmentation puts J_l_z R J_l_z^T + J_l_x P_rr J_l_x^T into the new block.
///
/// The landmark. With t = r_WC and R = R(q / |q|) (camera -> world):
///
///   h_C = [ (u - cx) / fx, (v - cy) / fy, 1 ],   h_W = R h_C   (the ray in the world)
///   l   = [ t, theta, phi, rho0 ],  theta = atan2(h_Wy, h_Wx),
///                                   phi   = atan2(h_Wz, sqrt(h_Wx^2 + h_Wy^2)),
///
/// so that m(theta, phi) of landmarks/inverse_depth.hpp equals h_W / |h_W| (world z up:
/// theta is the azimuth from world x, phi the elevation). PinholePoint<InverseDepth> of l
/// from the same camera gives (u, v) back for any rho0 >= 0.
///
/// Jacobians. With r = sqrt(h_Wx^2 + h_Wy^2) and |h| = |h_W|,
///
///   d theta / d h_W = [ -h_Wy, h_Wx, 0 ] / r^2
///   d phi   / d h_W = [ -h_Wx h_Wz / r, -h_Wy h_Wz / r, r ] / |h|^2
///   d h_W / du = R e1 / fx,  d h_W / dv = R e2 / fy,
///   d h_W / dq = d(R(q/|q|) h_C)/dq = D(q*/|q|, h_C) diag(1, -1, -1, -1) (I - q q^T/|q|^2)/|q|
///
/// where q* is the conjugate and D(q, w) = d(R(q)^T w)/dq is
/// `rotateTransposedJacobian` (R(q) w = R(q*)^T w). J_l_x is the identity in the
/// position columns and the angle rows times d h_W / dq in the quaternion columns; J_l_z has the angle rows times [d h_W/du, d h_W/dv] and a 1 at
/// (rho, rho0).
///
/// Near the zenith or nadir (phi -> +-pi/2) the azimuth loses its meaning: d theta / d h_W
/// grows like 1 / cos(phi), so the new landmark gets a large azimuth variance. That is the
/// true uncertainty of theta; the point's position stays well determined because dm/dtheta
/// shrinks like cos(phi). A ray within 1e-9 rad of vertical, where theta is undefined, is
/// rejected with kDegenerateGeometry.
///
/// Errors: NaN or Inf in the camera state or in z -> kNonFinite; a quaternion of norm
/// < 1e-12, a prior inverse depth z[2] < 0 or a vertical ray -> kDegenerateGeometry. The
/// constructor validates the camera and requires finite rho0 > 0 and sigma_rho > 0
/// (kInvalidArgument; kNonFinite for NaN or Inf).

#include <cmath>
#include <sstream>
#include <string>

#include "sylva/core/error.hpp"
#include "sylva/core/jacobian_ref.hpp"
#include "sylva/core/quaternion.hpp"
#include "sylva/core/scalar.hpp"
#include "sylva/core/types.hpp"
#include "sylva/landmarks/inverse_depth.hpp"
#include "sylva/measurements/pinhole_camera.hpp"
#include "sylva/measurements/pinhole_point.hpp"
#include "sylva/motion/pose_3d.hpp"
#include "sylva/noise/gaussian.hpp"

namespace sylva {

struct InverseDepthInitialization {
  using Robot = Pose3D;
  using Landmark = InverseDepth;
  static constexpr int kMeasurementDim = 3;  ///< [u_px, v_px, rho0_per_m]
  static constexpr const char* kName = "InverseDepthInitialization";
  /// Rays closer than this (rad, as cos(phi)) to the vertical have no azimuth.
  static constexpr double kMinHorizontalFraction = 1e-9;

  /// Throws for invalid intrinsics, a non-finite or non-positive prior inverse depth
  /// (1/m) or standard deviation (1/m).
  explicit InverseDepthInitialization(const PinholeCamera& camera,
                                      double initial_inverse_depth = 0.1,
                                      double inverse_depth_sigma = 0.5)
      : camera_(camera), rho0_(initial_inverse_depth), sigma_rho_(inverse_depth_sigma) {
    camera_.validate();
    if (!std::isfinite(rho0_) || !std::isfinite(sigma_rho_)) {
      std::ostringstream os;
      os << kName << ": the prior inverse depth " << rho0_ << " and its sigma " << sigma_rho_
         << " must be finite";
      fail(ErrorCode::kNonFinite, os.str());
    }
    if (!(rho0_ > 0.0) || !(sigma_rho_ > 0.0)) {
      std::ostringstream os;
      os << kName << ": the prior inverse depth (" << rho0_ << " 1/m) and its sigma (" << sigma_rho_
         << " 1/m) must be > 0";
      fail(ErrorCode::kInvalidArgument, os.str());
    }
  }

  const PinholeCamera& camera() const { return camera_; }
  double initialInverseDepth() const { return rho0_; }
  double inverseDepthSigma() const { return sigma_rho_; }

  /// z = [u, v, rho0] for the pixel (u, v).
  Vec<3> measurement(const Vec<2>& pixel) const { return Vec<3>(pixel[0], pixel[1], rho0_); }

  /// diag(sigma_px^2, sigma_px^2, sigma_rho^2) for independent pixel noise `pixel_sigma`.
  template <int = 0>  // compiled only where called (docs/build-time.md)
  Gaussian<3> noise(double pixel_sigma) const {
    return Gaussian<3>::sigmas(Vec<3>(pixel_sigma, pixel_sigma, sigma_rho_));
  }

  /// The pixel noise `pixel_noise` (any 2x2 covariance) with sigma_rho^2 appended.
  template <int = 0>  // compiled only where called (docs/build-time.md)
  Gaussian<3> noise(const Gaussian<2>& pixel_noise) const {
    Mat<3, 3> covariance = Mat<3, 3>::Zero();
    covariance.topLeftCorner<2, 2>() = pixel_noise.covariance();
    covariance(2, 2) = sigma_rho_ * sigma_rho_;
    return Gaussian<3>::covariance(covariance);
  }

  /// The landmark [t, theta, phi, rho0], generic in the scalar for automatic
  /// differentiation. No checks: operator() validates the camera and z and returns this.
  template <typename T>
  Vec<6, T> initialize(const Vec<7, T>& camera, const Vec<3, T>& z) const {
    using std::sqrt;
    const Vec<4, T> q_raw = camera.template segment<4>(Pose3D::kQuaternion);
    const Vec<4, T> q = q_raw / q_raw.norm();
    const Mat<3, 3, T> R = rotationMatrix<T>(q);
    const Vec<3, T> h_C((z[0] - camera_.cx) / camera_.fx, (z[1] - camera_.cy) / camera_.fy, T(1.0));
    const Vec<3, T> h_W = R * h_C;
    Vec<6, T> l;
    l.template head<3>() = camera.template head<3>();
    l[3] = atan2Generic(h_W[1], h_W[0]);
    l[4] = atan2Generic(h_W[2], T(sqrt(h_W[0] * h_W[0] + h_W[1] * h_W[1])));
    l[5] = z[2];
    return l;
  }

  /// The landmark [t, theta, phi, rho0] with J_l_x (6x7) and J_l_z (6x3).
  template <typename Tag = void>  // compiled only where called (core/deferred.hpp)
  Vec<6> operator()(const Vec<7>& camera,
                    const Vec<3>& z,
                    JacobianArg<6, 7, Tag> J_l_x = {},
                    JacobianArg<6, 3, Tag> J_l_z = {}) const {
    detail::PinholePointMath::checkCamera(camera, kName);
    if (!z.allFinite())
      fail(ErrorCode::kNonFinite, std::string(kName) + ": measurement is not finite");
    if (z[2] < 0.0) {
      std::ostringstream os;
      os << kName << ": the prior inverse depth z[2] = " << z[2] << " 1/m must be >= 0";
      fail(ErrorCode::kDegenerateGeometry, os.str());
    }
    const double q_norm = camera.segment<4>(Pose3D::kQuaternion).norm();
    const Vec<4> q = camera.segment<4>(Pose3D::kQuaternion) / q_norm;
    const Mat<3, 3> R = rotationMatrix<double>(q);
    const Vec<3> h_C((z[0] - camera_.cx) / camera_.fx, (z[1] - camera_.cy) / camera_.fy, 1.0);
    const Vec<3> h_W = R * h_C;
    const double r2 = h_W[0] * h_W[0] + h_W[1] * h_W[1];
    const double r = std::sqrt(r2);
    const double h2 = r2 + h_W[2] * h_W[2];
    if (!(r > kMinHorizontalFraction * std::sqrt(h2))) {
      fail(ErrorCode::kDegenerateGeometry,
           std::string(kName) +
               ": the ray through this pixel is vertical; its azimuth is undefined");
    }
    const Vec<6> l = initialize<double>(camera, z);
    if (!J_l_x && !J_l_z) return l;

    Mat<2, 3> J_angles_h;                          // d [theta, phi] / d h_W
    J_angles_h << -h_W[1] / r2, h_W[0] / r2, 0.0,  //
        -h_W[0] * h_W[2] / (r * h2), -h_W[1] * h_W[2] / (r * h2), r / h2;
    if (J_l_x) {
      // R(q) h_C = R(q*)^T h_C, q* = (w, -x, -y, -z).
      const Vec<4> q_conj(q[0], -q[1], -q[2], -q[3]);
      Mat<3, 4> J_h_q = rotateTransposedJacobian(q_conj, h_C);
      J_h_q.rightCols<3>() *= -1.0;
      const Mat<4, 4> J_unit = (Mat<4, 4>::Identity() - q * q.transpose()) / q_norm;
      auto J = *J_l_x;
      J.setZero();
      J.template topLeftCorner<3, 3>().setIdentity();
      J.template block<2, 4>(3, 3) = J_angles_h * J_h_q * J_unit;
    }
    if (J_l_z) {
      Mat<3, 2> J_h_uv;
      J_h_uv.col(0) = R.col(0) / camera_.fx;
      J_h_uv.col(1) = R.col(1) / camera_.fy;
      auto J = *J_l_z;
      J.setZero();
      J.template block<2, 2>(3, 0) = J_angles_h * J_h_uv;
      J(5, 2) = 1.0;
    }
    return l;
  }

 private:
  PinholeCamera camera_;
  double rho0_;
  double sigma_rho_;
};

}  // namespace sylva
