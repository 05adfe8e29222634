#pragma once
/// @file
/// `sylva_bench::CircleWorld`: the shared, deterministic 2D range-bearing SLAM scenario of the
/// benchmarks (bench/peers/ compares sylva with MRPT on it; sylva's own step benchmark uses it
/// over the map size N). Header-only, needs only sylva (Eigen) and the standard library.
///
/// The world
///   - A robot drives laps of a circle of radius R counter-clockwise, at constant speed, in
///     `steps_per_lap` equal steps. It starts at the origin of the map frame with heading 0
///     (so the filter's initial pose [0, 0, 0] with zero covariance is exact); the circle's
///     centre is (0, R). Pose k (k = 0, 1, ...) is at angle k * 2 pi / steps_per_lap on the
///     circle.
///   - N point landmarks, uniform in area over the annulus of the points within `band_m` of
///     the circle (a disc when R < band_m). Landmark i has id i (0 <= i < N).
///   - The sensor sees landmarks with min_range_m <= range <= max_range_m and
///     |bearing| <= field_of_view_rad / 2 (bearing from the robot's heading).
///   - R is chosen for the landmark density at which the expected number of landmarks in the
///     sensor's footprint is `visible_per_step` (12 by default) whatever N is: the circle
///     grows with N. (The footprint is integrated numerically, curvature included, and R is
///     found by bisection.) `meanMeasurementsPerStep()` reports what was actually drawn.
///   - With the default band (8 m < max range 10 m), full field of view and 2 m steps every
///     landmark is seen within the first lap (`landmarksUnseenInFirstLap()` is 0), so lap 1
///     builds the whole map (state dimension 3 + 2N) and lap 2 only re-observes it.
///
/// The steps (what both filters consume, identically)
///   Step 0: no motion (`has_motion` false; the odometry is zero); the robot observes from
///   the start pose. Step k >= 1: the robot moves from pose k-1 to pose k, then observes.
///   `Step::odometry` is the measured increment [dx, dy, dtheta] in the frame of pose k-1:
///   the true chord of the circle plus Gaussian noise with `odometryNoise()`, which is the
///   noise model of `sylva::Odometry2D` and of MRPT's CActionRobotMovement2D with a
///   CPosePDFGaussian pose change. `Step::measurements` holds (id, range, bearing) for every
///   landmark in view at pose k, in ascending id, with Gaussian noise `measurementNoise()`;
///   the bearing is wrapped to (-pi, pi].
///   `unicycleControl()` is the noise-free [v, omega] over `dt_s` that moves a
///   `sylva::Unicycle2D` along the same chord, for benchmarks that prefer that robot.
///
/// Laps: steps [0, S) are lap 1 (map building), [S, 2S) lap 2 (the timed part of the
/// benchmarks), S = stepsPerLap(); `lapBegin(lap)` gives the first step of a 0-based lap.
///
/// Reproducibility: everything is drawn from `sylva::sim::Rng` streams derived from `seed`
/// (landmarks, odometry noise, measurement noise: one stream each), so a configuration gives
/// bit-identical steps on every platform. With `float_measurements` (default on) every range
/// and bearing is rounded to float, the precision of MRPT's CObservationBearingRange, so that
/// a double-precision filter and MRPT read exactly the same numbers (the rounding, about
/// 1e-7 relative, is far below the noise).
///
/// Usage:
///   sylva_bench::CircleWorldConfig config;
///   config.landmarks = 1000;
///   const sylva_bench::CircleWorld world(config);
///   for (const sylva_bench::Step& step : world.steps()) {
///     if (step.has_motion) { /* predict with step.odometry, world.odometryNoise() */ }
///     for (const sylva_bench::Measurement& m : step.measurements) { /* m.id, m.range_m, m.bearing_rad */ }
///   }

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <string>
#include <vector>

#include "sylva/core/angles.hpp"
#include "sylva/core/error.hpp"
#include "sylva/core/types.hpp"
#include "sylva/noise/gaussian.hpp"
#include "sylva/sim/random.hpp"

namespace sylva_bench {

/// Parameters of the circle world; the defaults are the benchmark's scenario.
struct CircleWorldConfig {
  int landmarks = 1000;            ///< N
  double visible_per_step = 12.0;  ///< expected landmarks in view per step (sets R)
  double max_range_m = 10.0;
  double min_range_m = 1.0;
  double field_of_view_rad = 2.0 * sylva::kPi;  ///< full angle, centred on the heading
  double band_m = 8.0;   ///< landmarks lie within this distance of the circle
  double step_m = 2.0;   ///< nominal arc length of a step (rounded to a whole lap)
  double dt_s = 1.0;     ///< duration of a step, for models with a time step
  int laps = 2;
  /// Standard deviations of the odometry increment [dx (m), dy (m), dtheta (rad)] per step:
  /// 0.5 % of the distance and 0.005 degrees (gyro-aided odometry). With noisier headings the
  /// drift over the long laps of large N (2.9 km at N = 2000) grows to metres, the EKF's loop
  /// closure turns inconsistent and MRPT's prediction window (1.5 m beyond the sensor range)
  /// misses landmarks; with these values the worst predicted-range error stays under 1 m up
  /// to N = 2000.
  sylva::Vec<3> odometry_sigma = sylva::Vec<3>(0.01, 0.005, 0.005 * sylva::kPi / 180.0);
  /// Measurement noise (3.1 cm, 0.11 degrees); powers of two so that they and their squares
  /// are exact in float (MRPT keeps these two numbers as float).
  double range_sigma_m = 0.03125;
  double bearing_sigma_rad = 0.001953125;
  bool float_measurements = true;  ///< round ranges and bearings to float (see the file comment)
  std::uint64_t seed = 0x51'7A'C1'2C'1E'00'00'01ULL;
};

/// One range-bearing measurement of landmark `id`.
struct Measurement {
  sylva::Id id;
  double range_m;
  double bearing_rad;  ///< from the robot's heading, counter-clockwise, in (-pi, pi]
  sylva::Vec<2> z() const { return sylva::Vec<2>(range_m, bearing_rad); }
};

/// One step: optional motion, then the measurements at the new pose.
struct Step {
  int index = 0;
  int lap = 0;                 ///< 0-based lap
  bool has_motion = false;     ///< false only for step 0
  sylva::Vec<3> odometry = sylva::Vec<3>::Zero();        ///< measured [dx, dy, dtheta]
  sylva::Vec<3> true_increment = sylva::Vec<3>::Zero();  ///< noise-free [dx, dy, dtheta]
  sylva::Vec<3> true_pose = sylva::Vec<3>::Zero();       ///< [x, y, theta] after the motion
  std::vector<Measurement> measurements;                  ///< ascending id
};

class CircleWorld {
 public:
  explicit CircleWorld(const CircleWorldConfig& config) : config_(config) {
    validate();
    radius_m_ = solveRadius();
    const double circumference = 2.0 * sylva::kPi * radius_m_;
    steps_per_lap_ = std::max(8, static_cast<int>(std::lround(circumference / config_.step_m)));
    placeLandmarks();
    simulate();
  }

  const CircleWorldConfig& config() const { return config_; }
  int landmarkCount() const { return config_.landmarks; }
  double radiusM() const { return radius_m_; }
  int stepsPerLap() const { return steps_per_lap_; }
  /// Arc length actually driven per step (step_m rounded to a whole number of steps per lap).
  double stepLengthM() const { return 2.0 * sylva::kPi * radius_m_ / steps_per_lap_; }
  /// First step of 0-based lap `lap` (lapBegin(1) is the first timed step).
  int lapBegin(int lap) const { return lap * steps_per_lap_; }

  /// True landmark positions in the map frame; index = id.
  const std::vector<sylva::Vec<2>>& landmarks() const { return landmarks_; }
  /// All steps of all laps, in order; steps()[k].index == k.
  const std::vector<Step>& steps() const { return steps_; }

  /// The filter's initial robot pose (exact: the map frame is the start pose).
  sylva::Vec<3> initialPose() const { return sylva::Vec<3>::Zero(); }
  /// Noise of the odometry increment [dx, dy, dtheta] (additive, robot frame).
  sylva::Gaussian<3> odometryNoise() const { return sylva::Gaussian<3>::sigmas(config_.odometry_sigma); }
  /// Noise of a [range, bearing] measurement.
  sylva::Gaussian<2> measurementNoise() const {
    return sylva::Gaussian<2>::sigmas(sylva::Vec<2>(config_.range_sigma_m, config_.bearing_sigma_rad));
  }
  /// Noise-free unicycle control [v (m/s), omega (rad/s)] over dt_s that drives the same chord
  /// as one step (`sylva::Unicycle2D`'s mid-point heading makes it exact).
  sylva::Vec<2> unicycleControl() const {
    const double delta = 2.0 * sylva::kPi / steps_per_lap_;
    const double chord = 2.0 * radius_m_ * std::sin(0.5 * delta);
    return sylva::Vec<2>(chord / config_.dt_s, delta / config_.dt_s);
  }

  /// Mean number of measurements per step over 0-based lap `lap`.
  double meanMeasurementsPerStep(int lap) const {
    std::size_t total = 0;
    for (int k = lapBegin(lap); k < lapBegin(lap + 1); ++k) total += steps_[k].measurements.size();
    return static_cast<double>(total) / steps_per_lap_;
  }
  /// Largest number of measurements in one step.
  int maxMeasurementsPerStep() const {
    std::size_t most = 0;
    for (const Step& s : steps_) most = std::max(most, s.measurements.size());
    return static_cast<int>(most);
  }
  /// Landmarks that no step of lap 1 measures (0 for the default configuration).
  int landmarksUnseenInFirstLap() const {
    std::vector<char> seen(landmarks_.size(), 0);
    for (int k = 0; k < steps_per_lap_; ++k)
      for (const Measurement& m : steps_[k].measurements) seen[static_cast<std::size_t>(m.id)] = 1;
    return static_cast<int>(std::count(seen.begin(), seen.end(), 0));
  }

  /// Expected number of landmarks in view for a circle of radius `radius_m` (the function
  /// whose root at `visible_per_step` sets R).
  double expectedVisible(double radius_m) const {
    return config_.landmarks * footprintAreaInWorld(radius_m) / worldArea(radius_m);
  }

 private:
  void validate() const {
    const CircleWorldConfig& c = config_;
    std::ostringstream os;
    if (c.landmarks < 1) os << "landmarks = " << c.landmarks << " must be >= 1; ";
    if (!(c.visible_per_step > 0.0)) os << "visible_per_step must be > 0; ";
    if (!(c.min_range_m >= 0.0 && c.max_range_m > c.min_range_m))
      os << "need 0 <= min_range_m < max_range_m; ";
    if (!(c.field_of_view_rad > 0.0 && c.field_of_view_rad <= 2.0 * sylva::kPi))
      os << "field_of_view_rad must be in (0, 2 pi]; ";
    if (!(c.band_m > 0.0)) os << "band_m must be > 0; ";
    if (!(c.step_m > 0.0)) os << "step_m must be > 0; ";
    if (!(c.dt_s > 0.0)) os << "dt_s must be > 0; ";
    if (c.laps < 1) os << "laps must be >= 1; ";
    if (!(c.odometry_sigma.minCoeff() > 0.0) || !(c.range_sigma_m > 0.0) || !(c.bearing_sigma_rad > 0.0))
      os << "noise sigmas must be > 0; ";
    if (!os.str().empty()) sylva::fail(sylva::ErrorCode::kInvalidArgument, "CircleWorld: " + os.str());
  }

  double innerRadius(double radius_m) const { return std::max(0.0, radius_m - config_.band_m); }
  double outerRadius(double radius_m) const { return radius_m + config_.band_m; }
  double worldArea(double radius_m) const {
    const double a = innerRadius(radius_m);
    const double b = outerRadius(radius_m);
    return sylva::kPi * (b * b - a * a);
  }

  /// Area of the sensor's footprint that lies in the landmark annulus, for the robot on the
  /// circle (the same at every pose by symmetry): midpoint rule in polar coordinates around
  /// the robot.
  double footprintAreaInWorld(double radius_m) const {
    constexpr int kRangeCells = 200;
    constexpr int kBearingCells = 720;
    const double r0 = config_.min_range_m;
    const double dr = (config_.max_range_m - r0) / kRangeCells;
    const double db = config_.field_of_view_rad / kBearingCells;
    const double inner2 = innerRadius(radius_m) * innerRadius(radius_m);
    const double outer2 = outerRadius(radius_m) * outerRadius(radius_m);
    // Robot at the circle point closest to the origin of a centred frame: (0, -R), heading +x.
    double area = 0.0;
    for (int j = 0; j < kBearingCells; ++j) {
      const double bearing = -0.5 * config_.field_of_view_rad + (j + 0.5) * db;
      const double c = std::cos(bearing);
      const double s = std::sin(bearing);
      for (int i = 0; i < kRangeCells; ++i) {
        const double r = r0 + (i + 0.5) * dr;
        const double x = r * c;
        const double y = -radius_m + r * s;
        const double d2 = x * x + y * y;
        if (d2 >= inner2 && d2 <= outer2) area += r * dr * db;
      }
    }
    return area;
  }

  /// R such that expectedVisible(R) = visible_per_step (bisection; the expectation falls as
  /// the circle grows).
  double solveRadius() const {
    double lo = 1e-3;
    double hi = 1.0;
    if (expectedVisible(lo) < config_.visible_per_step) {
      std::ostringstream os;
      os << "CircleWorld: " << config_.landmarks << " landmarks cannot give "
         << config_.visible_per_step << " in view per step with this sensor (at most about "
         << expectedVisible(lo) << ")";
      sylva::fail(sylva::ErrorCode::kInvalidArgument, os.str());
    }
    while (expectedVisible(hi) > config_.visible_per_step) hi *= 2.0;
    for (int it = 0; it < 100 && hi - lo > 1e-9 * hi; ++it) {
      const double mid = 0.5 * (lo + hi);
      (expectedVisible(mid) > config_.visible_per_step ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
  }

  void placeLandmarks() {
    sylva::sim::Rng rng(sylva::sim::deriveSeed(config_.seed, 0));
    const double a2 = innerRadius(radius_m_) * innerRadius(radius_m_);
    const double b2 = outerRadius(radius_m_) * outerRadius(radius_m_);
    landmarks_.reserve(static_cast<std::size_t>(config_.landmarks));
    for (int i = 0; i < config_.landmarks; ++i) {
      const double r = std::sqrt(a2 + rng.uniform01() * (b2 - a2));  // uniform in area
      const double angle = 2.0 * sylva::kPi * rng.uniform01();
      landmarks_.emplace_back(r * std::cos(angle), radius_m_ + r * std::sin(angle));
    }
  }

  sylva::Vec<3> truePose(int k) const {
    const double delta = 2.0 * sylva::kPi / steps_per_lap_;
    const double phi = k * delta;  // angle travelled along the circle
    return sylva::Vec<3>(radius_m_ * std::sin(phi), radius_m_ * (1.0 - std::cos(phi)), sylva::wrapAngle(phi));
  }

  /// Rounds to float when asked; a bearing is kept in (-pi, pi] after rounding.
  double quantize(double value, bool is_bearing) const {
    if (!config_.float_measurements) return value;
    float f = static_cast<float>(value);
    if (is_bearing) {
      if (static_cast<double>(f) > sylva::kPi) f = std::nextafter(f, 0.0f);
      if (static_cast<double>(f) <= -sylva::kPi) f = std::nextafter(f, 0.0f);
    }
    return static_cast<double>(f);
  }

  void simulate() {
    sylva::sim::Rng odometry_rng(sylva::sim::deriveSeed(config_.seed, 1));
    sylva::sim::Rng measurement_rng(sylva::sim::deriveSeed(config_.seed, 2));
    const sylva::Gaussian<3> odometry_noise = odometryNoise();
    const double delta = 2.0 * sylva::kPi / steps_per_lap_;
    const sylva::Vec<3> chord(radius_m_ * std::sin(delta), radius_m_ * (1.0 - std::cos(delta)), delta);
    const double half_fov = 0.5 * config_.field_of_view_rad;
    const int total = config_.laps * steps_per_lap_;
    steps_.resize(static_cast<std::size_t>(total));
    for (int k = 0; k < total; ++k) {
      Step& step = steps_[static_cast<std::size_t>(k)];
      step.index = k;
      step.lap = k / steps_per_lap_;
      step.has_motion = k > 0;
      if (step.has_motion) {
        step.true_increment = chord;
        step.odometry = chord + odometry_rng.sample(odometry_noise);
      }
      step.true_pose = truePose(k);
      const sylva::Vec<3>& x = step.true_pose;
      for (int i = 0; i < config_.landmarks; ++i) {
        const sylva::Vec<2> d = landmarks_[static_cast<std::size_t>(i)] - x.head<2>();
        const double range = d.norm();
        const double bearing = sylva::wrapAngle(std::atan2(d[1], d[0]) - x[2]);
        if (range < config_.min_range_m || range > config_.max_range_m || std::abs(bearing) > half_fov)
          continue;
        const double noisy_range = range + config_.range_sigma_m * measurement_rng.normal();
        const double noisy_bearing = sylva::wrapAngle(bearing + config_.bearing_sigma_rad * measurement_rng.normal());
        step.measurements.push_back(
            Measurement{static_cast<sylva::Id>(i), quantize(noisy_range, false), quantize(noisy_bearing, true)});
      }
    }
  }

  CircleWorldConfig config_;
  double radius_m_ = 0.0;
  int steps_per_lap_ = 0;
  std::vector<sylva::Vec<2>> landmarks_;
  std::vector<Step> steps_;
};

}  // namespace sylva_bench
