#pragma once
/// @file
/// `sim::LoopPath2D`: a closed, counter-clockwise rounded rectangle in the plane, described by
/// arc length s. Its bounding box is `length_m` (along x) by `width_m` (along y), its four
/// corners are quarter circles of radius `corner_radius_m`; with length = width =
/// 2 * radius it is a circle. The path starts at the origin, in the middle of the bottom
/// side, heading along +x, so the box spans x in [-length/2, length/2], y in [0, width].
///
///   perimeter = 2 (length - 2 r) + 2 (width - 2 r) + 2 pi r
///
/// The path is a list of segments of constant curvature k (0 on the straight sides, 1/r on
/// the corners). On a segment starting at p0 with heading h0, at arc length t:
///
///   heading = h0 + k t,   position = p0 + t [cos h0, sin h0]                      (k = 0)
///                         position = c + (1/k) [sin(heading), -cos(heading)],
///                                    c = p0 + (1/k) [-sin h0, cos h0]             (k != 0)
///
/// `heading(s)` is continuous (not wrapped): it grows by 2 pi per lap, which is what a
/// trajectory needs to turn it into angular velocities.

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <vector>

#include "sylva/core/angles.hpp"
#include "sylva/core/error.hpp"
#include "sylva/core/types.hpp"

namespace sylva::sim {

class LoopPath2D {
 public:
  /// A rounded rectangle with the given bounding box and corner radius (all in metres).
  /// Requires 0 < corner_radius_m <= min(length_m, width_m) / 2, all finite.
  LoopPath2D(double length_m, double width_m, double corner_radius_m)
      : length_(length_m), width_(width_m), radius_(corner_radius_m) {
    if (!std::isfinite(length_m) || !std::isfinite(width_m) || !std::isfinite(corner_radius_m) ||
        !(corner_radius_m > 0.0) || !(2.0 * corner_radius_m <= length_m) ||
        !(2.0 * corner_radius_m <= width_m)) {
      std::ostringstream os;
      os << "LoopPath2D: need finite 0 < corner_radius <= min(length, width) / 2, got length = "
         << length_m << " m, width = " << width_m << " m, corner_radius = " << corner_radius_m
         << " m";
      fail(ErrorCode::kInvalidArgument, os.str());
    }
    build();
  }

  /// The rounded rectangle of the given perimeter whose bounding box has length = aspect *
  /// width, with corners of radius `corner_radius_m`. Throws kInvalidArgument when the
  /// corners do not fit (the perimeter is too small for the radius).
  static LoopPath2D withPerimeter(double perimeter_m, double aspect, double corner_radius_m) {
    if (!std::isfinite(perimeter_m) || !(perimeter_m > 0.0) || !std::isfinite(aspect) ||
        !(aspect >= 1.0) || !std::isfinite(corner_radius_m) || !(corner_radius_m > 0.0)) {
      std::ostringstream os;
      os << "LoopPath2D::withPerimeter: need finite perimeter > 0, aspect >= 1 and "
            "corner_radius > 0, got perimeter = "
         << perimeter_m << " m, aspect = " << aspect << ", corner_radius = " << corner_radius_m
         << " m";
      fail(ErrorCode::kInvalidArgument, os.str());
    }
    // perimeter = 2 (1 + aspect) width - (8 - 2 pi) r
    const double width =
        (perimeter_m + (8.0 - 2.0 * kPi) * corner_radius_m) / (2.0 * (1.0 + aspect));
    if (!(2.0 * corner_radius_m <= width * (1.0 + 1e-12))) {
      std::ostringstream os;
      os << "LoopPath2D::withPerimeter: a perimeter of " << perimeter_m
         << " m is too short for corners of radius " << corner_radius_m << " m (need at least "
         << 2.0 * kPi * corner_radius_m + 4.0 * (aspect - 1.0) * corner_radius_m << " m)";
      fail(ErrorCode::kInvalidArgument, os.str());
    }
    return LoopPath2D(aspect * width, width, std::min(corner_radius_m, 0.5 * width));
  }

  double length() const { return length_; }
  double width() const { return width_; }
  double cornerRadius() const { return radius_; }
  double perimeter() const { return perimeter_; }

  /// Position at arc length s (any real s; the path repeats every perimeter).
  Vec<2> position(double s) const {
    const Located at = locate(s);
    return positionOn(*at.segment, at.t);
  }

  /// Continuous heading at arc length s: 0 at s = 0, 2 pi after one lap, 2 pi k after k laps.
  double heading(double s) const {
    const Located at = locate(s);
    return 2.0 * kPi * at.laps + at.segment->h0 + at.segment->curvature * at.t;
  }

  /// Unit normal pointing to the left of the direction of travel (into the loop).
  Vec<2> leftNormal(double s) const {
    const double h = heading(s);
    return Vec<2>(-std::sin(h), std::cos(h));
  }

  /// Euclidean distance from `p` to the closest point of the path.
  double distanceTo(const Vec<2>& p) const {
    double best = std::numeric_limits<double>::infinity();
    for (const Segment& seg : segments_) {
      if (seg.curvature == 0.0) {
        const Vec<2> dir(std::cos(seg.h0), std::sin(seg.h0));
        const double t = std::clamp((p - seg.p0).dot(dir), 0.0, seg.length);
        best = std::min(best, (p - (seg.p0 + t * dir)).norm());
      } else {
        // Closest point on the full circle, if it lies on the arc; else an end point.
        const Vec<2> c = center(seg);
        const Vec<2> d = p - c;
        const double r = 1.0 / seg.curvature;
        // Heading of the tangent at the circle point in direction d: angle(d) + pi/2.
        const double angle = std::atan2(d[1], d[0]) + 0.5 * kPi;
        const double t = wrapAngle(angle - seg.h0) / seg.curvature;
        const double t_arc = t < 0.0 ? t + 2.0 * kPi * r : t;
        if (t_arc <= seg.length) {
          best = std::min(best, std::abs(d.norm() - r));
        } else {
          best = std::min(best, (p - positionOn(seg, 0.0)).norm());
          best = std::min(best, (p - positionOn(seg, seg.length)).norm());
        }
      }
    }
    return best;
  }

 private:
  struct Segment {
    Vec<2> p0;
    double h0;
    double length;
    double curvature;  ///< 1/m, 0 for a straight piece (only +1/r here: counter-clockwise)
    double s0;         ///< arc length at the segment start
  };
  struct Located {
    const Segment* segment;
    double t;  ///< arc length within the segment
    double laps;
  };

  static Vec<2> center(const Segment& seg) {
    return seg.p0 + (1.0 / seg.curvature) * Vec<2>(-std::sin(seg.h0), std::cos(seg.h0));
  }

  static Vec<2> positionOn(const Segment& seg, double t) {
    if (seg.curvature == 0.0) return seg.p0 + t * Vec<2>(std::cos(seg.h0), std::sin(seg.h0));
    const double h = seg.h0 + seg.curvature * t;
    return center(seg) + (1.0 / seg.curvature) * Vec<2>(std::sin(h), -std::cos(h));
  }

  void add(double length, double curvature) {
    if (!(length > 0.0)) return;  // a straight side of zero length (circle) is left out
    Segment seg{Vec<2>::Zero(), 0.0, length, curvature, perimeter_};
    if (!segments_.empty()) {
      const Segment& prev = segments_.back();
      seg.p0 = positionOn(prev, prev.length);
      seg.h0 = prev.h0 + prev.curvature * prev.length;
    }
    segments_.push_back(seg);
    perimeter_ += length;
  }

  void build() {
    const double a = length_ - 2.0 * radius_;  // straight part along x
    const double b = width_ - 2.0 * radius_;   // straight part along y
    const double quarter = 0.5 * kPi * radius_;
    const double k = 1.0 / radius_;
    add(0.5 * a, 0.0);
    add(quarter, k);
    add(b, 0.0);
    add(quarter, k);
    add(a, 0.0);
    add(quarter, k);
    add(b, 0.0);
    add(quarter, k);
    add(0.5 * a, 0.0);
  }

  Located locate(double s) const {
    if (!std::isfinite(s)) fail(ErrorCode::kNonFinite, "LoopPath2D: arc length is not finite");
    const double laps = std::floor(s / perimeter_);
    double r = s - laps * perimeter_;
    r = std::clamp(r, 0.0, perimeter_);
    // Few segments: a linear scan is the fastest search.
    std::size_t i = 0;
    while (i + 1 < segments_.size() && r >= segments_[i + 1].s0) ++i;
    const Segment& seg = segments_[i];
    return Located{&seg, std::min(r - seg.s0, seg.length), laps};
  }

  double length_;
  double width_;
  double radius_;
  double perimeter_ = 0.0;
  std::vector<Segment> segments_;
};

}  // namespace sylva::sim
