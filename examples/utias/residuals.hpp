#pragma once
// The noise study behind the example's default noise model (docs/examples/utias.md): the
// data against the Vicon ground truth, with no filter involved.
//
// Measurements: the residual z - h(x_gt(t), l_gt) of every landmark observation, h the
// range-bearing model at the interpolated true pose and the true landmark. Robust spread:
// 1.4826 x the median absolute deviation (the standard deviation for Gaussian data, not
// inflated by the outliers of a barcode camera), and the share of residuals beyond 3 and
// 5 robust sigmas.
//
// Commands: over windows of `window_s` seconds, the commands are integrated with the
// unicycle model from the true pose at the window's start (exactly as the filter predicts),
// and the end pose is compared with the true one. The error is expressed in the robot frame
// at the start: along track, across track, heading. Under white noise of spectral density
// q on a control the variance of its error grows as q T, so q = variance / T; the windows
// are split by mean speed to see how the error grows with speed.
//
// Command delay: the commanded turn rate against the true one (Vicon) at increasing lags.

#include <algorithm>
#include <cmath>
#include <map>
#include <vector>

#include <Eigen/Cholesky>

#include <sylva/core/angles.hpp>
#include <sylva/datasets/utias_mrclam.hpp>
#include <sylva/measurements/range_bearing.hpp>
#include <sylva/motion/unicycle_2d.hpp>

#include "ground_truth.hpp"

namespace utias {

/// Location and spread of a sample.
struct Spread {
  long count = 0;
  double mean = 0.0;
  double sigma = 0.0;         ///< standard deviation
  double robust_sigma = 0.0;  ///< 1.4826 median |x - median|
  double median = 0.0;
  double beyond3 = 0.0;  ///< share with |x - median| > 3 robust sigmas
  double beyond5 = 0.0;
};

inline double medianOf(std::vector<double> v) {
  if (v.empty()) return 0.0;
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

inline Spread spreadOf(const std::vector<double>& x) {
  Spread s;
  s.count = static_cast<long>(x.size());
  if (x.empty()) return s;
  double sum = 0.0, sum2 = 0.0;
  for (double v : x) sum += v;
  s.mean = sum / static_cast<double>(x.size());
  for (double v : x) sum2 += (v - s.mean) * (v - s.mean);
  s.sigma = std::sqrt(sum2 / static_cast<double>(x.size()));
  s.median = medianOf(x);
  std::vector<double> dev;
  dev.reserve(x.size());
  for (double v : x) dev.push_back(std::abs(v - s.median));
  s.robust_sigma = 1.4826 * medianOf(dev);
  for (double d : dev) {
    s.beyond3 += d > 3.0 * s.robust_sigma ? 1.0 : 0.0;
    s.beyond5 += d > 5.0 * s.robust_sigma ? 1.0 : 0.0;
  }
  s.beyond3 /= static_cast<double>(x.size());
  s.beyond5 /= static_cast<double>(x.size());
  return s;
}

struct MeasurementResiduals {
  std::vector<double> range_m, bearing_rad;
};

/// Residuals of every landmark observation of `robot` whose landmark has ground truth.
inline MeasurementResiduals measurementResiduals(const sylva::datasets::UtiasDataset& data,
                                                 const sylva::datasets::UtiasRobotData& robot) {
  std::map<int, Vec<2>> truth;
  for (const auto& l : data.landmarks) truth[l.subject] = l.position_m;
  const GroundTruth gt(robot.groundtruth);
  MeasurementResiduals out;
  const sylva::RangeBearing model;
  for (const auto& obs : robot.landmark_observations) {
    const auto it = truth.find(obs.subject);
    if (it == truth.end() || !gt.covers(obs.time_s)) continue;
    const Vec<2> h = model.predict<double>(gt.at(obs.time_s), it->second);
    const Vec<2> r = model.residual(obs.z, h);
    out.range_m.push_back(r[0]);
    out.bearing_rad.push_back(r[1]);
  }
  return out;
}

struct CommandResiduals {
  std::vector<double> along_m, across_m, heading_rad;
  std::vector<double> mean_speed_mps, mean_turn_radps;
};

/// Integrates the commands over consecutive windows from the true pose (see the file comment).
inline CommandResiduals commandResiduals(const sylva::datasets::UtiasRobotData& robot, double window_s, double delay_s) {
  const GroundTruth gt(robot.groundtruth);
  const sylva::Unicycle2D unicycle;
  CommandResiduals out;
  std::vector<sylva::datasets::UtiasCommand> cmds = robot.odometry;
  for (auto& c : cmds) c.time_s += delay_s;
  std::size_t k = 0;  // first command after the window's start
  for (double t0 = cmds.front().time_s; t0 + window_s <= std::min(cmds.back().time_s, gt.end()); t0 += window_s) {
    const double t1 = t0 + window_s;
    while (k < cmds.size() && cmds[k].time_s <= t0) ++k;
    Vec<2> u = cmds[k - 1].u;
    Vec<3> x = gt.at(t0);
    const Vec<3> start = x;
    double t = t0, dist = 0.0, turn = 0.0;
    std::size_t j = k;
    while (t < t1) {
      const double next = j < cmds.size() ? std::min(cmds[j].time_s, t1) : t1;
      x = unicycle(x, u, next - t);
      dist += std::abs(u[0]) * (next - t);
      turn += std::abs(u[1]) * (next - t);
      t = next;
      if (j < cmds.size() && cmds[j].time_s <= t1 && t == cmds[j].time_s) u = cmds[j++].u;
    }
    const Vec<3> end = gt.at(t1);
    const Vec<2> d = end.head<2>() - x.head<2>();
    const double c = std::cos(start[2]), s = std::sin(start[2]);
    out.along_m.push_back(c * d.x() + s * d.y());
    out.across_m.push_back(-s * d.x() + c * d.y());
    out.heading_rad.push_back(sylva::wrapAngle(end[2] - x[2]));
    out.mean_speed_mps.push_back(dist / window_s);
    out.mean_turn_radps.push_back(turn / window_s);
  }
  return out;
}

/// RMS difference between the commanded turn rate logged at t and the true turn rate at
/// t + lag (central difference of the Vicon heading over +-0.1 s), over every 5th command:
/// the lag that minimizes it is how late the robot follows its commands.
/// The sums behind turnRateLagRms, so that several robots can be pooled.
struct TurnRateLagSums {
  double squared_sum = 0.0;  ///< sum of squared differences (rad/s)^2
  long count = 0;
  void add(const TurnRateLagSums& o) {
    squared_sum += o.squared_sum;
    count += o.count;
  }
  double rms() const { return count > 0 ? std::sqrt(squared_sum / static_cast<double>(count)) : 0.0; }
};

inline TurnRateLagSums turnRateLagSums(const sylva::datasets::UtiasRobotData& robot, double lag_s) {
  const GroundTruth gt(robot.groundtruth);
  double sum = 0.0;
  long n = 0;
  for (std::size_t k = 0; k < robot.odometry.size(); k += 5) {
    const double t = robot.odometry[k].time_s + lag_s;
    if (t - 0.1 < gt.begin() || t + 0.1 > gt.end()) continue;
    const double rate = sylva::wrapAngle(gt.at(t + 0.1)[2] - gt.at(t - 0.1)[2]) / 0.2;
    sum += (rate - robot.odometry[k].u[1]) * (rate - robot.odometry[k].u[1]);
    ++n;
  }
  TurnRateLagSums out;
  out.squared_sum = sum;
  out.count = n;
  return out;
}

inline double turnRateLagRms(const sylva::datasets::UtiasRobotData& robot, double lag_s) {
  return turnRateLagSums(robot, lag_s).rms();
}

}  // namespace utias

namespace utias {

/// Least-squares calibration of the commands against the Vicon motion over consecutive
/// windows of `window_s` (commands delayed by `delay_s`, piecewise constant):
///   true turn      = omega_gain x commanded turn + omega_bias x window   (all windows)
///   true distance  = v_gain x commanded distance - v_turn_loss x integral of |omega| while driving
///                                                                      (windows with commanded distance > 0)
/// The sums are returned so several robots can be pooled.
struct CommandCalibration {
  Eigen::Matrix2d turn_normal = Eigen::Matrix2d::Zero();
  Eigen::Vector2d turn_rhs = Eigen::Vector2d::Zero();
  Eigen::Matrix2d distance_normal = Eigen::Matrix2d::Zero();
  Eigen::Vector2d distance_rhs = Eigen::Vector2d::Zero();
  long windows = 0;

  void add(const CommandCalibration& o) {
    turn_normal += o.turn_normal;
    turn_rhs += o.turn_rhs;
    distance_normal += o.distance_normal;
    distance_rhs += o.distance_rhs;
    windows += o.windows;
  }
  /// [omega_gain, omega_bias (rad/s)]
  Eigen::Vector2d turn(double window_s) const {
    Eigen::Vector2d c = turn_normal.ldlt().solve(turn_rhs);
    c[1] /= window_s;
    return c;
  }
  /// [v_gain, v_turn_loss (m/rad)]
  Eigen::Vector2d distance() const {
    Eigen::Vector2d c = distance_normal.ldlt().solve(distance_rhs);
    c[1] = -c[1];
    return c;
  }
};

inline CommandCalibration commandCalibration(const sylva::datasets::UtiasRobotData& robot, double window_s, double delay_s) {
  const GroundTruth gt(robot.groundtruth);
  const auto& cmds = robot.odometry;
  CommandCalibration out;
  std::size_t k = 0;
  for (double t0 = cmds.front().time_s + delay_s; t0 + window_s < std::min(gt.end(), cmds.back().time_s + delay_s);
       t0 += window_s) {
    while (k + 1 < cmds.size() && cmds[k + 1].time_s + delay_s <= t0) ++k;
    double turn = 0.0, dist = 0.0, turn_driving = 0.0, t = t0;
    for (std::size_t j = k; t < t0 + window_s;) {
      const double next = j + 1 < cmds.size() ? std::min(cmds[j + 1].time_s + delay_s, t0 + window_s) : t0 + window_s;
      const Vec<2>& u = cmds[j].u;
      turn += u[1] * (next - t);
      dist += u[0] * (next - t);
      turn_driving += (u[0] > 0.0 ? std::abs(u[1]) : 0.0) * (next - t);
      t = next;
      if (j + 1 < cmds.size() && cmds[j + 1].time_s + delay_s <= t) ++j;
    }
    const Vec<3> a = gt.at(t0), b = gt.at(t0 + window_s);
    ++out.windows;
    {
      const Eigen::Vector2d x(turn, window_s);
      out.turn_normal += x * x.transpose();
      out.turn_rhs += x * sylva::wrapAngle(b[2] - a[2]);
    }
    if (dist > 0.0) {
      const Eigen::Vector2d x(dist, turn_driving);
      out.distance_normal += x * x.transpose();
      out.distance_rhs += x * (b.head<2>() - a.head<2>()).norm();
    }
  }
  return out;
}

/// Correlation of the measurement residuals of the same landmark at two times, by the time
/// between them (pairs within `max_lag_s`, residuals beyond 1 m / 0.1 rad left out): how far
/// apart two readings must be to count as independent. Accumulated over robots.
struct ResidualCorrelation {
  std::vector<double> lag_edges_s{0.5, 1.0, 2.0, 4.0, 8.0, 16.0, 32.0};
  std::vector<Eigen::Matrix<double, 2, 3>> sums = std::vector<Eigen::Matrix<double, 2, 3>>(7, Eigen::Matrix<double, 2, 3>::Zero());
  std::vector<long> pairs = std::vector<long>(7, 0);

  void add(const sylva::datasets::UtiasDataset& data, const sylva::datasets::UtiasRobotData& robot) {
    std::map<int, Vec<2>> truth;
    for (const auto& l : data.landmarks) truth[l.subject] = l.position_m;
    const GroundTruth gt(robot.groundtruth);
    const sylva::RangeBearing model;
    std::map<int, std::vector<std::pair<double, Vec<2>>>> by_subject;
    for (const auto& o : robot.landmark_observations) {
      const auto it = truth.find(o.subject);
      if (it == truth.end() || !gt.covers(o.time_s)) continue;
      const Vec<2> r = model.residual(o.z, model.predict<double>(gt.at(o.time_s), it->second));
      if (std::abs(r[0]) > 1.0 || std::abs(r[1]) > 0.1) continue;
      by_subject[o.subject].push_back({o.time_s, r});
    }
    for (const auto& entry : by_subject) {
      const auto& v = entry.second;
      for (std::size_t i = 0; i < v.size(); ++i)
        for (std::size_t j = i + 1; j < v.size(); ++j) {
          const double lag = v[j].first - v[i].first;
          if (lag > lag_edges_s.back()) break;
          std::size_t b = 0;
          while (lag > lag_edges_s[b]) ++b;
          for (int c = 0; c < 2; ++c) {
            sums[b](c, 0) += v[i].second[c] * v[j].second[c];
            sums[b](c, 1) += v[i].second[c] * v[i].second[c];
            sums[b](c, 2) += v[j].second[c] * v[j].second[c];
          }
          ++pairs[b];
        }
    }
  }
  double correlation(std::size_t bin, int component) const {
    const auto& s = sums[bin];
    return s(component, 0) / std::sqrt(s(component, 1) * s(component, 2));
  }
};

}  // namespace utias
