#pragma once
// A simple laser corner extractor for the laser_camera_slam example: the laser-only point
// landmarks ("protruding features in the laser data", thesis Sec. 3.2.2 and 3.5).
//
//  1. readings -> points in the laser frame (only finite readings in [min, max] range);
//  2. clusters: consecutive points closer than gap_m + gap_per_m * range (an invalid reading
//     or a larger gap starts a new cluster);
//  3. each cluster is split recursively at the point farthest from the chord of its ends
//     while that distance exceeds split_m (iterative end-point fit);
//  4. for every split point between two pieces that each hold at least min_points points
//     and span at least min_length_m, a line is fitted to each piece (total least squares:
//     centroid and the principal direction); when the lines meet at an angle between
//     min_angle and 180 deg - min_angle, their intersection is a corner, kept if it lies
//     within max_offset_m of the split point.
//
// Only corners inside a cluster are reported: both faces are seen, so the point is direction
// invariant. The end of a cluster (an occluding edge) is not: it moves with the viewpoint.
// Each corner is reported as [range, bearing] with an isotropic position uncertainty
// sigma_m: R = diag(sigma^2, sigma^2 / range^2).

#include <cmath>
#include <vector>

#include <Eigen/Eigenvalues>

#include <sylva/core/types.hpp>
#include <sylva/laser_camera/sensor.hpp>

namespace laser_camera_slam {

using sylva::Mat;
using sylva::Vec;

struct CornerOptions {
  double gap_m = 0.10;
  double gap_per_m = 0.03;
  double split_m = 0.04;
  int min_points = 6;
  double min_length_m = 0.2;
  double min_angle_rad = 45.0 * sylva::kRadPerDeg;
  double max_offset_m = 0.15;
  double sigma_m = 0.03;  ///< position uncertainty told to the filter
};

struct Corner {
  Vec<2> point;        ///< laser frame
  Vec<2> z;            ///< [range, bearing]
  Mat<2, 2> covariance;
};

namespace detail {

/// Line through points[a..b] (inclusive) by total least squares: centroid and unit direction.
inline std::pair<Vec<2>, Vec<2>> fitLine(const std::vector<Vec<2>>& p, int a, int b) {
  Vec<2> c = Vec<2>::Zero();
  for (int k = a; k <= b; ++k) c += p[static_cast<std::size_t>(k)];
  c /= (b - a + 1);
  Mat<2, 2> s = Mat<2, 2>::Zero();
  for (int k = a; k <= b; ++k) {
    const Vec<2> d = p[static_cast<std::size_t>(k)] - c;
    s += d * d.transpose();
  }
  Eigen::SelfAdjointEigenSolver<Mat<2, 2>> eig(s);
  return {c, eig.eigenvectors().col(1)};
}

inline void split(const std::vector<Vec<2>>& p, int a, int b, double threshold, std::vector<int>& cuts) {
  if (b - a < 2) return;
  const Vec<2> d = p[static_cast<std::size_t>(b)] - p[static_cast<std::size_t>(a)];
  const double len = d.norm();
  int best = -1;
  double best_dist = threshold;
  for (int k = a + 1; k < b; ++k) {
    const Vec<2> q = p[static_cast<std::size_t>(k)] - p[static_cast<std::size_t>(a)];
    const double dist = len > 0.0 ? std::abs(d.x() * q.y() - d.y() * q.x()) / len : q.norm();
    if (dist > best_dist) {
      best_dist = dist;
      best = k;
    }
  }
  if (best < 0) return;
  split(p, a, best, threshold, cuts);
  cuts.push_back(best);
  split(p, best, b, threshold, cuts);
}

}  // namespace detail

inline std::vector<Corner> extractCorners(const std::vector<double>& ranges,
                                          const sylva::LaserScanGeometry& g,
                                          const CornerOptions& o = {}) {
  std::vector<Corner> out;
  std::vector<Vec<2>> cluster;
  auto flush = [&]() {
    const int n = static_cast<int>(cluster.size());
    if (n >= 2 * o.min_points) {
      std::vector<int> cuts;
      detail::split(cluster, 0, n - 1, o.split_m, cuts);
      std::vector<int> bounds;
      bounds.push_back(0);
      bounds.insert(bounds.end(), cuts.begin(), cuts.end());
      bounds.push_back(n - 1);
      for (std::size_t k = 1; k + 1 < bounds.size(); ++k) {
        const int a = bounds[k - 1], m = bounds[k], b = bounds[k + 1];
        // The split point itself is shared; fit each side without it.
        if (m - a < o.min_points || b - m < o.min_points) continue;
        const auto& P = cluster;
        if ((P[static_cast<std::size_t>(m - 1)] - P[static_cast<std::size_t>(a)]).norm() < o.min_length_m ||
            (P[static_cast<std::size_t>(b)] - P[static_cast<std::size_t>(m + 1)]).norm() < o.min_length_m)
          continue;
        const auto [c1, d1] = detail::fitLine(P, a, m - 1);
        const auto [c2, d2] = detail::fitLine(P, m + 1, b);
        const double cross = d1.x() * d2.y() - d1.y() * d2.x();
        if (std::abs(cross) < std::sin(o.min_angle_rad)) continue;
        const Vec<2> w = c2 - c1;
        const double t = (w.x() * d2.y() - w.y() * d2.x()) / cross;
        const Vec<2> corner = c1 + t * d1;
        if ((corner - P[static_cast<std::size_t>(m)]).norm() > o.max_offset_m) continue;
        const double r = corner.norm();
        Corner c;
        c.point = corner;
        c.z = Vec<2>(r, std::atan2(corner.y(), corner.x()));
        c.covariance = Mat<2, 2>::Zero();
        c.covariance(0, 0) = o.sigma_m * o.sigma_m;
        c.covariance(1, 1) = o.sigma_m * o.sigma_m / (r * r);
        out.push_back(c);
      }
    }
    cluster.clear();
  };
  double previous_range = 0.0;
  for (int k = 0; k < g.beams; ++k) {
    const double r = ranges[static_cast<std::size_t>(k)];
    if (!std::isfinite(r) || r < g.min_range_m || r > g.max_range_m) {
      flush();
      continue;
    }
    const double a = g.beamAngle(k);
    const Vec<2> p(r * std::cos(a), r * std::sin(a));
    if (!cluster.empty() && (p - cluster.back()).norm() > o.gap_m + o.gap_per_m * std::min(r, previous_range)) flush();
    cluster.push_back(p);
    previous_range = r;
  }
  flush();
  return out;
}

}  // namespace laser_camera_slam
