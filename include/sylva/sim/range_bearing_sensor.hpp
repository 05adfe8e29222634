#pragma once
/// @file
/// `sim::RangeBearingSensor2D`: a range-bearing sensor (laser, or camera bearing plus laser
/// range) on a `Unicycle2D` robot, looking forward along the heading.
///
/// A landmark at true range d and true bearing b (the `RangeBearing` model, thesis eq.
/// 2.16-2.17, evaluated at the true pose) is seen when
///
///   min_range <= d <= max_range   and   |b| <= fov_half_angle,
///
/// and its reading is z = [d + sigma_range n_1, wrap(b + sigma_bearing n_2)], n_i ~ N(0, 1)
/// (two normal draws per visible landmark, range then bearing, in the order of the landmark
/// list). Visibility is decided on the true geometry, so a landmark never "flickers" because
/// of noise. The bearing is wrapped to (-pi, pi] like the model's. These readings match
/// `RangeBearing` with noise `noise()` exactly, the model the filter is told.
///
/// Defaults: max range 8 m, field of view +-90 deg, and the noise of Table 3.1 of the
/// multisensor thesis (sigma_range = 5 cm, sigma_bearing = 1 deg).

#include <cmath>
#include <sstream>
#include <vector>

#include "sylva/core/angles.hpp"
#include "sylva/core/error.hpp"
#include "sylva/core/types.hpp"
#include "sylva/measurements/range_bearing.hpp"
#include "sylva/noise/gaussian.hpp"
#include "sylva/sim/landmarks_2d.hpp"
#include "sylva/sim/random.hpp"

namespace sylva::sim {

struct RangeBearingSensor2DOptions {
  double max_range_m = 8.0;                      ///< > min_range
  double min_range_m = 0.1;                      ///< >= 0; closer landmarks are not seen
  double fov_half_angle_rad = 0.5 * kPi;         ///< in (0, pi]
  double sigma_range_m = 0.05;                   ///< Table 3.1: 5 cm
  double sigma_bearing_rad = 1.0 * kRadPerDeg;  ///< Table 3.1: 1 deg
};

/// One reading: which landmark (the simulator's id, for known association and evaluation)
/// and the measured [range_m, bearing_rad].
struct RangeBearingReading {
  Id id;
  Vec<2> z;
};

class RangeBearingSensor2D {
 public:
  explicit RangeBearingSensor2D(const RangeBearingSensor2DOptions& options = {})
      : options_(validated(options)),
        noise_(Gaussian<2>::sigmas(Vec<2>(options.sigma_range_m, options.sigma_bearing_rad))) {}

  const RangeBearingSensor2DOptions& options() const { return options_; }
  /// The measurement noise as `Ekf::update` and `Ekf::add` take it.
  const Gaussian<2>& noise() const { return noise_; }

  /// True when a landmark at `landmark` is inside the sensor's range and field of view from
  /// the true pose `pose`.
  bool visible(const Vec<3>& pose, const Vec<2>& landmark) const {
    const double d = (landmark - pose.head<2>()).norm();
    if (!(d >= options_.min_range_m && d <= options_.max_range_m) || d < RangeBearing::kMinRange)
      return false;
    return std::abs(RangeBearing{}(pose, landmark)[1]) <= options_.fov_half_angle_rad;
  }

  /// Noisy readings of every visible landmark from the true pose `pose`.
  std::vector<RangeBearingReading> observe(const Vec<3>& pose,
                                           const std::vector<TrueLandmark2D>& landmarks,
                                           Rng& rng) const {
    if (!pose.allFinite())
      fail(ErrorCode::kNonFinite, "RangeBearingSensor2D::observe: pose is not finite");
    std::vector<RangeBearingReading> out;
    const RangeBearing model;
    for (const TrueLandmark2D& landmark : landmarks) {
      if (!visible(pose, landmark.position)) continue;
      const Vec<2> z = model(pose, landmark.position);
      const double range = z[0] + options_.sigma_range_m * rng.normal();
      const double bearing = wrapAngle(z[1] + options_.sigma_bearing_rad * rng.normal());
      out.push_back(RangeBearingReading{landmark.id, Vec<2>(range, bearing)});
    }
    return out;
  }

 private:
  static RangeBearingSensor2DOptions validated(const RangeBearingSensor2DOptions& o) {
    std::ostringstream os;
    if (!std::isfinite(o.max_range_m) || !std::isfinite(o.min_range_m) || !(o.min_range_m >= 0.0) ||
        !(o.max_range_m > o.min_range_m)) {
      os << "RangeBearingSensor2D: need finite 0 <= min_range < max_range, got min_range = "
         << o.min_range_m << " m, max_range = " << o.max_range_m << " m";
    } else if (!std::isfinite(o.fov_half_angle_rad) || !(o.fov_half_angle_rad > 0.0) ||
               !(o.fov_half_angle_rad <= kPi)) {
      os << "RangeBearingSensor2D: the field-of-view half angle must be in (0, pi], got "
         << o.fov_half_angle_rad << " rad";
    } else if (!std::isfinite(o.sigma_range_m) || !(o.sigma_range_m > 0.0) ||
               !std::isfinite(o.sigma_bearing_rad) || !(o.sigma_bearing_rad > 0.0)) {
      os << "RangeBearingSensor2D: sigma_range and sigma_bearing must be finite and > 0, got "
         << o.sigma_range_m << " m and " << o.sigma_bearing_rad << " rad";
    } else {
      return o;
    }
    fail(ErrorCode::kInvalidArgument, os.str());
  }

  RangeBearingSensor2DOptions options_;
  Gaussian<2> noise_;
};

}  // namespace sylva::sim
