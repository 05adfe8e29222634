#pragma once
/// @file
/// Stage 3 of the scan segmentation (Amarasinghe 2008, Sec. 4.3.2) and the Join operation of
/// Sec. 4.3.4.
///
/// Continuous segments. The readings of one set (say M_C) are visited in beam order; two
/// consecutive members i < i' are in the same segment when
///   - the beams between them hold no valid reading of another set (only no-return or
///     invalid readings, at most `max_beam_gap` of them: a dropout does not cut an object),
///   - and their points are closer than dd_s(r) = max(floor_s, k_s tan(resolution) r), the
///     eq. 4.4 form with its own k (Sec. 4.3.3), r the smaller of the two ranges.
///
/// Join(A, B). When an end of a segment a of A is within dd_s of an end of a segment b of B
/// (ends: the points of a segment's first and last beam), b is merged into a and removed
/// from B. Passes over all pairs repeat until B no longer shrinks.
///
/// Every segment keeps its beams sorted, so its ends stay its extreme beams after a join.

#include <algorithm>
#include <cmath>
#include <iterator>
#include <sstream>
#include <vector>

#include "sylva/core/error.hpp"

#include "sylva/laser/scan.hpp"
#include "sylva/laser/scan_matching.hpp"

namespace sylva::laser {

/// A continuous segment: beam indices of one scan, in increasing order.
struct Segment {
  std::vector<int> beams;
  int first() const { return beams.front(); }
  int last() const { return beams.back(); }
  int size() const { return static_cast<int>(beams.size()); }
};

struct SegmentOptions {
  double k = 5.0;          ///< k of the segmentation and Join threshold (eq. 4.4 form)
  double floor_m = 0.10;   ///< Sec. 4.3.5: readings closer than 10 cm belong to one object
  int max_beam_gap = 2;    ///< no-return/invalid beams a segment may bridge

  void validate() const {
    if (!std::isfinite(k) || k < 0.0 || !std::isfinite(floor_m) || floor_m < 0.0 ||
        (k == 0.0 && floor_m == 0.0) || max_beam_gap < 0 || max_beam_gap > 1000) {
      std::ostringstream os;
      os << "segment options: need finite k >= 0 and floor >= 0 (not both 0) and 0 <= "
            "max_beam_gap <= 1000, got k = "
         << k << ", floor = " << floor_m << " m, max_beam_gap = " << max_beam_gap;
      sylva::fail(sylva::ErrorCode::kInvalidArgument, os.str());
    }
  }
};

inline double segmentThreshold(const LaserScanGeometry& g, const SegmentOptions& o, double range_m) {
  return rangeThreshold(o.k, o.floor_m, g.angle_increment_rad, range_m);
}

/// True when readings i and j (valid) are close enough to belong to one object.
inline bool closeReadings(const LaserScanGeometry& g, const AlignedScan& scan, const SegmentOptions& o, int i, int j) {
  const double threshold = segmentThreshold(g, o, std::min(scan.range(i), scan.range(j)));
  return (scan.point(i) - scan.point(j)).norm() <= threshold;
}

/// The continuous segments of the readings of `scan` whose set is `which`.
inline std::vector<Segment> segmentSet(const LaserScanGeometry& g,
                                       const AlignedScan& scan,
                                       const std::vector<PointSet>& sets,
                                       PointSet which,
                                       const SegmentOptions& o) {
  std::vector<Segment> out;
  int last_member = -1;
  for (int i = 0; i < scan.size(); ++i) {
    if (sets[static_cast<std::size_t>(i)] != which) continue;
    bool extend = false;
    if (last_member >= 0 && i - last_member - 1 <= o.max_beam_gap) {
      extend = true;
      for (int b = last_member + 1; b < i && extend; ++b) extend = !scan.valid(b);
      extend = extend && closeReadings(g, scan, o, last_member, i);
    }
    if (extend) {
      out.back().beams.push_back(i);
    } else {
      out.push_back(Segment{{i}});
    }
    last_member = i;
  }
  return out;
}

/// True when an end of `a` is within the segmentation threshold of an end of `b`.
inline bool endsClose(const LaserScanGeometry& g, const AlignedScan& scan, const SegmentOptions& o, const Segment& a, const Segment& b) {
  for (const int ea : {a.first(), a.last()})
    for (const int eb : {b.first(), b.last()})
      if (closeReadings(g, scan, o, ea, eb)) return true;
  return false;
}

/// Join(A, B) of Sec. 4.3.4 (see the file comment). Returns the number of segments of B
/// merged into A.
inline int join(const LaserScanGeometry& g,
                const AlignedScan& scan,
                const SegmentOptions& o,
                std::vector<Segment>& a,
                std::vector<Segment>& b) {
  int merged = 0;
  for (;;) {
    const std::size_t before = b.size();
    for (Segment& target : a) {
      for (std::size_t j = 0; j < b.size();) {
        if (endsClose(g, scan, o, target, b[j])) {
          std::vector<int> beams;
          beams.reserve(target.beams.size() + b[j].beams.size());
          std::merge(target.beams.begin(), target.beams.end(), b[j].beams.begin(), b[j].beams.end(),
                     std::back_inserter(beams));
          target.beams = std::move(beams);
          b.erase(b.begin() + static_cast<std::ptrdiff_t>(j));
          ++merged;
          j = 0;  // the target's ends may have moved: look at the rest of B again
        } else {
          ++j;
        }
      }
    }
    if (b.size() == before) break;
  }
  return merged;
}

}  // namespace sylva::laser
