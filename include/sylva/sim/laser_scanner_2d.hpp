#pragma once
/// @file
/// `sim::LaserScanner2D`: a planar laser range finder (SICK LMS200 class) that casts its
/// beams into a `LaserScene2D`.
///
/// Beams. The scanner at sensor pose [x, y, theta] (world frame; theta is the direction of
/// the scanner's x axis) sends n beams at the angles, relative to theta,
///
///   alpha_i = -fov / 2 + i * resolution,   i = 0 .. n - 1,   n = floor(fov / resolution) + 1
///
/// (counter-clockwise positive, so beam 0 looks to the right, as in ROS). The defaults are
/// those of the multisensor thesis' experiments (Sec. 4.3.5): a 180 deg field of view at
/// 0.5 deg resolution, 361 beams, all taken at the same instant (the scan is a snapshot of
/// the scene; the sweep time of a real scanner is ignored).
///
/// Readings. Beam i meets the scene at true distance d_i (`LaserScene2D::castRay`). When
/// min_range <= d_i <= max_range the reading is
///
///   r_i = max(0, d_i + sigma_range n_i),   n_i ~ N(0, 1),
///
/// one normal draw per returning beam in beam order (none when sigma_range = 0). A beam
/// with d_i > max_range (nothing in reach) reads +infinity, "no return", as ROS reports it.
/// A beam with d_i < min_range (an object touching the scanner) reads NaN, "invalid", the
/// way real scanners flag a reading they cannot measure. The noise never makes a reading
/// disappear, so a reading may lie a few sigma beyond max_range; users that need readings
/// inside [min_range, max_range] clamp or drop them (the moving-object example treats
/// readings outside it as no return).
///
/// Ground truth. Alongside the ranges the scan records, per beam, the id of the object hit
/// (`kNoObject` for no return) and the true distance, for evaluating detectors.
///
/// Cost: n rays, each O(shapes in the scene); `scan(pose, scene, rng, out)` reuses `out`'s
/// storage and does not allocate once `out` has held a scan of this scanner.
///
/// Errors: options with fov outside (0, 2 pi], resolution <= 0 or above the fov, more than
/// 100000 beams, ranges not 0 <= min < max, sigma < 0, or anything non-finite throw
/// kInvalidArgument at construction; a non-finite pose throws kNonFinite.

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <vector>

#include "sylva/core/angles.hpp"
#include "sylva/core/error.hpp"
#include "sylva/core/types.hpp"
#include "sylva/measurements/laser_scan_geometry.hpp"
#include "sylva/sim/laser_scene_2d.hpp"
#include "sylva/sim/random.hpp"

namespace sylva::sim {

struct LaserScanner2DOptions {
  double fov_rad = kPi;                       ///< total field of view, in (0, 2 pi]
  double resolution_rad = 0.5 * kRadPerDeg;  ///< angle between neighbouring beams, > 0
  double min_range_m = 0.05;                  ///< >= 0; closer hits read NaN
  double max_range_m = 8.0;                   ///< > min_range; farther hits read +infinity
  double sigma_range_m = 0.01;                ///< range noise, >= 0 (SICK LMS200: about 1 cm)
};

/// One simulated scan: readings in beam order and the truth behind them.
struct LaserScan2D {
  std::vector<double> ranges_m;      ///< +infinity: no return; NaN: closer than min_range
  std::vector<Id> hit_object;        ///< truth: object hit by each beam, kNoObject if none
  std::vector<double> true_range_m;  ///< truth: noiseless distance, +infinity if none
  double time_s = 0.0;               ///< when the scan was taken (set by the caller)
};

class LaserScanner2D {
 public:
  explicit LaserScanner2D(const LaserScanner2DOptions& options = {})
      : options_(validated(options)),
        beams_(static_cast<int>(std::floor(options_.fov_rad / options_.resolution_rad + 1e-9)) + 1) {}

  const LaserScanner2DOptions& options() const { return options_; }
  int beamCount() const { return beams_; }
  /// Angle of beam i relative to the sensor heading (rad).
  double beamAngle(int i) const { return -0.5 * options_.fov_rad + i * options_.resolution_rad; }
  double angleMin() const { return -0.5 * options_.fov_rad; }
  double angleIncrement() const { return options_.resolution_rad; }
  /// The beams and valid ranges of this scanner's scans, as the scan readers take them.
  LaserScanGeometry geometry() const {
    LaserScanGeometry g;
    g.angle_min_rad = angleMin();
    g.angle_increment_rad = angleIncrement();
    g.beams = beamCount();
    g.min_range_m = options_.min_range_m;
    g.max_range_m = options_.max_range_m;
    return g;
  }

  /// Scans `scene` from `sensor_pose` = [x, y, theta] into `out` (storage reused).
  void scan(const Vec<3>& sensor_pose, const LaserScene2D& scene, Rng& rng, LaserScan2D& out) const {
    if (!sensor_pose.allFinite())
      fail(ErrorCode::kNonFinite, "LaserScanner2D::scan: the sensor pose is not finite");
    const auto n = static_cast<std::size_t>(beams_);
    out.ranges_m.resize(n);
    out.hit_object.resize(n);
    out.true_range_m.resize(n);
    const Vec<2> origin = sensor_pose.head<2>();
    constexpr double kInf = std::numeric_limits<double>::infinity();
    for (int i = 0; i < beams_; ++i) {
      const auto k = static_cast<std::size_t>(i);
      const double angle = sensor_pose[2] + beamAngle(i);
      const Vec<2> direction(std::cos(angle), std::sin(angle));
      const RayHit hit = scene.castRay(origin, direction, options_.max_range_m);
      out.true_range_m[k] = hit.distance_m;
      out.hit_object[k] = hit.object_id;
      if (hit.object_id == kNoObject) {
        out.ranges_m[k] = kInf;
      } else if (hit.distance_m < options_.min_range_m) {
        out.ranges_m[k] = std::numeric_limits<double>::quiet_NaN();
      } else {
        const double noise = options_.sigma_range_m > 0.0 ? options_.sigma_range_m * rng.normal() : 0.0;
        out.ranges_m[k] = std::max(0.0, hit.distance_m + noise);
      }
    }
  }

  LaserScan2D scan(const Vec<3>& sensor_pose, const LaserScene2D& scene, Rng& rng) const {
    LaserScan2D out;
    scan(sensor_pose, scene, rng, out);
    return out;
  }

 private:
  static LaserScanner2DOptions validated(const LaserScanner2DOptions& o) {
    std::ostringstream os;
    if (!std::isfinite(o.fov_rad) || !(o.fov_rad > 0.0) || !(o.fov_rad <= 2.0 * kPi + 1e-12)) {
      os << "LaserScanner2D: the field of view must be in (0, 2 pi] rad, got " << o.fov_rad;
    } else if (!std::isfinite(o.resolution_rad) || !(o.resolution_rad > 0.0) ||
               !(o.resolution_rad <= o.fov_rad)) {
      os << "LaserScanner2D: the resolution must be > 0 and at most the field of view, got "
         << o.resolution_rad << " rad for a field of view of " << o.fov_rad << " rad";
    } else if (o.fov_rad / o.resolution_rad > 100000.0) {
      os << "LaserScanner2D: " << o.fov_rad / o.resolution_rad
         << " beams per scan is more than the 100000 this simulator accepts";
    } else if (!std::isfinite(o.min_range_m) || !std::isfinite(o.max_range_m) ||
               !(o.min_range_m >= 0.0) || !(o.max_range_m > o.min_range_m)) {
      os << "LaserScanner2D: need finite 0 <= min_range < max_range, got min_range = "
         << o.min_range_m << " m, max_range = " << o.max_range_m << " m";
    } else if (!std::isfinite(o.sigma_range_m) || !(o.sigma_range_m >= 0.0)) {
      os << "LaserScanner2D: the range noise must be finite and >= 0, got " << o.sigma_range_m
         << " m";
    } else {
      return o;
    }
    fail(ErrorCode::kInvalidArgument, os.str());
  }

  LaserScanner2DOptions options_;
  int beams_;
};

}  // namespace sylva::sim
