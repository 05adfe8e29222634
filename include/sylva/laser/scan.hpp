#pragma once
/// @file
/// Laser scans as the moving-object detector sees them: the beam geometry shared by every
/// scan of one scanner, what each reading means, and a scan placed in the world frame with
/// the sensor pose it was taken from (the "alignment" the thesis assumes before detection,
/// Amarasinghe 2008 Sec. 4.3: the pose comes from the simulator, odometry or the filter).
///
/// Readings. A range r of beam i is
///   valid      range_min <= r <= range_max (finite);
///   no return  r = +infinity or r > range_max: nothing within reach; the beam saw free
///              space up to range_max (ROS reports "no return" as +inf);
///   invalid    NaN, r < range_min (negative included): the scanner could not measure; the
///              beam tells nothing, not even free space.
/// Only valid readings become points. This is a defined behaviour, not an error: real
/// scans hold both kinds (the leg-tracker data has 67 % inf and a few NaN).

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <vector>

#include "sylva/core/error.hpp"
#include "sylva/core/types.hpp"
#include "sylva/measurements/laser_scan_geometry.hpp"

namespace sylva::laser {


/// Throws kInvalidArgument unless the beam geometry `g` makes sense for the detector: 2 to
/// 100000 beams spanning at most 2 pi, and finite 0 <= min_range < max_range.
inline void validateScanGeometry(const LaserScanGeometry& g) {
  std::ostringstream os;
  if (g.beams < 2 || g.beams > 100000) {
    os << "scan geometry: need 2 to 100000 beams, got " << g.beams;
  } else if (!std::isfinite(g.angle_min_rad) || !std::isfinite(g.angle_increment_rad) ||
             !(g.angle_increment_rad > 0.0) || !((g.beams - 1) * g.angle_increment_rad <= 6.2832)) {
    os << "scan geometry: need a finite angle_min and 0 < increment with the beams spanning "
          "at most 2 pi, got angle_min = "
       << g.angle_min_rad << " rad, increment = " << g.angle_increment_rad << " rad";
  } else if (!std::isfinite(g.min_range_m) || !std::isfinite(g.max_range_m) || !(g.min_range_m >= 0.0) ||
             !(g.max_range_m > g.min_range_m)) {
    os << "scan geometry: need finite 0 <= min_range < max_range, got " << g.min_range_m << " m and "
       << g.max_range_m << " m";
  } else {
    return;
  }
  sylva::fail(sylva::ErrorCode::kInvalidArgument, os.str());
}

enum class Reading : std::uint8_t { kValid, kNoReturn, kInvalid };

inline Reading classifyReading(double r, const LaserScanGeometry& g) {
  if (std::isnan(r) || r < g.min_range_m) return Reading::kInvalid;
  if (r > g.max_range_m) return Reading::kNoReturn;  // +inf included
  return Reading::kValid;
}

/// One scan in the world frame.
struct AlignedScan {
  Vec<3> sensor_pose = Vec<3>::Zero();  ///< [x, y, theta] of the scanner in the world
  std::vector<double> ranges;           ///< as given
  std::vector<Reading> reading;         ///< what each range means
  std::vector<Vec<2>> points;           ///< world point of each valid reading (else NaN)
  int no_return = 0;
  int invalid = 0;

  bool valid(int i) const { return reading[static_cast<std::size_t>(i)] == Reading::kValid; }
  const Vec<2>& point(int i) const { return points[static_cast<std::size_t>(i)]; }
  double range(int i) const { return ranges[static_cast<std::size_t>(i)]; }
  int size() const { return static_cast<int>(ranges.size()); }
  Vec<2> origin() const { return sensor_pose.head<2>(); }
};

/// Places `ranges` (one per beam of `g`) in the world from `sensor_pose`. Throws
/// kInvalidArgument when the number of ranges is not the number of beams, kNonFinite when
/// the pose is not finite. Readings that are not valid are counted, never an error.
inline AlignedScan alignScan(const LaserScanGeometry& g, const std::vector<double>& ranges, const Vec<3>& sensor_pose) {
  if (static_cast<int>(ranges.size()) != g.beams) {
    std::ostringstream os;
    os << "a scan has " << ranges.size() << " ranges but the scanner has " << g.beams << " beams";
    sylva::fail(sylva::ErrorCode::kInvalidArgument, os.str());
  }
  if (!sensor_pose.allFinite())
    sylva::fail(sylva::ErrorCode::kNonFinite, "the sensor pose of a scan is not finite");
  AlignedScan out;
  out.sensor_pose = sensor_pose;
  out.ranges = ranges;
  out.reading.resize(ranges.size());
  out.points.assign(ranges.size(), Vec<2>::Constant(std::nan("")));
  for (int i = 0; i < g.beams; ++i) {
    const auto k = static_cast<std::size_t>(i);
    out.reading[k] = classifyReading(ranges[k], g);
    if (out.reading[k] == Reading::kNoReturn) ++out.no_return;
    if (out.reading[k] == Reading::kInvalid) ++out.invalid;
    if (out.reading[k] != Reading::kValid) continue;
    const double a = sensor_pose[2] + g.beamAngle(i);
    out.points[k] = sensor_pose.head<2>() + ranges[k] * Vec<2>(std::cos(a), std::sin(a));
  }
  return out;
}

/// eq. 4.4 with a floor: a distance threshold that grows with the range like the spacing of
/// neighbouring beams, max(floor, k tan(resolution) r). The thesis writes tan(pi / 360) for
/// its 0.5 deg scanner; with floor = 0 this is eq. 4.4 exactly.
inline double rangeThreshold(double k, double floor_m, double resolution_rad, double range_m) {
  return std::max(floor_m, k * std::tan(resolution_rad) * range_m);
}

}  // namespace sylva::laser
