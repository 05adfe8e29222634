#pragma once
/// @file
/// `LaserCameraCalibration`: the calibration curve that maps a camera bearing into the laser
/// frame (multisensor thesis, Amarasinghe 2008, Sec. 3.3.2).
///
/// A 'v' shaped target is placed at several angles across the camera's field of view; for
/// each placement the bearing of its tip is read in the image (theta_c, from the optical axis)
/// and in the laser scan (theta_l, from the central beam). The calibration error
/// e = theta_l - theta_c is approximated by a polynomial of theta_c,
///
///   e(theta_c) = c_0 + c_1 theta_c + ... + c_n theta_c^n,
///   theta_l    = theta_c + e(theta_c)                               (Sec. 3.3.2, Fig. 3.8)
///
/// fitted by linear least squares on the pairs (theta_c, theta_l) (the Vandermonde system
/// V c = theta_l - theta_c, solved with a column-pivoting QR; the fit's RMS residual is kept
/// as the remaining calibration uncertainty). c_0 absorbs a yaw offset between the sensors,
/// c_1 a focal length error, the higher terms the lens distortion left by the camera
/// calibration. The default-constructed curve is e = 0 (the frames coincide).
///
/// Angles are counter-clockwise positive (to the left), in radians. Evaluation is Horner's
/// rule on a fixed-capacity coefficient vector: no allocation.
///
/// Errors: a degree outside [0, kMaxDegree] or fewer pairs than degree + 1 ->
/// kInvalidArgument; a non-finite pair or coefficient -> kNonFinite; pairs with fewer than
/// degree + 1 distinct camera angles (the polynomial is not determined) ->
/// kDegenerateGeometry.

#include <cmath>
#include <sstream>
#include <vector>

#include <Eigen/Core>
#include <Eigen/QR>

#include "sylva/core/error.hpp"
#include "sylva/core/types.hpp"

namespace sylva {

/// One calibration pair: the target's bearing in the image and in the laser scan (rad).
struct CalibrationPair {
  double camera_rad;
  double laser_rad;
};

class LaserCameraCalibration {
 public:
  static constexpr int kMaxDegree = 9;
  using Coefficients = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxDegree + 1, 1>;

  /// e = 0: camera and laser bearings coincide.
  LaserCameraCalibration() : coefficients_(Coefficients::Zero(1)) {}

  /// e(theta) = sum_k coefficients[k] theta^k (1 to kMaxDegree + 1 coefficients).
  explicit LaserCameraCalibration(const Eigen::VectorXd& coefficients, double residual_rms_rad = 0.0) {
    if (coefficients.size() < 1 || coefficients.size() > kMaxDegree + 1) {
      std::ostringstream os;
      os << "LaserCameraCalibration: need 1 to " << kMaxDegree + 1 << " coefficients, got "
         << coefficients.size();
      fail(ErrorCode::kInvalidArgument, os.str());
    }
    if (!coefficients.allFinite() || !std::isfinite(residual_rms_rad))
      fail(ErrorCode::kNonFinite, "LaserCameraCalibration: a coefficient or the residual is not finite");
    if (!(residual_rms_rad >= 0.0))
      fail(ErrorCode::kInvalidArgument, "LaserCameraCalibration: the residual RMS must be >= 0");
    coefficients_ = coefficients;
    residual_rms_ = residual_rms_rad;
  }

  /// Least-squares fit of e(theta_c) = theta_l - theta_c of the given degree (Sec. 3.3.2).
  template <int = 0>  // compiled only where called (docs/build-time.md)
  static LaserCameraCalibration fit(const std::vector<CalibrationPair>& pairs, int degree) {
    if (degree < 0 || degree > kMaxDegree) {
      std::ostringstream os;
      os << "LaserCameraCalibration::fit: the degree must be in [0, " << kMaxDegree << "], got "
         << degree;
      fail(ErrorCode::kInvalidArgument, os.str());
    }
    const auto n = static_cast<Eigen::Index>(pairs.size());
    if (n < degree + 1) {
      std::ostringstream os;
      os << "LaserCameraCalibration::fit: a degree " << degree << " polynomial needs at least "
         << degree + 1 << " calibration pairs, got " << n;
      fail(ErrorCode::kInvalidArgument, os.str());
    }
    Eigen::MatrixXd V(n, degree + 1);
    Eigen::VectorXd e(n);
    for (Eigen::Index i = 0; i < n; ++i) {
      const CalibrationPair& p = pairs[static_cast<std::size_t>(i)];
      if (!std::isfinite(p.camera_rad) || !std::isfinite(p.laser_rad)) {
        std::ostringstream os;
        os << "LaserCameraCalibration::fit: calibration pair " << i << " is not finite";
        fail(ErrorCode::kNonFinite, os.str());
      }
      double power = 1.0;
      for (int k = 0; k <= degree; ++k, power *= p.camera_rad) V(i, k) = power;
      e[i] = p.laser_rad - p.camera_rad;
    }
    const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(V);
    if (qr.rank() < degree + 1) {
      std::ostringstream os;
      os << "LaserCameraCalibration::fit: the " << n << " calibration pairs do not determine a degree "
         << degree << " polynomial (too few distinct camera angles; rank " << qr.rank() << ")";
      fail(ErrorCode::kDegenerateGeometry, os.str());
    }
    const Eigen::VectorXd c = qr.solve(e);
    const double rms = std::sqrt((V * c - e).squaredNorm() / static_cast<double>(n));
    return LaserCameraCalibration(c, rms);
  }

  int degree() const { return static_cast<int>(coefficients_.size()) - 1; }
  const Coefficients& coefficients() const { return coefficients_; }
  /// RMS residual of the fit (rad): calibration uncertainty left after the mapping.
  double residualRms() const { return residual_rms_; }

  /// e(theta_c) (rad).
  double error(double camera_rad) const {
    double value = 0.0;
    for (Eigen::Index k = coefficients_.size() - 1; k >= 0; --k) value = value * camera_rad + coefficients_[k];
    return value;
  }

  /// de/dtheta_c.
  double errorDerivative(double camera_rad) const {
    double value = 0.0;
    for (Eigen::Index k = coefficients_.size() - 1; k >= 1; --k)
      value = value * camera_rad + static_cast<double>(k) * coefficients_[k];
    return value;
  }

  /// theta_l = theta_c + e(theta_c): the camera bearing in the laser frame (Sec. 3.3.2).
  double toLaser(double camera_rad) const { return camera_rad + error(camera_rad); }

  /// d theta_l / d theta_c = 1 + e'(theta_c): scales the camera's bearing noise.
  double toLaserDerivative(double camera_rad) const { return 1.0 + errorDerivative(camera_rad); }

 private:
  Coefficients coefficients_;
  double residual_rms_ = 0.0;
};

}  // namespace sylva
