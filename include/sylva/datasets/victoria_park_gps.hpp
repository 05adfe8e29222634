#pragma once
/// @file
/// The trajectory error of a Victoria Park run against the data set's GPS
/// (sylva/datasets/victoria_park.hpp loads it).
///
/// The estimate lives in the filter's map frame (the start pose), GPS in a local east/north
/// frame: the two are related by a rigid 2D transform, found by least squares between the
/// estimated laser position at each GPS time and the fix (`eval::alignRigid2`, Umeyama 1991
/// without scale). The data set's README draws the GPS antenna at the laser, so the laser's
/// position is compared, not the rear axle's.
///
/// GPS outliers. ACFR warn that the receiver was failing ("jumps and regions without gps
/// data"). The rule, stated before any result and using the data only, never the estimate:
/// a fix is *valid* when
///   (1) the previous fix is at most 1 s older (the receiver has been tracking), and
///   (2) the step from the previous fix agrees with the distance the car drove in between
///       (integrated encoder speed at the axle centre) within 0.5 m + 20 %;
/// and fixes within 2 s after an invalid step (a jump or a gap) are invalid too, because
/// after a jump the receiver stays off for a while. The RMSE and median are over the valid
/// fixes (the alignment is fitted on them); `rmse_all_m` is over every fix inside the run,
/// with the same alignment.

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "sylva/core/error.hpp"
#include "sylva/core/types.hpp"
#include "sylva/datasets/victoria_park.hpp"
#include "sylva/eval/rigid_2d.hpp"

namespace sylva::datasets {

/// Fixes within this time after a jump or a gap are invalid too (see the file comment).
inline constexpr double kVictoriaParkGpsHoldS = 2.0;

struct TimedPosition {
  double t_s;
  Vec<2> p;
};

/// Linear interpolation of a time-ordered path at time t (clamped at the ends).
/// Throws kInvalidArgument for an empty path.
inline Vec<2> interpolatePath(const std::vector<TimedPosition>& path, double t) {
  if (path.empty()) fail(ErrorCode::kInvalidArgument, "interpolatePath: the path is empty");
  if (t <= path.front().t_s) return path.front().p;
  if (t >= path.back().t_s) return path.back().p;
  const auto it = std::lower_bound(
      path.begin(), path.end(), t, [](const TimedPosition& a, double x) { return a.t_s < x; });
  const TimedPosition& b = *it;
  const TimedPosition& a = *(it - 1);
  const double w = b.t_s > a.t_s ? (t - a.t_s) / (b.t_s - a.t_s) : 1.0;
  return a.p + w * (b.p - a.p);
}

/// The validity flag of every fix (the rule of the file comment). `wheelbase_m` and
/// `encoder_offset_m` turn the encoder speed into the axle centre's, as `Ackermann2D` does.
inline std::vector<char> validVictoriaParkGpsFixes(
    const std::vector<VictoriaParkGps>& gps,
    const std::vector<VictoriaParkOdometry>& odometry,
    double wheelbase_m,
    double encoder_offset_m,
    double hold_s = kVictoriaParkGpsHoldS) {
  // Cumulative distance of the axle centre at each odometry sample.
  std::vector<double> distance(odometry.size(), 0.0);
  for (std::size_t i = 1; i < odometry.size(); ++i) {
    const auto& o = odometry[i - 1];
    const double v_c =
        o.speed_mps / (1.0 - std::tan(o.steering_rad) * encoder_offset_m / wheelbase_m);
    distance[i] = distance[i - 1] + std::abs(v_c) * (odometry[i].t_s - o.t_s);
  }
  const auto distanceAt = [&](double t) {
    const auto it = std::lower_bound(
        odometry.begin(), odometry.end(), t, [](const VictoriaParkOdometry& o, double x) {
          return o.t_s < x;
        });
    if (it == odometry.begin()) return 0.0;
    return distance[static_cast<std::size_t>(it - odometry.begin()) - 1];
  };
  std::vector<char> valid(gps.size(), 0);
  double last_bad_t = -1e300;
  for (std::size_t i = 1; i < gps.size(); ++i) {
    const double dt = gps[i].t_s - gps[i - 1].t_s;
    const double step = std::hypot(gps[i].x_m - gps[i - 1].x_m, gps[i].y_m - gps[i - 1].y_m);
    const double driven = distanceAt(gps[i].t_s) - distanceAt(gps[i - 1].t_s);
    const bool good = dt <= 1.0 && std::abs(step - driven) <= 0.5 + 0.2 * driven;
    if (!good) last_bad_t = gps[i].t_s;
    valid[i] = good && gps[i].t_s - last_bad_t > hold_s;
  }
  return valid;
}

struct VictoriaParkGpsError {
  double rmse_valid_m = 0.0;
  double median_valid_m = 0.0;
  double rmse_all_m = 0.0;
  double max_valid_m = 0.0;
  int valid = 0;
  int total = 0;
  eval::Rigid2 transform;                    ///< map frame -> GPS frame
  std::vector<double> fix_t_s, fix_error_m;  ///< per fix inside the run
  std::vector<char> fix_valid;
};

/// Aligns the estimated laser path (time-ordered, in the filter's map frame) to the valid
/// fixes inside its time span and measures the error of every fix. With fewer than 3 valid
/// fixes nothing is aligned and only the counts are set. Throws kInvalidArgument for an empty
/// path or a flag count that differs from the fixes'. `Fix` is any type with `t_s`, `x_m` and
/// `y_m`, such as `VictoriaParkGps`; a template, so that the alignment (an SVD) is compiled only
/// in the programs that call it.
template <typename Fix>
VictoriaParkGpsError victoriaParkGpsError(const std::vector<TimedPosition>& laser_path,
                                          const std::vector<Fix>& gps,
                                          const std::vector<char>& valid) {
  if (laser_path.empty())
    fail(ErrorCode::kInvalidArgument, "victoriaParkGpsError: the path is empty");
  if (valid.size() != gps.size())
    fail(ErrorCode::kInvalidArgument,
         "victoriaParkGpsError: " + std::to_string(valid.size()) + " validity flags for " +
             std::to_string(gps.size()) + " fixes");
  VictoriaParkGpsError r;
  std::vector<Vec<2>> est_all, gps_all;
  std::vector<char> flag;
  for (std::size_t i = 0; i < gps.size(); ++i) {
    if (gps[i].t_s < laser_path.front().t_s || gps[i].t_s > laser_path.back().t_s) continue;
    est_all.push_back(interpolatePath(laser_path, gps[i].t_s));
    r.fix_t_s.push_back(gps[i].t_s);
    gps_all.push_back(Vec<2>(gps[i].x_m, gps[i].y_m));
    flag.push_back(valid[i]);
  }
  r.total = static_cast<int>(est_all.size());
  for (char f : flag) r.valid += f ? 1 : 0;
  if (r.valid < 3) return r;
  std::vector<Vec<2>> src, dst;
  for (std::size_t i = 0; i < est_all.size(); ++i)
    if (flag[i]) {
      src.push_back(est_all[i]);
      dst.push_back(gps_all[i]);
    }
  r.transform = eval::alignRigid2(src, dst);
  std::vector<double> errors;
  double sum_valid = 0.0, sum_all = 0.0;
  for (std::size_t i = 0; i < est_all.size(); ++i) {
    const Vec<2> p = r.transform(est_all[i]);
    const double e2 = (p - gps_all[i]).squaredNorm();
    sum_all += e2;
    r.fix_error_m.push_back(std::sqrt(e2));
    r.fix_valid.push_back(flag[i]);
    if (flag[i]) {
      sum_valid += e2;
      errors.push_back(std::sqrt(e2));
      r.max_valid_m = std::max(r.max_valid_m, std::sqrt(e2));
    }
  }
  r.rmse_valid_m = std::sqrt(sum_valid / r.valid);
  r.rmse_all_m = std::sqrt(sum_all / r.total);
  std::nth_element(
      errors.begin(), errors.begin() + static_cast<long>(errors.size() / 2), errors.end());
  r.median_valid_m = errors[errors.size() / 2];
  return r;
}

}  // namespace sylva::datasets
