#pragma once
/// @file
/// `sylva::slam::landmarksInReach`: the mapped landmarks a planar range-bearing sensor can see
/// from the current estimate, the candidates that association (nearest neighbour, JCBB) and
/// the new-landmark test compare a scan with.
///
/// A landmark is in reach when its predicted reading, measured the way `RangeBearing`
/// measures it (range from the sensor position, bearing relative to the robot heading, so a
/// mounted sensor is handled), lies in
///
///   min_range_m <= range <= max_range_m   and   |bearing| <= half_fov_rad.
///
/// Give the limits with a margin for the estimate's uncertainty (a landmark just outside the
/// sensor's nominal range may still be the one it saw). A landmark closer to the sensor than
/// `RangeBearing::kMinRange` has no bearing and is never in reach, whatever `min_range_m` says.
///
/// Cost: O(number of landmarks of the type asked for); no allocation once `out` has grown.

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <vector>

#include "sylva/core/angles.hpp"
#include "sylva/core/error.hpp"
#include "sylva/core/types.hpp"
#include "sylva/filter/ekf.hpp"
#include "sylva/measurements/range_bearing.hpp"

namespace sylva::slam {

/// The part of the plane a range-bearing sensor can see (see the file comment).
struct RangeBearingReach {
  double max_range_m = std::numeric_limits<double>::infinity();
  double half_fov_rad = kPi;  ///< all around by default
  double min_range_m = 0.0;
};

/// Throws kInvalidArgument unless 0 <= min_range_m <= max_range_m (max may be +inf) and
/// half_fov_rad >= 0, none of them NaN.
inline void checkReach(const RangeBearingReach& reach) {
  const bool ok = reach.min_range_m >= 0.0 && reach.max_range_m >= reach.min_range_m && reach.half_fov_rad >= 0.0 &&
                  std::isfinite(reach.min_range_m) && !std::isnan(reach.half_fov_rad);
  if (!ok) {
    std::ostringstream os;
    os << "slam::RangeBearingReach: need 0 <= min_range_m <= max_range_m and half_fov_rad >= 0, got min_range_m = "
       << reach.min_range_m << ", max_range_m = " << reach.max_range_m << ", half_fov_rad = " << reach.half_fov_rad;
    fail(ErrorCode::kInvalidArgument, os.str());
  }
}

/// Replaces `out` with the ids of the filter's `Landmark` slots (a type with a planar
/// position, `Landmark::kPlanarPosition`: Point2, TreeXYR) whose reading through `sensor` at
/// the current estimate is within `reach`, in slot order. Slots of other types are skipped.
/// Throws kInvalidArgument for a malformed reach (`out` is then unchanged).
template <typename Landmark, typename Filter>
void landmarksInReach(const Filter& ekf, const RangeBearing& sensor, const RangeBearingReach& reach,
                      std::vector<Id>& out) {
  static_assert(Filter::template kHolds<Landmark>, "landmarksInReach: Landmark is not in the filter's Landmarks...");
  constexpr int kPosition = Landmark::kPlanarPosition;
  checkReach(reach);
  out.clear();
  const Vec<3> pose = ekf.robotMean().template head<3>();  // the Pose2D view
  const Vec<2> origin = sensor.sensorPosition<double>(pose);
  const double min_range = std::max(reach.min_range_m, RangeBearing::kMinRange);
  const int type = Filter::template typeIndexOf<Landmark>();
  for (const LandmarkSlot& s : ekf.slots()) {
    if (s.type_index != type) continue;
    const Vec<2> d = ekf.template landmarkMean<Landmark>(s.id).template segment<2>(kPosition) - origin;
    const double range = d.norm();
    if (range > reach.max_range_m || range < min_range) continue;
    if (std::abs(wrapAngle(std::atan2(d.y(), d.x()) - pose[2])) > reach.half_fov_rad) continue;
    out.push_back(s.id);
  }
}

/// landmarksInReach (above), returning a new vector.
template <typename Landmark, typename Filter>
std::vector<Id> landmarksInReach(const Filter& ekf, const RangeBearing& sensor, const RangeBearingReach& reach) {
  std::vector<Id> out;
  landmarksInReach<Landmark>(ekf, sensor, reach, out);
  return out;
}

/// The candidate source of `slam::FrontEnd` (front_end.hpp) for a planar range-bearing
/// sensor: a callable `(const Filter&, std::vector<Id>&)` that runs `landmarksInReach`.
/// Throws kInvalidArgument for a malformed reach, here rather than at the first step.
template <typename Landmark>
auto candidatesInReach(const RangeBearing& sensor, const RangeBearingReach& reach) {
  checkReach(reach);
  return [sensor, reach](const auto& ekf, std::vector<Id>& out) { landmarksInReach<Landmark>(ekf, sensor, reach, out); };
}

}  // namespace sylva::slam
