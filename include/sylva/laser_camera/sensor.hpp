#pragma once
/// @file
/// `LaserCameraSensor`: the calibrated laser-vision sensor of the multisensor thesis
/// (Amarasinghe 2008, Sec. 3.3 and 3.5). The camera detects a vertical line and gives its
/// bearing; the laser scan gives its range. The output is a `[range, bearing]` measurement in
/// the laser frame with its covariance, ready for `RangeBearing` / `InverseRangeBearing`
/// (with the laser at the robot's origin facing forward, the laser frame is the robot frame).
///
/// Geometry (thesis Fig. 3.5). The camera sits on the laser's vertical axis (a = 0), b metres
/// above the scan plane, its optical axis along the central beam up to the calibration
/// curve. A detected line is given by its bearing theta_c (rad, counter-clockwise from the
/// optical axis, i.e. to the left) and its vertical extent in normalized image coordinates
/// (y = Y / Z, y down; `image_top_y <= image_bottom_y`).
///
/// Steps of `measure(line, ranges)`:
///
///  1. theta_l = theta_c + e(theta_c)                         calibration curve, Sec. 3.3.2
///  2. the beams i, i + 1 around theta_l: a_i <= theta_l <= a_(i+1) with
///     a_k = angle_min + k * increment, any increment          (outside: kOutsideScan)
///  3. both readings finite and within [min_range, max_range]  (else: kInvalidReading)
///  4. |r_(i+1) - r_i| <= max_jump                              (else: kRangeDiscontinuity)
///     With `near_side_at_jumps` a jump is not rejected at once: a vertical line at a range
///     jump is usually the occluding edge of the nearer surface, so the range is extrapolated
///     along the nearer surface (its reading and the next one on its own side, which must be
///     continuous); still kRangeDiscontinuity when those two are not.
///  5. r = interpolated range at theta_l (eq. 3.4, see laser_range_interpolation.hpp);
///     incidence <= max_incidence                              (else: kGrazingIncidence)
///  6. the laser plane crosses the line in the image (Sec. 3.5): the scan point at range r,
///     bearing theta_l appears at image row y = b / (r cos theta_l) (thesis: q = lambda b /
///     (r_i cos theta_i), lambda = 1 in normalized coordinates); the line is kept when
///     image_top_y - margin <= y <= image_bottom_y + margin   (else: kMissesLaserPlane:
///     a line on a protruding or retracted object, a poster above the scan plane).
///
/// Covariance (eq. 3.5, propagated rather than assumed diagonal). The inputs are the camera
/// bearing (sigma_bearing, the camera's noise), the calibration residual (sigma_cal, the RMS
/// residual of the fit) and the two readings (sigma_reading each), independent. With
/// g = 1 + e'(theta_c) and the derivatives of eq. 3.4':
///
///   sigma_l^2 = g^2 sigma_bearing^2 + sigma_cal^2                       bearing variance
///   R = [ (dr/dphi)^2 sigma_l^2 + ((dr/dr_i)^2 + (dr/dr_j)^2) sigma_reading^2 + s2   dr/dphi sigma_l^2 ]
///       [ dr/dphi sigma_l^2                                                           sigma_l^2        ]
///
///   s2 = ((d2r/dphi dr_i)^2 + (d2r/dphi dr_j)^2) sigma_reading^2 min(sigma_l^2, delta^2 / 12)
///
/// s2 is the variance of the product of the bearing error and the chord's tilt caused by the
/// readings' noise: second order, but at 0.5 deg between beams the chord's slope is so
/// noisy (~ sqrt(2) sigma_reading / 0.0087 rad) that the first-order R underestimates the
/// range variance by 10-20 % without it (the Monte Carlo test shows it). The mixed
/// derivatives are taken by central differences of dr/dphi (four more interpolations). A
/// bearing error wider than the beam spacing delta moves the line onto other readings, so the
/// tilt acts over one chord at most: its bearing variance is capped at delta^2 / 12 (uniform
/// over one chord), an approximation that the Monte Carlo test bounds at 1 deg bearing noise.
///
/// Plus the model error of a surface that bends between the two beams (a corner):
/// (bend_fraction r increment)^2 on the range variance (option, default 0.3; the thesis
/// covers it with its worst-case sigma_r).
///
/// For a surface seen head-on dr/dphi = 0 and R is diagonal, diag(sigma_r^2, sigma_theta^2),
/// the thesis' eq. 3.5; at oblique incidence the bearing error moves the range along the
/// surface and the off-diagonal term carries that correlation. (The thesis uses worst-case
/// constant sigmas instead; see docs/models/laser-camera.md.)
///
/// Rejections are data conditions, reported in the result's `status` with `describe()`;
/// never thrown. Errors that are the caller's: a non-finite detection -> kNonFinite; a
/// bearing at or beyond +-90 deg from the optical axis, top > bottom, or a scan whose size is
/// not the geometry's beam count -> kInvalidArgument; invalid options or scan geometry ->
/// kInvalidArgument at construction. `measure` does not allocate.

#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

#include "sylva/core/angles.hpp"
#include "sylva/core/error.hpp"
#include "sylva/core/types.hpp"
#include "sylva/laser_camera/calibration.hpp"
#include "sylva/laser_camera/range_interpolation.hpp"
#include "sylva/measurements/laser_scan_geometry.hpp"

namespace sylva {

struct LaserCameraOptions {
  double camera_above_laser_m = 0.19;          ///< b of Fig. 3.5 (thesis: 19 cm), >= 0
  double sigma_bearing_rad = kRadPerDeg;      ///< camera bearing noise (Table 3.1: 1 deg), > 0
  double sigma_reading_m = 0.01;               ///< noise of one laser reading, > 0
  double max_jump_m = 0.10;                    ///< larger neighbour differences are a jump, > 0
  double max_incidence_rad = 80.0 * kRadPerDeg;  ///< in (0, pi/2]
  double plane_margin = 0.01;                  ///< tolerance of step 6 (normalized image units), >= 0
  bool near_side_at_jumps = false;             ///< step 4: extrapolate the nearer surface
  /// Model error of eq. 3.4' where the surface bends between the two beams (a corner, the
  /// very place vertical edges stand): the chord cuts the bend by up to about the distance
  /// between the two beam spots, r * increment. Its standard deviation is taken as
  /// bend_fraction * r * increment, added to the range variance (0: flat surfaces only).
  double bend_fraction = 0.3;
};

/// A vertical line detected in the image.
struct VerticalLineDetection {
  double bearing_rad;     ///< theta_c, counter-clockwise from the optical axis
  double image_top_y;     ///< normalized image row of the line's upper end (y down)
  double image_bottom_y;  ///< normalized image row of the line's lower end
};

enum class LaserCameraStatus {
  kOk,
  kOutsideScan,
  kInvalidReading,
  kRangeDiscontinuity,
  kGrazingIncidence,
  kMissesLaserPlane,
};

inline const char* describe(LaserCameraStatus status) {
  switch (status) {
    case LaserCameraStatus::kOk: return "ok";
    case LaserCameraStatus::kOutsideScan: return "the line's bearing is outside the laser scan";
    case LaserCameraStatus::kInvalidReading:
      return "a neighbouring laser reading is invalid (NaN, no return or out of range)";
    case LaserCameraStatus::kRangeDiscontinuity:
      return "the neighbouring laser readings straddle a range discontinuity";
    case LaserCameraStatus::kGrazingIncidence:
      return "the laser meets the surface at grazing incidence";
    case LaserCameraStatus::kMissesLaserPlane: return "the line does not cross the laser plane";
  }
  return "unknown";
}

struct LaserCameraMeasurement {
  LaserCameraStatus status = LaserCameraStatus::kOk;
  Vec<2> z = Vec<2>::Zero();                ///< [range_m, bearing_rad] in the laser frame
  Mat<2, 2> covariance = Mat<2, 2>::Zero();  ///< eq. 3.5 (propagated)
  int beam = -1;                             ///< lower of the two beams used
  double incidence_rad = 0.0;
  bool extrapolated = false;  ///< the nearer surface was extrapolated at a jump
  bool ok() const { return status == LaserCameraStatus::kOk; }
};

class LaserCameraSensor {
 public:
  LaserCameraSensor(const LaserScanGeometry& scan,
                    const LaserCameraCalibration& calibration = {},
                    const LaserCameraOptions& options = {})
      : scan_(validated(scan)), calibration_(calibration), options_(validated(options)) {}

  const LaserScanGeometry& scanGeometry() const { return scan_; }
  const LaserCameraCalibration& calibration() const { return calibration_; }
  const LaserCameraOptions& options() const { return options_; }

  /// Range and bearing of `line` from the readings `ranges` (one per beam), or the reason
  /// why not. See the file comment.
  template <int = 0>  // compiled only where called (docs/build-time.md)
  LaserCameraMeasurement measure(const VerticalLineDetection& line, const std::vector<double>& ranges) const {
    if (!std::isfinite(line.bearing_rad) || std::isnan(line.image_top_y) || std::isnan(line.image_bottom_y))
      fail(ErrorCode::kNonFinite, "LaserCameraSensor::measure: the line detection is not finite");
    if (!(std::abs(line.bearing_rad) < 0.5 * kPi)) {
      std::ostringstream os;
      os << "LaserCameraSensor::measure: a camera bearing of " << line.bearing_rad
         << " rad is not in front of the camera (|bearing| < pi/2)";
      fail(ErrorCode::kInvalidArgument, os.str());
    }
    if (!(line.image_top_y <= line.image_bottom_y))
      fail(ErrorCode::kInvalidArgument,
           "LaserCameraSensor::measure: the line's top lies below its bottom (image_top_y > image_bottom_y)");
    if (ranges.size() != static_cast<std::size_t>(scan_.beams)) {
      std::ostringstream os;
      os << "LaserCameraSensor::measure: the scan has " << ranges.size() << " readings, the geometry "
         << scan_.beams << " beams";
      fail(ErrorCode::kInvalidArgument, os.str());
    }
    LaserCameraMeasurement out;
    // 1. calibration curve
    const double theta = calibration_.toLaser(line.bearing_rad);
    // 2. the two beams around theta
    const double position = (theta - scan_.angle_min_rad) / scan_.angle_increment_rad;
    if (!(position >= 0.0) || !(position <= scan_.beams - 1)) return rejected(LaserCameraStatus::kOutsideScan);
    int i = static_cast<int>(std::floor(position));
    if (i >= scan_.beams - 1) i = scan_.beams - 2;
    int j = i + 1;
    out.beam = i;
    // 3. valid readings
    if (!valid(ranges, i) || !valid(ranges, j)) return rejected(LaserCameraStatus::kInvalidReading, i);
    // 4. continuity
    if (std::abs(at(ranges, j) - at(ranges, i)) > options_.max_jump_m) {
      if (!options_.near_side_at_jumps) return rejected(LaserCameraStatus::kRangeDiscontinuity, i);
      const int near = at(ranges, i) < at(ranges, j) ? i : j;
      const int other = near == i ? i - 1 : j + 1;
      if (other < 0 || other >= scan_.beams || !valid(ranges, other) ||
          std::abs(at(ranges, other) - at(ranges, near)) > options_.max_jump_m)
        return rejected(LaserCameraStatus::kRangeDiscontinuity, i);
      i = std::min(near, other);
      j = i + 1;
      out.extrapolated = true;
    }
    // 5. interpolated (eq. 3.4') range
    const double a_i = scan_.beamAngle(i);
    const double a_j = scan_.beamAngle(j);
    InterpolatedLaserRange ir{};
    try {
      ir = interpolateLaserRange(theta, a_i, at(ranges, i), a_j, at(ranges, j));
    } catch (const Error&) {
      // Only reachable when extrapolating: the nearer surface runs away from the bearing.
      return rejected(LaserCameraStatus::kGrazingIncidence, out.beam);
    }
    out.incidence_rad = ir.incidence_rad;
    if (ir.incidence_rad > options_.max_incidence_rad) {
      LaserCameraMeasurement r = rejected(LaserCameraStatus::kGrazingIncidence, out.beam);
      r.incidence_rad = ir.incidence_rad;
      return r;
    }
    // 6. the laser plane crosses the line in the image (Sec. 3.5)
    const double depth = ir.range_m * std::cos(theta);
    if (!(depth > 0.0)) return rejected(LaserCameraStatus::kMissesLaserPlane, out.beam);
    const double y = options_.camera_above_laser_m / depth;
    if (y < line.image_top_y - options_.plane_margin || y > line.image_bottom_y + options_.plane_margin) {
      LaserCameraMeasurement r = rejected(LaserCameraStatus::kMissesLaserPlane, out.beam);
      r.incidence_rad = ir.incidence_rad;
      return r;
    }
    // Covariance: eq. 3.5 propagated (file comment).
    const double g = calibration_.toLaserDerivative(line.bearing_rad);
    const double cal = calibration_.residualRms();
    const double var_theta = g * g * options_.sigma_bearing_rad * options_.sigma_bearing_rad + cal * cal;
    const double var_reading = options_.sigma_reading_m * options_.sigma_reading_m;
    const Vec<3>& J = ir.J_r_input;
    // Second-order term: the readings' noise tilts the interpolating chord, and that tilt
    // times the bearing error is a range error of variance var(dr/dphi) var_theta (exact for
    // a product of independent zero-mean Gaussians). At 0.5 deg between beams the chord's
    // slope is noisy (about sqrt(2) sigma_reading / 0.0087 rad), so this term is not small.
    const double h = 1e-6 * std::max(1.0, ir.range_m);
    const double ri = at(ranges, i);
    const double rj = at(ranges, j);
    const double d2_phi_ri = (interpolateLaserRange(theta, a_i, ri + h, a_j, rj).J_r_input[0] -
                              interpolateLaserRange(theta, a_i, ri - h, a_j, rj).J_r_input[0]) / (2.0 * h);
    const double d2_phi_rj = (interpolateLaserRange(theta, a_i, ri, a_j, rj + h).J_r_input[0] -
                              interpolateLaserRange(theta, a_i, ri, a_j, rj - h).J_r_input[0]) / (2.0 * h);
    const double var_slope = (d2_phi_ri * d2_phi_ri + d2_phi_rj * d2_phi_rj) * var_reading;
    // A bearing error larger than the beam spacing leaves the chord for other readings, so
    // the tilt acts over at most one chord: cap the bearing variance at that of a position
    // spread uniformly over it, increment^2 / 12.
    const double var_theta_on_chord =
        std::min(var_theta, scan_.angle_increment_rad * scan_.angle_increment_rad / 12.0);
    out.z = Vec<2>(ir.range_m, wrapAngle(theta));
    out.covariance(0, 0) =
        J[0] * J[0] * var_theta + (J[1] * J[1] + J[2] * J[2]) * var_reading + var_slope * var_theta_on_chord;
    const double bend = options_.bend_fraction * ir.range_m * scan_.angle_increment_rad;
    out.covariance(0, 0) += bend * bend;
    out.covariance(0, 1) = out.covariance(1, 0) = J[0] * var_theta;
    out.covariance(1, 1) = var_theta;
    out.status = LaserCameraStatus::kOk;
    return out;
  }

 private:
  static LaserCameraMeasurement rejected(LaserCameraStatus status, int beam = -1) {
    LaserCameraMeasurement m;
    m.status = status;
    m.beam = beam;
    return m;
  }

  static double at(const std::vector<double>& ranges, int k) { return ranges[static_cast<std::size_t>(k)]; }

  bool valid(const std::vector<double>& ranges, int k) const {
    const double r = at(ranges, k);
    return std::isfinite(r) && r >= scan_.min_range_m && r <= scan_.max_range_m && r > 0.0;
  }

  static LaserScanGeometry validated(const LaserScanGeometry& s) {
    std::ostringstream os;
    if (!std::isfinite(s.angle_min_rad) || !std::isfinite(s.angle_increment_rad) ||
        !(s.angle_increment_rad > 0.0)) {
      os << "LaserCameraSensor: the scan needs a finite angle_min and an increment > 0, got "
         << s.angle_min_rad << " and " << s.angle_increment_rad << " rad";
    } else if (s.beams < 2) {
      os << "LaserCameraSensor: the scan needs at least 2 beams, got " << s.beams;
    } else if (!std::isfinite(s.min_range_m) || !std::isfinite(s.max_range_m) || !(s.min_range_m >= 0.0) ||
               !(s.max_range_m > s.min_range_m)) {
      os << "LaserCameraSensor: the scan needs finite 0 <= min_range < max_range, got " << s.min_range_m
         << " and " << s.max_range_m << " m";
    } else {
      return s;
    }
    fail(ErrorCode::kInvalidArgument, os.str());
  }

  static LaserCameraOptions validated(const LaserCameraOptions& o) {
    std::ostringstream os;
    if (!std::isfinite(o.camera_above_laser_m) || !(o.camera_above_laser_m >= 0.0)) {
      os << "LaserCameraSensor: camera_above_laser_m must be finite and >= 0, got " << o.camera_above_laser_m;
    } else if (!std::isfinite(o.sigma_bearing_rad) || !(o.sigma_bearing_rad > 0.0) ||
               !std::isfinite(o.sigma_reading_m) || !(o.sigma_reading_m > 0.0)) {
      os << "LaserCameraSensor: the noise sigmas must be finite and > 0, got sigma_bearing = "
         << o.sigma_bearing_rad << " rad, sigma_reading = " << o.sigma_reading_m << " m";
    } else if (!std::isfinite(o.max_jump_m) || !(o.max_jump_m > 0.0)) {
      os << "LaserCameraSensor: max_jump_m must be finite and > 0, got " << o.max_jump_m;
    } else if (!(o.max_incidence_rad > 0.0) || !(o.max_incidence_rad <= 0.5 * kPi)) {
      os << "LaserCameraSensor: max_incidence_rad must be in (0, pi/2], got " << o.max_incidence_rad;
    } else if (!std::isfinite(o.bend_fraction) || !(o.bend_fraction >= 0.0)) {
      os << "LaserCameraSensor: bend_fraction must be finite and >= 0, got " << o.bend_fraction;
    } else if (!std::isfinite(o.plane_margin) || !(o.plane_margin >= 0.0)) {
      os << "LaserCameraSensor: plane_margin must be finite and >= 0, got " << o.plane_margin;
    } else {
      return o;
    }
    fail(ErrorCode::kInvalidArgument, os.str());
  }

  LaserScanGeometry scan_;
  LaserCameraCalibration calibration_;
  LaserCameraOptions options_;
};

}  // namespace sylva
