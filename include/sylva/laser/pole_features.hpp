#pragma once
/// @file
/// Point features for 2D range-bearing SLAM from one laser scan: small, free-standing,
/// roughly circular segments (poles, trunks and, unavoidably, legs), each turned into a
/// [range, bearing] measurement of its centre.
///
/// A feature is a continuous segment of the scan's valid readings (segments.hpp thresholds)
/// that
///   - has at least `min_points` readings,
///   - has a chord (first to last point) of at most `max_width_m`,
///   - stands free: the beams just outside it are no-return, or read farther than the
///     segment's nearest reading by at least `min_depth_gap_m` (a piece of wall cut by
///     occlusion fails this on one side), and the segment is not at the edge of the scan.
///
/// Centre estimate. For a disc of radius r the readings lie on its near arc. The radius is
/// estimated as r^ = (chord + one beam spacing at that range) / 2 (the extreme readings lie
/// up to a beam inside the silhouette), clamped to [min_radius_m, max_width_m / 2]; the
/// centre is r^ beyond the median range of the segment's middle third, on the bearing
/// halfway between the first and last beams.

#include <algorithm>
#include <cmath>
#include <vector>

#include "sylva/core/angles.hpp"
#include "sylva/core/types.hpp"

#include "sylva/laser/scan.hpp"
#include "sylva/laser/segments.hpp"

namespace sylva::laser {

struct FeatureOptions {
  SegmentOptions segments{3.0, 0.06, 1};
  int min_points = 3;
  double max_width_m = 0.35;
  double min_depth_gap_m = 0.3;
  double min_radius_m = 0.02;
};

struct PointFeature {
  Vec<2> z;                  ///< [range, bearing] of the estimated centre, sensor frame
  Vec<2> world;              ///< the centre in the world, from the scan's sensor pose
  double radius_m = 0.0;     ///< estimated radius
  std::vector<int> beams;    ///< readings it was made of
};

inline std::vector<PointFeature> extractPointFeatures(const LaserScanGeometry& g,
                                                      const AlignedScan& scan,
                                                      const FeatureOptions& o) {
  std::vector<PointSet> all(static_cast<std::size_t>(scan.size()), PointSet::kNone);
  for (int i = 0; i < scan.size(); ++i)
    if (scan.valid(i)) all[static_cast<std::size_t>(i)] = PointSet::kA;
  const std::vector<Segment> segments = segmentSet(g, scan, all, PointSet::kA, o.segments);
  std::vector<PointFeature> out;
  for (const Segment& s : segments) {
    if (s.size() < o.min_points) continue;
    if (s.first() == 0 || s.last() == scan.size() - 1) continue;  // may continue outside the scan
    const double chord = (scan.point(s.first()) - scan.point(s.last())).norm();
    if (chord > o.max_width_m) continue;
    double nearest = scan.range(s.first());
    for (const int b : s.beams) nearest = std::min(nearest, scan.range(b));
    const auto freeSide = [&](int beam) {
      const auto kind = scan.reading[static_cast<std::size_t>(beam)];
      if (kind == Reading::kNoReturn) return true;
      return kind == Reading::kValid && scan.range(beam) >= nearest + o.min_depth_gap_m;
    };
    if (!freeSide(s.first() - 1) || !freeSide(s.last() + 1)) continue;

    std::vector<double> middle;
    const int n = s.size();
    for (int k = n / 3; k < n - n / 3; ++k) middle.push_back(scan.range(s.beams[static_cast<std::size_t>(k)]));
    std::nth_element(middle.begin(), middle.begin() + static_cast<std::ptrdiff_t>(middle.size() / 2), middle.end());
    const double front = middle[middle.size() / 2];
    const double spacing = std::tan(g.angle_increment_rad) * front;
    const double radius = std::clamp(0.5 * (chord + spacing), o.min_radius_m, 0.5 * o.max_width_m);
    const double bearing = sylva::wrapAngle(0.5 * (g.beamAngle(s.first()) + g.beamAngle(s.last())));
    PointFeature f;
    f.z = Vec<2>(front + radius, bearing);
    const double a = scan.sensor_pose[2] + bearing;
    f.world = scan.origin() + f.z[0] * Vec<2>(std::cos(a), std::sin(a));
    f.radius_m = radius;
    f.beams = s.beams;
    out.push_back(std::move(f));
  }
  return out;
}

}  // namespace sylva::laser
