#pragma once
/// @file
/// The laser moving-object detector of Amarasinghe 2008, chapter 4 (Sec. 4.3-4.4), on two
/// scans of one scanner aligned in the world frame by their sensor poses:
///
///   1. closest points (eq. 4.3, threshold eq. 4.4)          -> A_C, A_P; B_C, B_P
///   2. Algorithm 2 (scan lines and ranges)                  -> M_C, O_C, N_C (and _P)
///   3. continuous segments of M_C, O_C, A_C                  -> M_C^s, O_C^s, A_C^s;
///      segments of M_C^s shorter than `min_seed_points` (2) are dropped here already unless
///      they stand more than `seed_gap_factor` (3) dd_c in front of what the previous scan saw
///      on their scan line: a single reading pushed out of its match by range noise would
///      otherwise Join a whole wall of A_C^s in step 4, while the one-reading leading edge of
///      an object sliding sideways (case 5) stands far in front of the old background (not
///      in the thesis, which filters by size only at the end)
///   4. Algorithm 3: if M_C^s is not empty,
///        M_C^s <- Join(M_C^s, A_C^s), then M_C^s <- Join(M_C^s, O_C^s)   (cases 2 and 5)
///   5. Algorithm 4: if M_C^s is empty and O_C^s is not, M_C^s <- O_C^s   (case 3), only
///      when O_C^s holds at most `replace_max_o_segments` segments of the minimum size (the
///      thesis: "only when one moving object is present ... detected from the number of
///      segments in O_C^s"); then segments of M_C^s whose ends touch are merged (they are one
///      continuous segment once the joins filled the gap between them)
///   6. segments of M_C^s with fewer than `min_segment_points` readings are dropped
///      (Sec. 4.4.1, false positives)
///   7. each remaining segment is an object: the centroid of its convex hull and its bounding
///      rectangle (Sec. 4.4.1), its range from the scanner, and the minimum relative speed
///      it must have had to be detected, V_min = dd_c(r) / dt (eq. 4.5).
///
/// See scan_matching.hpp and segments.hpp for the details and where this departs from the
/// printed thesis (observation 3's inequality, the free-space extension, thresholds with a
/// floor). Everything is deterministic.
///
/// Bad input: scans whose sizes differ from the geometry's beam count -> kInvalidArgument;
/// a non-finite pose -> kNonFinite; dt <= 0 or not finite, nonsense options ->
/// kInvalidArgument. NaN, infinite and out-of-range readings are not errors (scan.hpp).

#include <algorithm>
#include <cmath>
#include <iterator>
#include <sstream>
#include <vector>

#include "sylva/core/error.hpp"
#include "sylva/core/types.hpp"

#include "sylva/laser/object_position.hpp"
#include "sylva/laser/scan.hpp"
#include "sylva/laser/scan_matching.hpp"
#include "sylva/laser/segments.hpp"

namespace sylva::laser {

struct DetectorOptions {
  MatchingOptions matching;
  SegmentOptions segments;
  int min_segment_points = 3;      ///< Sec. 4.4.1: shorter segments of M_C^s are ignored
  int min_seed_points = 2;         ///< M_C^s segments shorter than this are noise, dropped before Algorithm 3 ...
  double seed_gap_factor = 3.0;    ///< ... unless they stand this many dd_c in front of the previous scan
  int replace_max_o_segments = 1;  ///< Algorithm 4 only with at most this many O_C^s segments (0: never)
  bool join_a = true;              ///< Algorithm 3, line 2
  bool join_o = true;              ///< Algorithm 3, line 3

  void validate() const {
    matching.validate();
    segments.validate();
    if (min_segment_points < 1 || min_segment_points > 10000 || min_seed_points < 1 ||
        min_seed_points > 10000 || replace_max_o_segments < 0) {
      std::ostringstream os;
      os << "detector options: need 1 <= min_segment_points, min_seed_points <= 10000 and "
            "replace_max_o_segments >= 0, got "
         << min_segment_points << ", " << min_seed_points << " and " << replace_max_o_segments;
      sylva::fail(sylva::ErrorCode::kInvalidArgument, os.str());
    }
  }
};

/// How a detected object was found.
enum class Recovery { kMoving, kReplacedFromOccluded };

struct DetectedObject {
  std::vector<int> beams;       ///< readings of the current scan
  std::vector<Vec<2>> points;   ///< their world points
  Vec<2> hull_centroid;         ///< Sec. 4.4.1: position of the object
  Box2 box;                     ///< Sec. 4.4.1: bounding rectangle
  double range_m = 0.0;         ///< scanner to hull centroid
  double min_speed_mps = 0.0;   ///< eq. 4.5 at this range
  Recovery recovery = Recovery::kMoving;
  int joined_from_a = 0;        ///< segments of A_C^s joined in (Algorithm 3)
  int joined_from_o = 0;        ///< segments of O_C^s joined in
};

struct Detection {
  SetClassification sets;                 ///< eq. 4.1-4.2 for both scans
  std::vector<Segment> m_segments;        ///< M_C^s before Algorithms 3-4 (seeds: at least min_seed_points)
  std::vector<Segment> a_segments;        ///< A_C^s (after Join removed what went to M)
  std::vector<Segment> o_segments;        ///< O_C^s (after Join removed what went to M)
  bool replaced_from_o = false;           ///< Algorithm 4 was applied
  std::vector<DetectedObject> objects;    ///< final M_C^s, one object per segment
  std::vector<char> moving;               ///< per current beam: part of a reported object
  int no_return = 0;                      ///< current readings without return
  int invalid = 0;                        ///< current readings that are NaN or below range_min
};

/// eq. 4.5: the smallest relative speed that moves an object at range r by more than the
/// closest-point threshold dd_c(r) between scans dt seconds apart.
inline double minDetectableSpeed(const LaserScanGeometry& g, const MatchingOptions& o, double range_m, double dt_s) {
  return rangeThreshold(o.match_k, o.match_floor_m, g.angle_increment_rad, range_m) / dt_s;
}

class MovingObjectDetector {
 public:
  MovingObjectDetector(const LaserScanGeometry& geometry, const DetectorOptions& options = {})
      : geometry_(geometry), options_(options) {
    validateScanGeometry(geometry_);
    options_.validate();
  }

  const LaserScanGeometry& geometry() const { return geometry_; }
  const DetectorOptions& options() const { return options_; }

  /// Moving objects in `current` (ranges of the scan at sensor pose `current_pose`) against
  /// `previous`, taken dt_s seconds earlier.
  Detection detect(const std::vector<double>& previous,
                   const Vec<3>& previous_pose,
                   const std::vector<double>& current,
                   const Vec<3>& current_pose,
                   double dt_s) const {
    if (previous.size() != current.size()) {
      std::ostringstream os;
      os << "detect: the previous scan has " << previous.size() << " ranges and the current one "
         << current.size() << "; both must have the scanner's " << geometry_.beams;
      sylva::fail(sylva::ErrorCode::kInvalidArgument, os.str());
    }
    if (!std::isfinite(dt_s) || !(dt_s > 0.0)) {
      std::ostringstream os;
      os << "detect: the time between the scans must be finite and > 0, got " << dt_s << " s";
      sylva::fail(sylva::ErrorCode::kInvalidArgument, os.str());
    }
    return detect(alignScan(geometry_, previous, previous_pose), alignScan(geometry_, current, current_pose), dt_s);
  }

  Detection detect(const AlignedScan& previous, const AlignedScan& current, double dt_s) const {
    const LaserScanGeometry& g = geometry_;
    const DetectorOptions& o = options_;
    Detection d;
    d.no_return = current.no_return;
    d.invalid = current.invalid;
    d.sets = classifyScans(g, previous, current, o.matching);  // stages 1-2
    // Stage 3.
    std::vector<Segment> m = segmentSet(g, current, d.sets.current, PointSet::kM, o.segments);
    m.erase(std::remove_if(m.begin(), m.end(),
                           [&](const Segment& s) {
                             if (s.size() >= o.min_seed_points) return false;
                             // A short seed stays when it stands well in front of what the
                             // previous scan saw: more than seed_gap_factor * dd_c.
                             double gap = 0.0;
                             for (const int b : s.beams) gap = std::max(gap, d.sets.gap[static_cast<std::size_t>(b)]);
                             const double threshold = rangeThreshold(o.matching.match_k, o.matching.match_floor_m,
                                                                     g.angle_increment_rad, current.range(s.first()));
                             return !(gap > o.seed_gap_factor * threshold);
                           }),
            m.end());
    d.a_segments = segmentSet(g, current, d.sets.current, PointSet::kA, o.segments);
    d.o_segments = segmentSet(g, current, d.sets.current, PointSet::kO, o.segments);
    d.m_segments = m;

    std::vector<int> from_a(m.size(), 0), from_o(m.size(), 0);
    if (!m.empty()) {  // Algorithm 3
      for (std::size_t s = 0; s < m.size(); ++s) {
        // Join segment by segment to count where each object's readings came from; the
        // union is the same as Join on the whole set.
        std::vector<Segment> one{m[s]};
        if (o.join_a) from_a[s] = join(g, current, o.segments, one, d.a_segments);
        m[s] = one.front();
      }
      for (std::size_t s = 0; s < m.size(); ++s) {
        std::vector<Segment> one{m[s]};
        if (o.join_o) from_o[s] = join(g, current, o.segments, one, d.o_segments);
        m[s] = one.front();
      }
    } else if (!d.o_segments.empty()) {  // Algorithm 4
      int sizable = 0;
      for (const Segment& s : d.o_segments) sizable += s.size() >= o.min_segment_points ? 1 : 0;
      if (sizable >= 1 && sizable <= o.replace_max_o_segments) {
        m = d.o_segments;
        from_a.assign(m.size(), 0);
        from_o.assign(m.size(), 0);
        d.replaced_from_o = true;
      }
    }

    // After the joins two segments of M_C^s can touch (an object whose middle matched A_C
    // was cut in two, and the A_C piece joined one half): they are one continuous segment.
    for (std::size_t s = 0; s < m.size(); ++s) {
      for (std::size_t t = s + 1; t < m.size();) {
        if (endsClose(g, current, o.segments, m[s], m[t])) {
          std::vector<int> beams;
          std::merge(m[s].beams.begin(), m[s].beams.end(), m[t].beams.begin(), m[t].beams.end(),
                     std::back_inserter(beams));
          m[s].beams = std::move(beams);
          from_a[s] += from_a[t];
          from_o[s] += from_o[t];
          m.erase(m.begin() + static_cast<std::ptrdiff_t>(t));
          from_a.erase(from_a.begin() + static_cast<std::ptrdiff_t>(t));
          from_o.erase(from_o.begin() + static_cast<std::ptrdiff_t>(t));
          t = s + 1;
        } else {
          ++t;
        }
      }
    }

    d.moving.assign(static_cast<std::size_t>(current.size()), 0);
    for (std::size_t s = 0; s < m.size(); ++s) {
      if (m[s].size() < o.min_segment_points) continue;  // step 6
      DetectedObject object;
      object.beams = m[s].beams;
      for (const int b : object.beams) {
        object.points.push_back(current.point(b));
        d.moving[static_cast<std::size_t>(b)] = 1;
      }
      object.hull_centroid = hullCentroid(object.points);
      object.box = boundingBox(object.points);
      object.range_m = (object.hull_centroid - current.origin()).norm();
      object.min_speed_mps = minDetectableSpeed(g, o.matching, object.range_m, dt_s);
      object.recovery = d.replaced_from_o ? Recovery::kReplacedFromOccluded : Recovery::kMoving;
      object.joined_from_a = d.replaced_from_o ? 0 : from_a[s];
      object.joined_from_o = d.replaced_from_o ? 0 : from_o[s];
      d.objects.push_back(std::move(object));
    }
    return d;
  }

 private:
  LaserScanGeometry geometry_;
  DetectorOptions options_;
};

}  // namespace sylva::laser
