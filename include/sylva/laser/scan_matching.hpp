#pragma once
/// @file
/// Stages 1 and 2 of the laser scan segmentation of Amarasinghe 2008, Sec. 4.3.2: two aligned
/// scans, the previous L_P and the current L_C, are split into the sets of eq. 4.1-4.2,
///
///   L_P = A_P + O_P + M_P + N_P,     L_C = A_C + O_C + M_C + N_C,
///
/// A: the same stationary surface seen in both scans; M: a moving object, not hidden by the
/// other scan; O: what the other scan's moving object hid (or will hide); N: the rest.
///
/// Stage 1 (eq. 4.3, closest points). A reading of one scan whose closest point in the other
/// scan lies within dd_c(r) = max(floor, k tan(resolution) r) (eq. 4.4, r the reading's own
/// range) is in A. What is left are B_C = O_C + M_C + N_C and B_P = O_P + M_P + N_P.
///
/// Stage 2 (Algorithm 2). For each B_C^i, the B_P^j closest to the scan line of B_C^i (the ray
/// from the current sensor position through B_C^i) is looked for among those within a
/// perpendicular distance dd_l(t) = max(floor_l, k_l tan(resolution) t) of it, t the distance
/// along the ray. Comparing ranges from the current sensor position:
///
///   r(B_C^i) < r(B_P^j):  B_C^i in M_C and B_P^j in O_P  (something now stands in front
///                         of where the previous scan saw a surface);
///   r(B_C^i) > r(B_P^j):  B_C^i in O_C and B_P^j in M_P  (the previous scan saw something
///                         in front of a surface that is now visible).
///
/// The thesis prints observation 3 of Sec. 4.3.1 as r(O_P) < r(M_C); Algorithm 2 (and the
/// geometry: the O_P surface is behind the moving object) says r(O_P) > r(M_C), which is what
/// is implemented.
///
/// Extension (free space, on by default; `free_space = false` gives the thesis' algorithm):
/// a B_C^i with no B_P^j near its scan line would be N_C. If the previous scan looked in
/// B_C^i's direction and saw farther (its readings on the three beams nearest that direction,
/// seen from the previous pose, are all no-return or beyond B_C^i by more than dd_c), B_C^i
/// stands in space the previous scan saw free, and is put in M_C. Without it a person walking
/// in front of open space (no return behind them; 67 % of the leg-tracker data's readings) is
/// never detected, because no B_P^j exists behind them. It also recovers the edge readings of
/// an object in front of a wall: the wall readings the previous scan had there are usually in
/// A_P, matched by eq. 4.4 to wall readings a beam or two away in the current scan, so they
/// are not in B_P and Algorithm 2 finds nothing on the scan line. With the printed algorithm
/// (free_space = false) the scripted cases lose 1-4 edge readings each and only case 3 is
/// recovered in full. "No return" is trusted only for readings closer than
/// `free_space_max_range_fraction` (0.8) of range_max, for two reasons: real scanners lose
/// weak returns near their maximum range (the leg-tracker background at 4.3-5.5 m of 5.6 m
/// flickers between a reading and "no return"), and from a moving robot a static object that
/// has just come within range was "no return" in the previous scan (with 1.0 the static
/// check of the program finds 4 false objects in 480 scan pairs instead of 0).

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>
#include <vector>

#include "sylva/core/angles.hpp"
#include "sylva/core/error.hpp"

#include "sylva/laser/scan.hpp"

namespace sylva::laser {

/// The set of eq. 4.1-4.2 a reading belongs to; kNone for readings that are not valid.
enum class PointSet : std::uint8_t { kNone, kA, kM, kO, kN };

inline const char* toString(PointSet s) {
  switch (s) {
    case PointSet::kNone: return "none";
    case PointSet::kA: return "A";
    case PointSet::kM: return "M";
    case PointSet::kO: return "O";
    case PointSet::kN: return "N";
  }
  return "?";
}

struct MatchingOptions {
  double match_k = 3.0;             ///< k of eq. 4.4 for closest points
  double match_floor_m = 0.04;      ///< floor of the closest-point threshold (range noise)
  double scan_line_k = 1.0;         ///< Algorithm 2: "close to the scan line", in beam spacings
  double scan_line_floor_m = 0.02;  ///< floor of the scan-line distance
  bool free_space = true;           ///< the free-space extension (see the file comment)
  double free_space_max_range_fraction = 0.8;  ///< ... only for readings within this share of range_max

  void validate() const {
    const bool ok = std::isfinite(match_k) && match_k >= 0.0 && std::isfinite(match_floor_m) &&
                    match_floor_m >= 0.0 && std::isfinite(scan_line_k) && scan_line_k >= 0.0 &&
                    std::isfinite(scan_line_floor_m) && scan_line_floor_m >= 0.0 &&
                    std::isfinite(free_space_max_range_fraction) && free_space_max_range_fraction > 0.0 &&
                    free_space_max_range_fraction <= 1.0 &&
                    (match_k > 0.0 || match_floor_m > 0.0) && (scan_line_k > 0.0 || scan_line_floor_m > 0.0);
    if (!ok) {
      std::ostringstream os;
      os << "matching options: the k factors and floors must be finite and >= 0, with k or floor "
            "> 0 for each threshold; got match k = "
         << match_k << ", floor = " << match_floor_m << " m, scan line k = " << scan_line_k
         << ", floor = " << scan_line_floor_m << " m, and a free-space range fraction in (0, 1], got "
         << free_space_max_range_fraction;
      sylva::fail(sylva::ErrorCode::kInvalidArgument, os.str());
    }
  }
};

/// The beam of `scan` nearest to the direction of world point p (may be outside 0..beams-1).
inline int nearestBeam(const LaserScanGeometry& g, const AlignedScan& scan, const Vec<2>& p) {
  const Vec<2> d = p - scan.origin();
  const double bearing = sylva::wrapAngle(std::atan2(d.y(), d.x()) - scan.sensor_pose[2]);
  double rel = bearing - g.angle_min_rad;
  // Bring the bearing into the scan's angular range where the wrap allows it.
  while (rel < -sylva::kPi) rel += 2.0 * sylva::kPi;
  const double index = std::round(rel / g.angle_increment_rad);
  if (index < -1e6 || index > 1e6) return -1;
  return static_cast<int>(index);
}

/// Stage 1 (eq. 4.3): matched[i] = 1 when valid reading i of `scan` has a valid point of
/// `other` within dd_c(r_i). The search starts at the beam of `other` pointing at the reading
/// and widens, stopping at the first point within the threshold.
inline std::vector<char> closestPointMatches(const LaserScanGeometry& g,
                                             const AlignedScan& scan,
                                             const AlignedScan& other,
                                             const MatchingOptions& o) {
  std::vector<char> matched(static_cast<std::size_t>(scan.size()), 0);
  const int n = other.size();
  for (int i = 0; i < scan.size(); ++i) {
    if (!scan.valid(i)) continue;
    const Vec<2>& p = scan.point(i);
    const double threshold = rangeThreshold(o.match_k, o.match_floor_m, g.angle_increment_rad, scan.range(i));
    const double threshold2 = threshold * threshold;
    const int start = std::clamp(nearestBeam(g, other, p), 0, n - 1);
    for (int offset = 0; offset < n; ++offset) {
      const int lo = start - offset, hi = start + offset;
      if (lo < 0 && hi >= n) break;
      if (lo >= 0 && other.valid(lo) && (other.point(lo) - p).squaredNorm() <= threshold2) {
        matched[static_cast<std::size_t>(i)] = 1;
        break;
      }
      if (offset > 0 && hi < n && other.valid(hi) && (other.point(hi) - p).squaredNorm() <= threshold2) {
        matched[static_cast<std::size_t>(i)] = 1;
        break;
      }
    }
  }
  return matched;
}

/// The sets of eq. 4.1-4.2 for both scans.
struct SetClassification {
  std::vector<PointSet> current;   ///< per beam of L_C
  std::vector<PointSet> previous;  ///< per beam of L_P
  int free_space_moving = 0;       ///< readings put in M_C by the free-space extension
  /// Per beam of L_C: for readings in M_C, how much nearer than the B_P^j on its scan line
  /// (m; +infinity when put there by the free-space extension); 0 otherwise.
  std::vector<double> gap;
};

/// True when the previous scan saw free space beyond world point p (the extension above).
inline bool previousSawFreeSpaceAt(const LaserScanGeometry& g,
                                   const AlignedScan& previous,
                                   const Vec<2>& p,
                                   const MatchingOptions& o) {
  const double rho = (p - previous.origin()).norm();
  if (!(rho <= o.free_space_max_range_fraction * g.max_range_m)) return false;
  const int k = nearestBeam(g, previous, p);
  if (k < 1 || k > previous.size() - 2) return false;  // outside the previous field of view
  const double margin = rangeThreshold(o.match_k, o.match_floor_m, g.angle_increment_rad, rho);
  for (int j = k - 1; j <= k + 1; ++j) {
    const auto kind = previous.reading[static_cast<std::size_t>(j)];
    if (kind == Reading::kInvalid) return false;  // unknown
    if (kind == Reading::kValid && !(previous.range(j) > rho + margin)) return false;
  }
  return true;
}

/// Stages 1 and 2: closest points, then Algorithm 2 on what is left.
inline SetClassification classifyScans(const LaserScanGeometry& g,
                                       const AlignedScan& previous,
                                       const AlignedScan& current,
                                       const MatchingOptions& o) {
  o.validate();
  const std::vector<char> a_current = closestPointMatches(g, current, previous, o);
  const std::vector<char> a_previous = closestPointMatches(g, previous, current, o);

  SetClassification out;
  out.current.assign(static_cast<std::size_t>(current.size()), PointSet::kNone);
  out.previous.assign(static_cast<std::size_t>(previous.size()), PointSet::kNone);
  out.gap.assign(static_cast<std::size_t>(current.size()), 0.0);
  std::vector<int> b_previous;
  for (int j = 0; j < previous.size(); ++j) {
    if (!previous.valid(j)) continue;
    if (a_previous[static_cast<std::size_t>(j)]) {
      out.previous[static_cast<std::size_t>(j)] = PointSet::kA;
    } else {
      b_previous.push_back(j);
    }
  }

  const Vec<2> origin = current.origin();
  for (int i = 0; i < current.size(); ++i) {
    if (!current.valid(i)) continue;
    const auto ci = static_cast<std::size_t>(i);
    if (a_current[ci]) {
      out.current[ci] = PointSet::kA;
      continue;
    }
    // Algorithm 2, line 3: the B_P^j nearest to the scan line of B_C^i.
    const double r_current = current.range(i);
    const Vec<2> ray = (current.point(i) - origin) / r_current;
    int best = -1;
    double best_perpendicular = std::numeric_limits<double>::infinity();
    double best_along = 0.0;
    for (const int j : b_previous) {
      const Vec<2> v = previous.point(j) - origin;
      const double along = v.dot(ray);
      if (!(along > 0.0)) continue;
      const double perpendicular = std::abs(ray.x() * v.y() - ray.y() * v.x());
      const double tolerance = rangeThreshold(o.scan_line_k, o.scan_line_floor_m, g.angle_increment_rad, along);
      if (perpendicular <= tolerance && perpendicular < best_perpendicular) {
        best = j;
        best_perpendicular = perpendicular;
        best_along = along;
      }
    }
    if (best >= 0) {
      const auto cj = static_cast<std::size_t>(best);
      if (r_current < best_along) {  // lines 4-5
        out.current[ci] = PointSet::kM;
        out.gap[ci] = best_along - r_current;
        out.previous[cj] = PointSet::kO;
      } else if (r_current > best_along) {  // lines 7-8
        out.current[ci] = PointSet::kO;
        out.previous[cj] = PointSet::kM;
      } else {
        out.current[ci] = PointSet::kN;
      }
    } else if (o.free_space && previousSawFreeSpaceAt(g, previous, current.point(i), o)) {
      out.current[ci] = PointSet::kM;
      out.gap[ci] = std::numeric_limits<double>::infinity();
      ++out.free_space_moving;
    } else {
      out.current[ci] = PointSet::kN;  // line 11
    }
  }
  for (const int j : b_previous)  // line 14: N_P = B_P - O_P - M_P
    if (out.previous[static_cast<std::size_t>(j)] == PointSet::kNone)
      out.previous[static_cast<std::size_t>(j)] = PointSet::kN;
  return out;
}

}  // namespace sylva::laser
