#pragma once
// One EKF-SLAM run over the Victoria Park data, for either variant:
//   PointVariant  Ekf<Ackermann2D, Point2>   with RangeBearing        z = [range, bearing]
//   TreeVariant   Ekf<Ackermann2D, TreeXYR>  with RangeBearingDiameter z = [range, bearing, diameter]
// Both measure from the laser, mounted at (L + a, b) in the rear-axle frame. With
// `bias_states` other than "none" the car is Ackermann2DWithBias instead: an encoder speed scale error and a
// steering offset join the state and are estimated online; the sensors see its pose view.
//
// Per laser scan (the scan is the only event that changes the map):
//   1. Predict to the scan time with the odometry since the previous scan. "scan" (default):
//      the samples are integrated into one step: the distance D = sum v_c dt_i and the
//      heading change Phi = sum omega dt_i of the samples (zero-order hold, the last segment
//      cut at the scan time) define the constant control [v_e, alpha] over T = sum dt_i with
//      the same D and Phi, and the per-sample control noise is scaled by dt_s / T (independent
//      per-sample errors add up). "odometry": one filter prediction per sample segment, the
//      same scaling. The mean differs by the chord-vs-arc error of a 0.2 s step (mm).
//   Steps 2-5 are sylva::slam::FrontEnd's, with these options:
//   2. Candidates: map landmarks whose predicted range is below max range + 5 m and whose
//      bearing is within 100 deg of the car's axis (the laser sees 180 deg ahead).
//   3. Association of the readings (range <= max range) with the candidates: JCBB (default)
//      or nearest neighbour, chi-square gate 0.99.
//   4. One batched update with every paired reading (`Fusion::kBatched`). If the filter
//      refuses the batch, the readings are fused one at a time and the refused ones skipped.
//   5. New landmarks: a reading that paired with nothing and whose NIS with every candidate
//      exceeds chi2(dim, 0.9999) feeds the nearest tentative track within 1 m (world position
//      from the inverse model at the current estimate) or starts one. A tentative track seen
//      in 5 scans becomes a landmark, initialized from its latest reading; one not seen for
//      2 s is dropped. Readings in between the two gates are ambiguous and dropped.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <vector>

#include <sylva/datasets/victoria_park.hpp>
#include <sylva/datasets/victoria_park_gps.hpp>
#include <sylva/filter/compression.hpp>
#include <sylva/filter/ekf.hpp>
#include <sylva/landmarks.hpp>
#include <sylva/measurements.hpp>
#include <sylva/motion/ackermann_2d.hpp>
#include <sylva/motion/ackermann_2d_with_bias.hpp>
#include <sylva/slam/front_end.hpp>
#include <sylva/slam/reach.hpp>

#include "config.hpp"

namespace victoria_park {

using sylva::Gaussian;
using sylva::Id;
using sylva::Mat;
using sylva::Vec;
namespace ds = sylva::datasets;

struct PointVariant {
  static constexpr const char* kName = "point";
  using Landmark = sylva::Point2;
  using Model = sylva::RangeBearing;
  using Inverse = sylva::InverseRangeBearing;
  static constexpr int kDim = 2;
  static Vec<2> measurement(const ds::VictoriaParkDetection& d) { return Vec<2>(d.range_m, ds::carBearing(d)); }
  static Gaussian<2> noise(const Config& c) { return Gaussian<2>::sigmas(Vec<2>(c.noise.range_m, c.noise.bearing_rad)); }
  static double radius(const Vec<2>&) { return 0.0; }
};

struct TreeVariant {
  static constexpr const char* kName = "tree";
  using Landmark = sylva::TreeXYR;
  using Model = sylva::RangeBearingDiameter;
  using Inverse = sylva::InverseRangeBearingDiameter;
  static constexpr int kDim = 3;
  static Vec<3> measurement(const ds::VictoriaParkDetection& d) {
    return Vec<3>(d.range_m, ds::carBearing(d), d.diameter_m);
  }
  static Gaussian<3> noise(const Config& c) {
    return Gaussian<3>::sigmas(Vec<3>(c.noise.range_m, c.noise.bearing_rad, c.diameter_sigma_m));
  }
  static double radius(const Vec<3>& l) { return l[2]; }
};

struct MapLandmark {
  Vec<2> p;          ///< in the GPS frame after alignment
  double radius_m;   ///< 0 for points
  int sightings;
};

struct RunResult {
  std::string variant;
  ds::VictoriaParkGpsError gps;
  int landmarks = 0;
  long scans = 0;
  long predictions = 0;
  long readings = 0;           ///< detections within the max range
  long paired = 0;             ///< fused into the map
  long ambiguous = 0;          ///< unpaired but too close to a landmark to start a new one
  long tentative_readings = 0; ///< fed or started a tentative track
  long tentatives_dropped = 0;
  long refused_updates = 0;    ///< readings the filter refused after a refused batch
  double runtime_s = 0.0;
  double step_ms_end = 0.0;    ///< mean time per scan over the last 100 scans
  double step_ms_mean = 0.0;
  std::vector<ds::TimedPosition> laser_path;  ///< in the GPS frame after alignment
  std::vector<MapLandmark> map;        ///< in the GPS frame after alignment
  // With bias states: the final estimates and their standard deviations (else NaN).
  double speed_scale = std::nan("");
  double speed_scale_sigma = std::nan("");
  double steering_offset_rad = std::nan("");
  double steering_offset_sigma_rad = std::nan("");
  long global_updates = 0;             ///< the compressed EKF's (0 for the plain filter)
};

/// The filter's final estimate with the landmarks in increasing order of id (the compressed
/// EKF orders its slots by region), for comparing two runs.
struct FinalState {
  Eigen::VectorXd mean;
  Eigen::MatrixXd covariance;
  std::vector<Id> ids;
};

namespace detail {

/// Integrates odometry up to time t, either into the filter one sample at a time or into one
/// step (see the file comment). For a car with bias states the noise gains the biases'
/// random walks (variance q dt over a step of dt: Var(w) = q / dt).
template <class Filter>
class OdometryIntegrator {
 public:
  static constexpr int kNoiseDim = Filter::kNoiseDim;
  OdometryIntegrator(const std::vector<ds::VictoriaParkOdometry>& odometry, const Config& c, const sylva::Ackermann2D& car)
      : odo_(odometry), cfg_(c), car_(car),
        q_sample_(Vec<2>(c.noise.speed_mps * c.noise.speed_mps, c.noise.steering_rad * c.noise.steering_rad).asDiagonal()) {
    t_ = odometry.front().t_s;
  }

  /// Moves the filter to time t; returns the number of filter predictions made.
  long advanceTo(Filter& ekf, double t) {
    long predictions = 0;
    double distance = 0.0, turn = 0.0, span = 0.0, alpha_sum = 0.0;
    while (t_ < t - 1e-9) {
      while (next_ < odo_.size() && odo_[next_].t_s <= t_ + 1e-9) ++next_;
      if (next_ == 0) {  // before the first sample: the car stands still
        t_ = std::min(t, odo_.front().t_s);
        continue;
      }
      const ds::VictoriaParkOdometry& o = odo_[next_ - 1];
      const double end = next_ < odo_.size() ? std::min(t, odo_[next_].t_s) : t;
      const double dt = end - t_;
      t_ = end;
      if (dt <= 1e-9) continue;
      if (cfg_.predict == "odometry") {
        ekf.predict(Vec<2>(o.speed_mps, o.steering_rad), dt, noiseFor(dt));
        ++predictions;
      } else {
        double v_c = 0.0, omega = 0.0;
        car_.axleMotion(o.speed_mps, o.steering_rad, v_c, omega);
        distance += v_c * dt;
        turn += omega * dt;
        span += dt;
        alpha_sum += o.steering_rad * dt;
      }
    }
    if (span > 1e-9) {
      const double v_c = distance / span;
      const double omega = turn / span;
      double alpha = alpha_sum / span;
      if (std::abs(v_c) > 1e-3) alpha = std::atan(car_.wheelbase() * omega / v_c);
      const double v_e = v_c * (1.0 - std::tan(alpha) * car_.encoderOffset() / car_.wheelbase());
      ekf.predict(Vec<2>(v_e, alpha), span, noiseFor(span));
      ++predictions;
    }
    return predictions;
  }

 private:
  Gaussian<kNoiseDim> noiseFor(double dt) const {
    Mat<kNoiseDim, kNoiseDim> Q = Mat<kNoiseDim, kNoiseDim>::Zero();
    Q.template topLeftCorner<2, 2>() = q_sample_ * (cfg_.odometry_period_s / dt);
    if constexpr (kNoiseDim == 4) {
      const double speed = cfg_.estimatesSpeedScale() ? cfg_.speed_scale_walk : Config::kHeldSigma;
      const double steering = cfg_.estimatesSteeringOffset() ? cfg_.steering_offset_walk_rad : Config::kHeldSigma;
      Q(2, 2) = speed * speed / dt;
      Q(3, 3) = steering * steering / dt;
    }
    return Gaussian<kNoiseDim>::covariance(Q);
  }
  const std::vector<ds::VictoriaParkOdometry>& odo_;
  const Config& cfg_;
  sylva::Ackermann2D car_;
  Mat<2, 2> q_sample_;
  std::size_t next_ = 0;
  double t_ = 0.0;
};

}  // namespace detail

template <class V, class Car>
RunResult runSlamWith(const ds::VictoriaParkData& data, const Config& cfg, const std::vector<char>& gps_valid,
                      FinalState* final_state) {
  using Filter = sylva::Ekf<Car, typename V::Landmark>;
  constexpr int kCarDim = Car::kDim;
  using Model = typename V::Model;
  constexpr int M = V::kDim;
  using Clock = std::chrono::steady_clock;

  const Car car(cfg.wheelbase_m, cfg.encoder_offset_m);
  const Vec<2> mount(cfg.wheelbase_m + cfg.laser_ahead_m, cfg.laser_left_m);
  const Gaussian<M> R = V::noise(cfg);

  // The car starts at the origin of the map; the biases (if any) at zero with their priors.
  Mat<kCarDim, kCarDim> P0 = Mat<kCarDim, kCarDim>::Zero();
  if constexpr (kCarDim == 5) {
    const double speed = cfg.estimatesSpeedScale() ? cfg.speed_scale_prior : Config::kHeldSigma;
    const double steering = cfg.estimatesSteeringOffset() ? cfg.steering_offset_prior_rad : Config::kHeldSigma;
    P0(3, 3) = speed * speed;
    P0(4, 4) = steering * steering;
  }
  Filter ekf(Vec<kCarDim>::Zero(), P0, car);
  if (cfg.linearization == "first-estimates") ekf.setLinearizationPoint(sylva::LinearizationPoint::kFirstEstimates);
  if (cfg.linearization == "invariant") ekf.setLinearizationPoint(sylva::LinearizationPoint::kInvariant);
  ekf.reserve(V::Landmark::kDim * 512);
  if (cfg.compress_radius_m > 0.0) ekf.setCompression(Filter::withinRadius(cfg.compress_radius_m, cfg.compress_ahead_m));
  detail::OdometryIntegrator<Filter> odometry(data.odometry, cfg, sylva::Ackermann2D(cfg.wheelbase_m, cfg.encoder_offset_m));

  // Steps 2-5 of the file comment. Candidates: landmarks in front of the laser and within range.
  sylva::slam::FrontEndOptions options;
  options.association = cfg.association == "nn" ? sylva::slam::Association::kNearestNeighbor : sylva::slam::Association::kJcbb;
  options.gate_probability = cfg.gate_probability;
  options.new_landmark_probability = cfg.new_landmark_probability;
  options.new_landmarks = sylva::slam::NewLandmarks::kTentative;
  options.tentative = {cfg.confirm_sightings, cfg.tentative_radius_m, cfg.tentative_timeout_s};
  // Braces: with parentheses g++ reads `typename V::Inverse(mount)` as a parameter declaration.
  sylva::slam::FrontEnd<Filter, Model, typename V::Inverse> front_end{
      Model(mount), typename V::Inverse(mount), options,
      sylva::slam::candidatesInReach<typename V::Landmark>(sylva::RangeBearing(mount),
                                                           {cfg.max_range_m + 5.0, 100.0 * sylva::kRadPerDeg})};

  RunResult out;
  out.variant = V::kName;
  std::vector<ds::TimedPosition> path;
  std::vector<double> step_ms;
  std::vector<sylva::slam::Reading<M>> readings;
  const double t_start = data.scans.front().t_s;
  const auto run_begin = Clock::now();

  for (const ds::VictoriaParkScan& scan : data.scans) {
    if (cfg.duration_s > 0.0 && scan.t_s > t_start + cfg.duration_s) break;
    const auto step_begin = Clock::now();
    out.predictions += odometry.advanceTo(ekf, scan.t_s);
    ++out.scans;

    readings.clear();
    for (const auto& d : scan.detections)
      if (d.range_m <= cfg.max_range_m) readings.push_back({V::measurement(d), R});
    out.readings += static_cast<long>(readings.size());
    const sylva::slam::StepReport& report = front_end.update(ekf, readings, scan.t_s);
    using sylva::slam::Outcome;
    out.paired += report.count(Outcome::kPaired);
    out.ambiguous += report.count(Outcome::kAmbiguous);
    out.tentative_readings += report.count(Outcome::kTentative) + report.count(Outcome::kAdded);
    out.refused_updates += report.count(Outcome::kRefused);

    const Vec<3> xr = ekf.robotMean().template head<3>();
    path.push_back(ds::TimedPosition{scan.t_s, sylva::RangeBearing(mount).sensorPosition<double>(xr)});
    step_ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - step_begin).count());
  }
  out.runtime_s = std::chrono::duration<double>(Clock::now() - run_begin).count();
  const std::size_t tail = std::min<std::size_t>(100, step_ms.size());
  double sum = 0.0;
  for (std::size_t i = step_ms.size() - tail; i < step_ms.size(); ++i) sum += step_ms[i];
  out.step_ms_end = tail ? sum / static_cast<double>(tail) : 0.0;
  out.step_ms_mean = step_ms.empty() ? 0.0 : 1e3 * out.runtime_s / static_cast<double>(step_ms.size());
  out.landmarks = ekf.landmarkCount();

  out.gps = ds::victoriaParkGpsError(path, data.gps, gps_valid);
  const auto toGps = [&](const Vec<2>& p) { return out.gps.transform(p); };
  for (const ds::TimedPosition& tp : path) out.laser_path.push_back(ds::TimedPosition{tp.t_s, toGps(tp.p)});
  for (const sylva::LandmarkSlot& s : ekf.slots()) {
    const auto l = ekf.template landmarkMean<typename V::Landmark>(s.id);
    out.map.push_back(MapLandmark{toGps(l.template head<2>()), V::radius(l), front_end.sightings(s.id)});
  }
  out.global_updates = ekf.globalUpdates();
  if (final_state != nullptr) {
    std::vector<sylva::LandmarkSlot> by_id = ekf.slots();
    std::sort(by_id.begin(), by_id.end(), [](const sylva::LandmarkSlot& a, const sylva::LandmarkSlot& b) { return a.id < b.id; });
    std::vector<int> rows;
    for (int i = 0; i < Filter::kRobotDim; ++i) rows.push_back(i);
    final_state->ids.clear();
    for (const sylva::LandmarkSlot& s : by_id) {
      final_state->ids.push_back(s.id);
      for (int i = 0; i < s.dim; ++i) rows.push_back(s.offset + i);
    }
    static_assert(Filter::kRobotStateDim == Filter::kRobotDim, "the car's state is its own tangent");
    const Eigen::VectorXd mean = ekf.mean();
    const Eigen::MatrixXd covariance = ekf.covariance();
    const auto n = static_cast<Eigen::Index>(rows.size());
    final_state->mean.resize(n);
    final_state->covariance.resize(n, n);
    for (Eigen::Index j = 0; j < n; ++j) {
      final_state->mean[j] = mean[rows[static_cast<std::size_t>(j)]];
      for (Eigen::Index i = 0; i < n; ++i)
        final_state->covariance(i, j) = covariance(rows[static_cast<std::size_t>(i)], rows[static_cast<std::size_t>(j)]);
    }
  }
  if constexpr (kCarDim == 5) {
    out.speed_scale = ekf.robotMean()[3];
    out.steering_offset_rad = ekf.robotMean()[4];
    out.speed_scale_sigma = std::sqrt(ekf.robotCovariance()(3, 3));
    out.steering_offset_sigma_rad = std::sqrt(ekf.robotCovariance()(4, 4));
  }
  return out;
}

/// One run of variant V with the car the configuration asks for.
template <class V>
RunResult runSlam(const ds::VictoriaParkData& data, const Config& cfg, const std::vector<char>& gps_valid,
                  FinalState* final_state = nullptr) {
  if (cfg.bias_states != "none") return runSlamWith<V, sylva::Ackermann2DWithBias>(data, cfg, gps_valid, final_state);
  return runSlamWith<V, sylva::Ackermann2D>(data, cfg, gps_valid, final_state);
}

}  // namespace victoria_park
