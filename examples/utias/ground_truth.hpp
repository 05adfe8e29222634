#pragma once
// The Vicon ground truth of one robot as a function of time: linear interpolation between
// the two samples around t (x and y linear, theta along the shorter arc). The samples are
// irregular (median 16 ms, gaps up to 0.32 s in Dataset 7), so interpolation, not the
// nearest sample, is what the filter's estimate at time t is compared with.
//
// Where the truth exists: a time t is covered when it lies within the recorded span and the
// two samples around it are at most `max_gap_s` apart (1 s by default: Dataset 7's gaps
// are at most 0.32 s). Outside that, `at` would only repeat the nearest sample, so the scores
// (evaluation.hpp) leave such times out. In MRCLAM Dataset 6 robot 1's truth stops about
// 130 s before its odometry does; the program then says how far it scored.

#include <algorithm>
#include <vector>

#include <sylva/core/angles.hpp>
#include <sylva/core/error.hpp>
#include <sylva/core/types.hpp>
#include <sylva/datasets/utias_mrclam.hpp>

namespace utias {

using sylva::Vec;

class GroundTruth {
 public:
  static constexpr double kDefaultMaxGapS = 1.0;

  explicit GroundTruth(const std::vector<sylva::datasets::UtiasPose>& samples, double max_gap_s = kDefaultMaxGapS)
      : samples_(samples), max_gap_s_(max_gap_s) {
    if (samples_.empty()) sylva::fail(sylva::ErrorCode::kInvalidArgument, "GroundTruth: no samples");
    if (!(max_gap_s_ > 0.0))
      sylva::fail(sylva::ErrorCode::kInvalidArgument, "GroundTruth: the largest gap must be > 0 s");
  }

  double begin() const { return samples_.front().time_s; }
  double end() const { return samples_.back().time_s; }
  double maxGap() const { return max_gap_s_; }

  /// t lies within the recorded span and its two neighbouring samples are at most maxGap() apart.
  bool covers(double t) const {
    if (!(t >= begin() && t <= end())) return false;
    const auto it = std::lower_bound(samples_.begin(), samples_.end(), t,
                                     [](const auto& s, double time) { return s.time_s < time; });
    if (it == samples_.begin() || it->time_s == t) return true;  // on a sample
    return it->time_s - (it - 1)->time_s <= max_gap_s_;
  }

  /// The pose at time t (clamped to the first / last sample outside the covered span).
  Vec<3> at(double t) const {
    if (t <= begin()) return samples_.front().pose;
    if (t >= end()) return samples_.back().pose;
    const auto it = std::upper_bound(samples_.begin(), samples_.end(), t,
                                     [](double time, const auto& s) { return time < s.time_s; });
    const auto& b = *it;
    const auto& a = *(it - 1);
    const double span = b.time_s - a.time_s;
    const double w = span > 0.0 ? (t - a.time_s) / span : 0.0;
    Vec<3> p = a.pose + w * (b.pose - a.pose);
    p[2] = sylva::wrapAngle(a.pose[2] + w * sylva::wrapAngle(b.pose[2] - a.pose[2]));
    return p;
  }

 private:
  const std::vector<sylva::datasets::UtiasPose>& samples_;
  double max_gap_s_;
};

}  // namespace utias
