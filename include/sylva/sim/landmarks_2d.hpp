#pragma once
/// @file
/// A field of point landmarks for 2D simulations: `TrueLandmark2D` (id and position) and
/// `landmarksAlongPath`, which scatters landmarks in a band on both sides of a `LoopPath2D`,
/// the way posts, trees or pillars line a corridor or a road.
///
/// Sampling, for each landmark in turn: s ~ U[0, perimeter), side = +-1 with probability
/// 1/2, offset d ~ U[band_min, band_max), candidate p = path(s) + side d n(s) with n the left
/// normal. The candidate is kept when it is at least band_min from every part of the path
/// (so the robot never drives into a landmark where the loop folds back) and at least
/// `min_separation_m` from every landmark kept so far; otherwise it is drawn again. Ids are
/// 0 .. count - 1 in the order of placement. The result depends only on the options, the
/// path and the state of `rng`.
///
/// Common mistakes: a dense field with a large separation may not fit; after
/// `max_attempts_per_landmark * count` draws the function gives up with kInvalidArgument
/// instead of looping forever.

#include <cmath>
#include <sstream>
#include <vector>

#include "sylva/core/error.hpp"
#include "sylva/core/types.hpp"
#include "sylva/sim/loop_path_2d.hpp"
#include "sylva/sim/random.hpp"

namespace sylva::sim {

/// A landmark of the simulated world with its true position.
struct TrueLandmark2D {
  Id id;
  Vec<2> position;
};

struct LandmarkField2DOptions {
  int count = 120;                       ///< number of landmarks, > 0
  double band_min_m = 1.0;               ///< closest distance to the path, >= 0
  double band_max_m = 7.0;               ///< farthest lateral offset from the path, > band_min
  double min_separation_m = 0.0;         ///< smallest distance between two landmarks, >= 0
  int max_attempts_per_landmark = 1000;  ///< rejection-sampling budget, > 0
};

/// `options.count` landmarks in a band on both sides of `path` (see the file comment).
inline std::vector<TrueLandmark2D> landmarksAlongPath(const LoopPath2D& path,
                                                      const LandmarkField2DOptions& options,
                                                      Rng& rng) {
  const auto& o = options;
  if (o.count <= 0 || o.max_attempts_per_landmark <= 0) {
    std::ostringstream os;
    os << "landmarksAlongPath: count and max_attempts_per_landmark must be > 0, got count = "
       << o.count << ", max_attempts_per_landmark = " << o.max_attempts_per_landmark;
    fail(ErrorCode::kInvalidArgument, os.str());
  }
  if (!std::isfinite(o.band_min_m) || !std::isfinite(o.band_max_m) || !(o.band_min_m >= 0.0) ||
      !(o.band_max_m > o.band_min_m) || !std::isfinite(o.min_separation_m) ||
      !(o.min_separation_m >= 0.0)) {
    std::ostringstream os;
    os << "landmarksAlongPath: need finite 0 <= band_min < band_max and min_separation >= 0, "
          "got band_min = "
       << o.band_min_m << " m, band_max = " << o.band_max_m
       << " m, min_separation = " << o.min_separation_m << " m";
    fail(ErrorCode::kInvalidArgument, os.str());
  }
  std::vector<TrueLandmark2D> out;
  out.reserve(static_cast<std::size_t>(o.count));
  const long long budget = static_cast<long long>(o.max_attempts_per_landmark) * o.count;
  const double min_sep2 = o.min_separation_m * o.min_separation_m;
  long long attempts = 0;
  while (static_cast<int>(out.size()) < o.count) {
    if (attempts++ >= budget) {
      std::ostringstream os;
      os << "landmarksAlongPath: placed only " << out.size() << " of " << o.count
         << " landmarks after " << budget << " attempts; lower min_separation ("
         << o.min_separation_m << " m) or the count, or widen the band";
      fail(ErrorCode::kInvalidArgument, os.str());
    }
    const double s = rng.uniform(0.0, path.perimeter());
    const double side = rng.uniform01() < 0.5 ? -1.0 : 1.0;
    const double d = rng.uniform(o.band_min_m, o.band_max_m);
    const Vec<2> p = path.position(s) + side * d * path.leftNormal(s);
    if (path.distanceTo(p) < o.band_min_m - 1e-9) continue;
    bool separated = true;
    for (const TrueLandmark2D& other : out) {
      if ((other.position - p).squaredNorm() < min_sep2) {
        separated = false;
        break;
      }
    }
    if (!separated) continue;
    out.push_back(TrueLandmark2D{static_cast<Id>(out.size()), p});
  }
  return out;
}

}  // namespace sylva::sim
