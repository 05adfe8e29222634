#pragma once
/// @file
/// `sim::LaserScene2D`: what a planar laser scanner can hit. A scene is a snapshot of the
/// world at one instant, made of two kinds of shapes in the world x-y plane:
///
///   Circle2D   a disc (centre, radius): a leg, a tree trunk, a pole, a pillar;
///   Segment2D  a line segment (two end points): a wall, one side of a box.
///
/// Every shape carries the `Id` of the object it belongs to (a wall, a box made of four
/// segments, one leg of a person), so a simulated scan can report which object each beam
/// hit. Ids are the caller's; several shapes may share one.
///
/// `castRay(origin, direction, max_range)` returns the first shape a ray meets:
///
///   circle:  |o + t d - c|^2 = r^2  ->  t = -b - sqrt(b^2 - q),  b = (o - c).d,
///            q = |o - c|^2 - r^2  (d a unit vector). A ray starting inside a disc
///            (q <= 0) is blocked at t = 0: a scanner inside an object sees nothing.
///   segment: o + t d = a + s (b - a) with t >= 0 and s in [0, 1] (2x2 solve by cross
///            products). A ray parallel to a segment does not hit it (it would only graze
///            an edge of zero thickness). The ends count as part of the segment (with a
///            margin of 1e-9 of its length, so no ray slips through a polyline's vertex).
///
/// and t = +infinity with `kNoObject` when nothing lies within `max_range`. Ties (two
/// shapes at exactly the same distance) go to the shape added first, circles before
/// segments, so the result is deterministic.
///
/// Cost: one ray is O(circles + segments); a scene of a few hundred shapes is cast 361
/// times per scan without allocation. `clear()` keeps the storage, so a scene rebuilt
/// every scan (moving objects, see dynamic_scene_2d.hpp) does not allocate either.
///
/// Errors (kInvalidArgument / kNonFinite): a radius <= 0, a segment whose end points
/// coincide, a polygon with fewer than two vertices, a non-finite coordinate, a ray
/// direction that is not a unit vector.

#include <cmath>
#include <limits>
#include <sstream>
#include <vector>

#include "sylva/core/error.hpp"
#include "sylva/core/types.hpp"

namespace sylva::sim {

/// The object id of "nothing was hit".
inline constexpr Id kNoObject = -1;

/// A disc in the world plane.
struct Circle2D {
  Vec<2> center;
  double radius_m;
  Id object_id;
};

/// A line segment in the world plane (a wall, one side of a box).
struct Segment2D {
  Vec<2> a;
  Vec<2> b;
  Id object_id;
};

/// Where a ray ended: distance along the ray (m, +infinity if nothing) and what it hit.
struct RayHit {
  double distance_m;
  Id object_id;
};

/// Distance along the ray o + t d (d unit) to the circle, +infinity when it misses;
/// 0 when o lies inside the circle.
inline double rayCircleDistance(const Vec<2>& origin,
                                const Vec<2>& direction,
                                const Vec<2>& center,
                                double radius) {
  const Vec<2> m = origin - center;
  const double b = m.dot(direction);
  const double q = m.squaredNorm() - radius * radius;
  if (q <= 0.0) return 0.0;                                              // inside
  if (b > 0.0) return std::numeric_limits<double>::infinity();            // pointing away
  const double discriminant = b * b - q;
  if (discriminant < 0.0) return std::numeric_limits<double>::infinity();  // misses
  return -b - std::sqrt(discriminant);
}

/// Distance along the ray o + t d (d unit) to the segment [a, b], +infinity when it misses
/// or runs parallel to it.
inline double raySegmentDistance(const Vec<2>& origin,
                                 const Vec<2>& direction,
                                 const Vec<2>& a,
                                 const Vec<2>& b) {
  const Vec<2> e = b - a;
  const double denominator = direction.x() * e.y() - direction.y() * e.x();  // d x e
  if (denominator == 0.0) return std::numeric_limits<double>::infinity();
  const Vec<2> w = a - origin;
  const double t = (w.x() * e.y() - w.y() * e.x()) / denominator;                  // w x e / d x e
  const double s = (w.x() * direction.y() - w.y() * direction.x()) / denominator;  // w x d / d x e
  // The end points are included with a margin of 1e-9 of the length: without it a ray
  // through the shared vertex of two sides of a polyline can slip between them by rounding.
  constexpr double kEndMargin = 1e-9;
  if (t < 0.0 || s < -kEndMargin || s > 1.0 + kEndMargin) return std::numeric_limits<double>::infinity();
  return t;
}

class LaserScene2D {
 public:
  /// Adds a disc. Throws unless the centre is finite and radius_m > 0.
  void addCircle(const Vec<2>& center, double radius_m, Id object_id) {
    if (!center.allFinite() || !std::isfinite(radius_m))
      fail(ErrorCode::kNonFinite, "LaserScene2D::addCircle: centre or radius is not finite");
    if (!(radius_m > 0.0)) {
      std::ostringstream os;
      os << "LaserScene2D::addCircle: the radius must be > 0, got " << radius_m << " m";
      fail(ErrorCode::kInvalidArgument, os.str());
    }
    circles_.push_back(Circle2D{center, radius_m, object_id});
  }

  /// Adds a segment. Throws unless both ends are finite and distinct.
  void addSegment(const Vec<2>& a, const Vec<2>& b, Id object_id) {
    if (!a.allFinite() || !b.allFinite())
      fail(ErrorCode::kNonFinite, "LaserScene2D::addSegment: an end point is not finite");
    if (a == b) {
      std::ostringstream os;
      os << "LaserScene2D::addSegment: the end points coincide at (" << a.x() << ", " << a.y()
         << "); a segment needs length > 0";
      fail(ErrorCode::kInvalidArgument, os.str());
    }
    segments_.push_back(Segment2D{a, b, object_id});
  }

  /// Adds the sides of a polyline through `vertices` (closed: also last -> first), all
  /// with the same object id. Checks every vertex before adding anything.
  void addPolyline(const std::vector<Vec<2>>& vertices, bool closed, Id object_id) {
    if (vertices.size() < 2)
      fail(ErrorCode::kInvalidArgument, "LaserScene2D::addPolyline: need at least two vertices");
    for (std::size_t i = 0; i < vertices.size(); ++i) {
      if (!vertices[i].allFinite())
        fail(ErrorCode::kNonFinite, "LaserScene2D::addPolyline: a vertex is not finite");
      const std::size_t next = (i + 1) % vertices.size();
      if ((next != 0 || closed) && vertices[i] == vertices[next])
        fail(ErrorCode::kInvalidArgument,
             "LaserScene2D::addPolyline: two consecutive vertices coincide");
    }
    const std::size_t sides = closed ? vertices.size() : vertices.size() - 1;
    for (std::size_t i = 0; i < sides; ++i)
      segments_.push_back(Segment2D{vertices[i], vertices[(i + 1) % vertices.size()], object_id});
  }

  /// Appends every shape of `other` (e.g. the static part of a world to a snapshot).
  void append(const LaserScene2D& other) {
    circles_.insert(circles_.end(), other.circles_.begin(), other.circles_.end());
    segments_.insert(segments_.end(), other.segments_.begin(), other.segments_.end());
  }

  /// Removes every shape, keeping the storage.
  void clear() {
    circles_.clear();
    segments_.clear();
  }

  bool empty() const { return circles_.empty() && segments_.empty(); }
  const std::vector<Circle2D>& circles() const { return circles_; }
  const std::vector<Segment2D>& segments() const { return segments_; }

  /// The first shape hit by the ray from `origin` along the unit vector `direction`, within
  /// `max_range_m`; {+infinity, kNoObject} when nothing is that close.
  RayHit castRay(const Vec<2>& origin, const Vec<2>& direction, double max_range_m) const {
    if (!origin.allFinite() || !direction.allFinite())
      fail(ErrorCode::kNonFinite, "LaserScene2D::castRay: origin or direction is not finite");
    if (std::abs(direction.squaredNorm() - 1.0) > 1e-9)
      fail(ErrorCode::kInvalidArgument, "LaserScene2D::castRay: the direction must be a unit vector");
    RayHit best{std::numeric_limits<double>::infinity(), kNoObject};
    for (const Circle2D& c : circles_) {
      const double t = rayCircleDistance(origin, direction, c.center, c.radius_m);
      if (t < best.distance_m) best = RayHit{t, c.object_id};
    }
    for (const Segment2D& s : segments_) {
      const double t = raySegmentDistance(origin, direction, s.a, s.b);
      if (t < best.distance_m) best = RayHit{t, s.object_id};
    }
    if (!(best.distance_m <= max_range_m))
      return RayHit{std::numeric_limits<double>::infinity(), kNoObject};
    return best;
  }

 private:
  std::vector<Circle2D> circles_;
  std::vector<Segment2D> segments_;
};

}  // namespace sylva::sim
