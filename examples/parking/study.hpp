#pragma once
// The repeatability study (thesis Sec. 5.5.3, Table 5.3, Fig. 5.15 and 5.16): many parking
// attempts from random starts with the whole station in view, the spread of the final poses,
// the success rate, the cycles and the time.
//
// Starts: the distance r to P2 uniform in [r_min_m, r_max_m], the polar angle from the
// thesis' y axis uniform in [-max_angle_deg, max_angle_deg] (the robot at (r sin(phi),
// -r cos(phi))), the heading pointing at P2 plus an offset uniform in +-max_heading_offset_deg,
// drawn again until every feature lies at least margin_px inside the image.
// Run i draws its start from deriveSeed(seed, 2 i) and its pixel noise from
// deriveSeed(seed, 2 i + 1), so every run is reproducible on its own and every controller
// variant meets the same starts and the same noise.
//
// Spread: half the range (max - min) of the final position error over the parked runs, in
// x (lateral) and y (along the axis): the +- of Fig. 5.16. Cycles and time are averaged over
// the parked runs.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include <sylva/sim/random.hpp>

#include "episode.hpp"

namespace parking {

struct StudyOptions {
  int runs = 200;
  std::uint64_t seed = 1;
  double r_min_m = 0.8;
  double r_max_m = 1.5;
  double max_angle_deg = 35.0;
  double max_heading_offset_deg = 25.0;
  double margin_px = 20.0;
  double max_time_s = 300.0;

  void validate() const {
    const auto bad = [](const std::string& sentence) {
      sylva::fail(sylva::ErrorCode::kInvalidArgument, "study: " + sentence);
    };
    for (double v :
         {r_min_m, r_max_m, max_angle_deg, max_heading_offset_deg, margin_px, max_time_s})
      if (!std::isfinite(v))
        sylva::fail(sylva::ErrorCode::kNonFinite, "study: options must be finite");
    if (runs < 1 || runs > 10000000) bad("runs must be in [1, 10^7]");
    if (!(r_min_m > 0.0 && r_min_m <= r_max_m)) bad("need 0 < r_min_m <= r_max_m");
    if (!(max_angle_deg >= 0.0 && max_angle_deg < 89.0)) bad("max_angle_deg must be in [0, 89)");
    if (!(max_heading_offset_deg >= 0.0 && max_heading_offset_deg <= 90.0))
      bad("max_heading_offset_deg must be in [0, 90]");
    if (!(margin_px >= 0.0)) bad("margin_px must be >= 0");
    if (!(max_time_s > 0.0)) bad("max_time_s must be > 0");
  }
};

/// A random start with the whole station in view (see the file comment).
inline Pose drawStart(const StationCamera& camera, const StudyOptions& o, sylva::sim::Rng& rng) {
  const double r = o.r_min_m < o.r_max_m ? rng.uniform(o.r_min_m, o.r_max_m) : o.r_min_m;
  const double phi =
      o.max_angle_deg > 0.0 ? rng.uniform(-o.max_angle_deg, o.max_angle_deg) * kRadPerDeg : 0.0;
  Pose start(r * std::sin(phi), -r * std::cos(phi), 0.0);
  const double toward_p2 = std::atan2(-start[1], -start[0]);
  const double W = camera.params().image_width_px;
  for (int attempt = 0; attempt < 10000; ++attempt) {
    const double offset = o.max_heading_offset_deg > 0.0
                              ? rng.uniform(-o.max_heading_offset_deg, o.max_heading_offset_deg)
                              : 0.0;
    start[2] = sylva::wrapAngle(toward_p2 + offset * kRadPerDeg);
    const StationView v = camera.view(start);
    if (v.allVisible() && v.u[0] >= o.margin_px && v.u[2] <= W - o.margin_px) return start;
  }
  std::ostringstream os;
  os << "study: no heading within +-" << o.max_heading_offset_deg << " deg of P2 shows the "
     << "whole station " << o.margin_px << " px inside the image from (" << start[0] << ", "
     << start[1] << ") m; widen the heading offset or move the starts";
  sylva::fail(sylva::ErrorCode::kInvalidArgument, os.str());
}

struct StudyRun {
  Pose start = Pose::Zero();
  Outcome outcome = Outcome::kTimedOut;
  Pose error = Pose::Zero();
  int cycles = 0;
  double time_s = 0.0;
  double min_station_distance_m = 0.0;
};

struct StudySummary {
  int runs = 0;
  int parked = 0;
  int station_lost = 0;
  int timed_out = 0;
  int collided = 0;
  double success_rate = 0.0;
  double x_spread_m = 0.0;  ///< half of max - min of the final lateral error (parked runs)
  double y_spread_m = 0.0;  ///< the same along the axis
  double x_mean_m = 0.0, y_mean_m = 0.0;
  double x_std_m = 0.0, y_std_m = 0.0;
  double heading_spread_rad = 0.0;
  double mean_cycles = 0.0;
  int max_cycles = 0;
  double mean_time_s = 0.0;
  double max_time_s = 0.0;
  double min_station_distance_m = 0.0;  ///< closest approach over all runs
};

struct StudyResult {
  std::vector<StudyRun> runs;
  StudySummary summary;
};

inline StudySummary summarize(const std::vector<StudyRun>& runs) {
  StudySummary s;
  s.runs = static_cast<int>(runs.size());
  double x_lo = 0, x_hi = 0, y_lo = 0, y_hi = 0, h_lo = 0, h_hi = 0;
  double sx = 0, sy = 0, sxx = 0, syy = 0, cycles = 0, time = 0;
  s.min_station_distance_m = std::numeric_limits<double>::infinity();
  for (const StudyRun& r : runs) {
    s.min_station_distance_m = std::min(s.min_station_distance_m, r.min_station_distance_m);
    switch (r.outcome) {
      case Outcome::kParked:
        break;
      case Outcome::kStationLost:
        ++s.station_lost;
        continue;
      case Outcome::kTimedOut:
        ++s.timed_out;
        continue;
      case Outcome::kCollided:
        ++s.collided;
        continue;
    }
    const double x = r.error[0], y = r.error[1], h = r.error[2];
    if (s.parked == 0) {
      x_lo = x_hi = x;
      y_lo = y_hi = y;
      h_lo = h_hi = h;
    }
    ++s.parked;
    x_lo = std::min(x_lo, x), x_hi = std::max(x_hi, x);
    y_lo = std::min(y_lo, y), y_hi = std::max(y_hi, y);
    h_lo = std::min(h_lo, h), h_hi = std::max(h_hi, h);
    sx += x, sy += y, sxx += x * x, syy += y * y;
    cycles += r.cycles;
    time += r.time_s;
    s.max_cycles = std::max(s.max_cycles, r.cycles);
    s.max_time_s = std::max(s.max_time_s, r.time_s);
  }
  s.success_rate = s.runs > 0 ? static_cast<double>(s.parked) / s.runs : 0.0;
  if (s.parked > 0) {
    const double n = s.parked;
    s.x_spread_m = 0.5 * (x_hi - x_lo);
    s.y_spread_m = 0.5 * (y_hi - y_lo);
    s.heading_spread_rad = 0.5 * (h_hi - h_lo);
    s.x_mean_m = sx / n;
    s.y_mean_m = sy / n;
    s.x_std_m = std::sqrt(std::max(0.0, sxx / n - s.x_mean_m * s.x_mean_m));
    s.y_std_m = std::sqrt(std::max(0.0, syy / n - s.y_mean_m * s.y_mean_m));
    s.mean_cycles = cycles / n;
    s.mean_time_s = time / n;
  }
  return s;
}

/// Runs the study for one controller variant. Single-threaded: a run takes well under a
/// millisecond, so 200 runs take a fraction of a second.
inline StudyResult runStudy(const StationCamera& camera,
                            const ControllerParams& controller,
                            const RobotParams& robot,
                            const StudyOptions& o) {
  o.validate();
  controller.validate();
  StudyResult result;
  result.runs.reserve(static_cast<std::size_t>(o.runs));
  EpisodeOptions episode;
  episode.max_time_s = o.max_time_s;
  for (int i = 0; i < o.runs; ++i) {
    const auto index = static_cast<std::uint64_t>(i);
    sylva::sim::Rng start_rng(sylva::sim::deriveSeed(o.seed, 2 * index));
    const Pose start = drawStart(camera, o, start_rng);
    const EpisodeResult e = runEpisode(
        camera, controller, robot, start, sylva::sim::deriveSeed(o.seed, 2 * index + 1), episode);
    StudyRun run;
    run.start = start;
    run.outcome = e.outcome;
    run.error = e.error;
    run.cycles = e.cycles;
    run.time_s = e.time_s;
    run.min_station_distance_m = e.min_station_distance_m;
    result.runs.push_back(run);
  }
  result.summary = summarize(result.runs);
  return result;
}

}  // namespace parking
