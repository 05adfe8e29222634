#pragma once
// The Vicon ground truth of one robot as a function of time: linear interpolation between
// the two samples around t (x and y linear, theta along the shorter arc). The samples are
// irregular (median 16 ms, gaps up to 0.32 s in Dataset 7), so interpolation, not the
// nearest sample, is what the filter's estimate at time t is compared with.

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
  explicit GroundTruth(const std::vector<sylva::datasets::UtiasPose>& samples) : samples_(samples) {
    if (samples_.empty()) sylva::fail(sylva::ErrorCode::kInvalidArgument, "GroundTruth: no samples");
  }

  double begin() const { return samples_.front().time_s; }
  double end() const { return samples_.back().time_s; }
  bool covers(double t) const { return t >= begin() && t <= end(); }

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
};

}  // namespace utias
