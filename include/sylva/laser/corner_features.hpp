#pragma once
/// @file
/// Corner features for range-bearing SLAM from one laser scan: the "protruding features in the
/// laser data" of the multisensor thesis (Amarasinghe 2008, Sec. 3.2.2 and 3.5), the
/// laser-only point landmarks of its indoor laser-camera SLAM. pole_features.hpp finds the
/// other kind of point feature, small free-standing segments.
///
///  1. Readings become points in the sensor frame (finite readings in [min, max] range only).
///  2. Clusters: consecutive points closer than gap_m + gap_per_m * range (the smaller of the
///     two ranges); a reading that is not valid, or a larger gap, starts a new cluster.
///  3. Each cluster is split recursively at the point farthest from the chord of its ends,
///     while that distance exceeds split_m (iterative end-point fit).
///  4. At every split point between two pieces that each hold at least min_points points and
///     span at least min_length_m, a line is fitted to each piece without the split point
///     (total least squares: the centroid and the principal axis of the scatter). Where the
///     two lines meet at an angle between min_angle and 180 deg - min_angle, their
///     intersection is a corner, kept if it lies within max_offset_m of the split point.
///
/// Only corners inside a cluster are reported: both faces are seen, so the point does not
/// depend on the viewpoint. The end of a cluster (an occluding edge) does, and is not reported.
/// Each corner comes as [range, bearing] with an isotropic position uncertainty sigma_m, so
/// R = diag(sigma^2, sigma^2 / range^2).

#include <algorithm>
#include <cmath>
#include <sstream>
#include <utility>
#include <vector>

#include "sylva/core/angles.hpp"
#include "sylva/core/error.hpp"
#include "sylva/core/types.hpp"
#include "sylva/measurements/laser_scan_geometry.hpp"

namespace sylva::laser {

struct CornerOptions {
  double gap_m = 0.10;        ///< a cluster breaks where consecutive points are farther apart
  double gap_per_m = 0.03;    ///< ... than gap_m + gap_per_m * range
  double split_m = 0.04;      ///< end-point fit: split while a point is this far from the chord
  int min_points = 6;         ///< points on each face of a corner
  double min_length_m = 0.2;  ///< length of each face
  double min_angle_rad = 45.0 * kRadPerDeg;  ///< the faces meet at [min, 180 deg - min]
  double max_offset_m = 0.15;  ///< intersection of the faces' lines to the split point
  double sigma_m = 0.03;       ///< position uncertainty told to the filter

  /// Throws kInvalidArgument naming the first option out of range.
  void validate() const {
    std::ostringstream os;
    const auto positive = [](double v) { return std::isfinite(v) && v > 0.0; };
    if (!std::isfinite(gap_m) || gap_m < 0.0 || !std::isfinite(gap_per_m) || gap_per_m < 0.0 ||
        gap_m + gap_per_m == 0.0)
      os << "corner options: need finite gap_m >= 0 and gap_per_m >= 0, not both 0, got " << gap_m
         << " m and " << gap_per_m;
    else if (!positive(split_m))
      os << "corner options: need a finite split_m > 0, got " << split_m << " m";
    else if (min_points < 2 || min_points > 100000)
      os << "corner options: need 2 <= min_points <= 100000, got " << min_points;
    else if (!std::isfinite(min_length_m) || min_length_m < 0.0)
      os << "corner options: need a finite min_length_m >= 0, got " << min_length_m << " m";
    else if (!positive(min_angle_rad) || !(min_angle_rad < 0.5 * kPi))
      os << "corner options: need 0 < min_angle < 90 deg, got " << min_angle_rad << " rad";
    else if (!positive(max_offset_m))
      os << "corner options: need a finite max_offset_m > 0, got " << max_offset_m << " m";
    else if (!positive(sigma_m))
      os << "corner options: need a finite sigma_m > 0, got " << sigma_m << " m";
    else
      return;
    fail(ErrorCode::kInvalidArgument, os.str());
  }
};

struct CornerFeature {
  Vec<2> point;          ///< the corner in the sensor frame
  Vec<2> z;              ///< [range, bearing] of `point`
  Mat<2, 2> covariance;  ///< diag(sigma^2, sigma^2 / range^2)
};

namespace detail {

/// Line through p[a..b] (inclusive) by total least squares: the centroid and a unit vector along
/// the principal axis of the scatter, whose angle is atan2(2 s_xy, s_xx - s_yy) / 2 (the major
/// axis of a 2 x 2 symmetric matrix in closed form; its sign is arbitrary).
inline std::pair<Vec<2>, Vec<2>> fitLine(const std::vector<Vec<2>>& p, int a, int b) {
  Vec<2> c = Vec<2>::Zero();
  for (int k = a; k <= b; ++k) c += p[static_cast<std::size_t>(k)];
  c /= (b - a + 1);
  double sxx = 0.0, sxy = 0.0, syy = 0.0;
  for (int k = a; k <= b; ++k) {
    const Vec<2> d = p[static_cast<std::size_t>(k)] - c;
    sxx += d.x() * d.x();
    sxy += d.x() * d.y();
    syy += d.y() * d.y();
  }
  const double angle = 0.5 * std::atan2(2.0 * sxy, sxx - syy);
  return {c, Vec<2>(std::cos(angle), std::sin(angle))};
}

/// Iterative end-point fit of p[a..b]: appends, in order, the indices where it splits.
inline void splitAtFarthest(
    const std::vector<Vec<2>>& p, int a, int b, double threshold, std::vector<int>& cuts) {
  if (b - a < 2) return;
  const Vec<2> d = p[static_cast<std::size_t>(b)] - p[static_cast<std::size_t>(a)];
  const double length = d.norm();
  int best = -1;
  double best_distance = threshold;
  for (int k = a + 1; k < b; ++k) {
    const Vec<2> q = p[static_cast<std::size_t>(k)] - p[static_cast<std::size_t>(a)];
    const double distance =
        length > 0.0 ? std::abs(d.x() * q.y() - d.y() * q.x()) / length : q.norm();
    if (distance > best_distance) {
      best_distance = distance;
      best = k;
    }
  }
  if (best < 0) return;
  splitAtFarthest(p, a, best, threshold, cuts);
  cuts.push_back(best);
  splitAtFarthest(p, best, b, threshold, cuts);
}

/// The corners of one cluster (points in beam order), appended to `out`.
inline void clusterCorners(const std::vector<Vec<2>>& p,
                           const CornerOptions& o,
                           std::vector<CornerFeature>& out) {
  const int n = static_cast<int>(p.size());
  if (n < 2 * o.min_points) return;
  std::vector<int> bounds{0};
  splitAtFarthest(p, 0, n - 1, o.split_m, bounds);
  bounds.push_back(n - 1);
  const auto at = [&p](int k) -> const Vec<2>& { return p[static_cast<std::size_t>(k)]; };
  for (std::size_t k = 1; k + 1 < bounds.size(); ++k) {
    const int a = bounds[k - 1], m = bounds[k], b = bounds[k + 1];
    // The split point belongs to both faces; each face's line is fitted without it.
    if (m - a < o.min_points || b - m < o.min_points) continue;
    if ((at(m - 1) - at(a)).norm() < o.min_length_m || (at(b) - at(m + 1)).norm() < o.min_length_m)
      continue;
    const auto [c1, d1] = fitLine(p, a, m - 1);
    const auto [c2, d2] = fitLine(p, m + 1, b);
    const double cross = d1.x() * d2.y() - d1.y() * d2.x();  // sin of the angle between the faces
    if (std::abs(cross) < std::sin(o.min_angle_rad)) continue;
    const Vec<2> w = c2 - c1;
    const Vec<2> corner = c1 + ((w.x() * d2.y() - w.y() * d2.x()) / cross) * d1;
    if ((corner - at(m)).norm() > o.max_offset_m) continue;
    const double r = corner.norm();
    CornerFeature f;
    f.point = corner;
    f.z = Vec<2>(r, std::atan2(corner.y(), corner.x()));
    f.covariance = Mat<2, 2>::Zero();
    f.covariance(0, 0) = o.sigma_m * o.sigma_m;
    f.covariance(1, 1) = o.sigma_m * o.sigma_m / (r * r);
    out.push_back(f);
  }
}

}  // namespace detail

/// The corners of one scan (`ranges`, one per beam of `g`), in beam order. Readings that are
/// not finite or lie outside [min_range, max_range] are skipped. Throws kInvalidArgument when
/// `ranges` does not hold one reading per beam or an option is out of range.
inline std::vector<CornerFeature> extractCornerFeatures(const std::vector<double>& ranges,
                                                        const LaserScanGeometry& g,
                                                        const CornerOptions& o = {}) {
  o.validate();
  if (g.beams < 0 || ranges.size() != static_cast<std::size_t>(g.beams)) {
    std::ostringstream os;
    os << "extractCornerFeatures: the scan holds " << ranges.size() << " readings for " << g.beams
       << " beams";
    fail(ErrorCode::kInvalidArgument, os.str());
  }
  std::vector<CornerFeature> out;
  std::vector<Vec<2>> cluster;
  double previous_range = 0.0;
  for (int k = 0; k < g.beams; ++k) {
    const double r = ranges[static_cast<std::size_t>(k)];
    if (!std::isfinite(r) || r < g.min_range_m || r > g.max_range_m) {
      detail::clusterCorners(cluster, o, out);
      cluster.clear();
      continue;
    }
    const double a = g.beamAngle(k);
    const Vec<2> p(r * std::cos(a), r * std::sin(a));
    if (!cluster.empty() &&
        (p - cluster.back()).norm() > o.gap_m + o.gap_per_m * std::min(r, previous_range)) {
      detail::clusterCorners(cluster, o, out);
      cluster.clear();
    }
    cluster.push_back(p);
    previous_range = r;
  }
  detail::clusterCorners(cluster, o, out);
  return out;
}

}  // namespace sylva::laser
