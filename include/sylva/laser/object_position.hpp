#pragma once
/// @file
/// Position of a detected object from its readings (Amarasinghe 2008, Sec. 4.4.1): the
/// centroid of the convex hull of the segment's points, or the bounding rectangle.
///
/// Convex hull: Andrew's monotone chain, counter-clockwise, collinear points dropped.
/// Centroid: the area centroid of the hull polygon,
///   A = 1/2 sum (x_k y_k+1 - x_k+1 y_k),  c = 1/(6 A) sum (p_k + p_k+1)(x_k y_k+1 - x_k+1 y_k);
/// when the hull has no area (one point, or all points on a line, as for a flat board seen
/// edge-on) the centroid of the hull is the midpoint of its extreme points.
/// Bounding rectangle: axis-aligned in the world frame, as drawn in the thesis' Fig. 4.9.
///
/// Both see only the side of the object that faces the scanner, so both lie nearer to the
/// scanner than the object's true centre: for a leg of radius r the hull centroid is about
/// r/2 to 2r/3 short of the centre. The thesis says so too ("only an approximate position").

#include <algorithm>
#include <cmath>
#include <vector>

#include "sylva/core/error.hpp"
#include "sylva/core/types.hpp"

namespace sylva::laser {


/// Convex hull of `points`, counter-clockwise, without collinear points. Empty input ->
/// kInvalidArgument.
inline std::vector<Vec<2>> convexHull(std::vector<Vec<2>> points) {
  if (points.empty()) sylva::fail(sylva::ErrorCode::kInvalidArgument, "convexHull: no points");
  std::sort(points.begin(), points.end(), [](const Vec<2>& a, const Vec<2>& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  points.erase(std::unique(points.begin(), points.end()), points.end());
  if (points.size() < 3) return points;
  const auto cross = [](const Vec<2>& o, const Vec<2>& a, const Vec<2>& b) {
    return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
  };
  std::vector<Vec<2>> hull(2 * points.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {  // lower chain
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], points[i]) <= 0.0) --k;
    hull[k++] = points[i];
  }
  for (std::size_t i = points.size() - 1, lower = k + 1; i-- > 0;) {  // upper chain
    while (k >= lower && cross(hull[k - 2], hull[k - 1], points[i]) <= 0.0) --k;
    hull[k++] = points[i];
  }
  hull.resize(k - 1);  // the last point repeats the first
  return hull;
}

/// Area centroid of the convex hull of `points` (midpoint of the extremes if it has no area).
inline Vec<2> hullCentroid(const std::vector<Vec<2>>& points) {
  const std::vector<Vec<2>> hull = convexHull(points);
  if (hull.size() >= 3) {
    double twice_area = 0.0;
    Vec<2> sum = Vec<2>::Zero();
    for (std::size_t i = 0; i < hull.size(); ++i) {
      const Vec<2>& p = hull[i];
      const Vec<2>& q = hull[(i + 1) % hull.size()];
      const double w = p.x() * q.y() - q.x() * p.y();
      twice_area += w;
      sum += (p + q) * w;
    }
    // Relative to the squared extent, so a sliver of rounding-error area counts as none.
    const double extent = (hull.front() - hull[hull.size() / 2]).squaredNorm();
    if (std::abs(twice_area) > 1e-12 * std::max(extent, 1e-300)) return sum / (3.0 * twice_area);
  }
  if (hull.size() == 1) return hull.front();
  // No area: the hull is a line segment between its two farthest points.
  Vec<2> a = hull.front(), b = hull.front();
  double best = -1.0;
  for (const Vec<2>& p : hull)
    for (const Vec<2>& q : hull)
      if ((p - q).squaredNorm() > best) {
        best = (p - q).squaredNorm();
        a = p;
        b = q;
      }
  return 0.5 * (a + b);
}

/// Axis-aligned bounding rectangle.
struct Box2 {
  Vec<2> min;
  Vec<2> max;
  Vec<2> center() const { return 0.5 * (min + max); }
};

inline Box2 boundingBox(const std::vector<Vec<2>>& points) {
  if (points.empty()) sylva::fail(sylva::ErrorCode::kInvalidArgument, "boundingBox: no points");
  Box2 box{points.front(), points.front()};
  for (const Vec<2>& p : points) {
    box.min = box.min.cwiseMin(p);
    box.max = box.max.cwiseMax(p);
  }
  return box;
}

}  // namespace sylva::laser
