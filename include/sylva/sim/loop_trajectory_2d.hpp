#pragma once
/// @file
/// `sim::LoopTrajectory2D`: a `Unicycle2D` robot driving laps of a `LoopPath2D` at constant
/// speed, sampled every dt seconds, with noisy odometry.
///
/// Step k (k = 0, 1, ...) covers the arc from s_k = k v dt to s_(k+1). Its true control is
///
///   u_k = [v, (heading(s_(k+1)) - heading(s_k)) / dt]
///
/// and the true pose is propagated with the filter's own motion model (thesis eq. 2.12-2.14):
/// x_(k+1) = Unicycle2D(x_k, u_k, dt), starting at `startPose()` = [0, 0, 0]. The headings
/// match the path exactly at every step; the positions follow it up to the model's
/// mid-point approximation of each arc (below 1e-4 m per lap for the default corners).
/// The odometry the robot reports is the true control plus independent Gaussian noise,
///
///   odometry_k = u_k + [sigma_v n_1, sigma_omega n_2],   n_i ~ N(0, 1),
///
/// which is exactly the additive control noise `Ekf::predict` assumes (eq. 2.22).
///
/// The speed is adjusted by less than half a step per lap so that one lap takes a whole
/// number of steps (`stepsPerLap()`); `speed()` returns the value used.
///
/// Defaults: a 120 m loop (about 44.6 m x 22.3 m, corner radius 8 m) at 1 m/s, dt = 0.1 s,
/// and the odometry noise of Table 3.1 of the multisensor thesis (sigma_v = 0.5 cm/s,
/// sigma_omega = 0.025 deg/s).

#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

#include "sylva/core/angles.hpp"
#include "sylva/core/error.hpp"
#include "sylva/core/types.hpp"
#include "sylva/motion/unicycle_2d.hpp"
#include "sylva/noise/gaussian.hpp"
#include "sylva/sim/loop_path_2d.hpp"
#include "sylva/sim/random.hpp"

namespace sylva::sim {

struct LoopTrajectory2DOptions {
  double perimeter_m = 120.0;    ///< length of one lap
  double aspect = 2.0;           ///< length / width of the loop's bounding box, >= 1
  double corner_radius_m = 8.0;  ///< radius of the four rounded corners
  double speed_mps = 1.0;        ///< forward speed (adjusted slightly, see the file comment)
  double dt_s = 0.1;             ///< time step
  double sigma_v_mps = 0.005;    ///< odometry noise on v (Table 3.1: 0.5 cm/s)
  double sigma_omega_radps = 0.025 * kRadPerDeg;  ///< odometry noise on omega (0.025 deg/s)
};

/// One simulated step: the control applied during the step, the true pose at its end and
/// the noisy odometry the robot reports for it.
struct TrajectoryStep2D {
  double time_s;        ///< time at the end of the step
  Vec<2> true_control;  ///< [v, omega]
  Vec<3> true_pose;     ///< [x, y, theta] at time_s
  Vec<2> odometry;      ///< true_control + noise
};

class LoopTrajectory2D {
 public:
  explicit LoopTrajectory2D(const LoopTrajectory2DOptions& options = {})
      : options_(validated(options)),
        path_(LoopPath2D::withPerimeter(
            options.perimeter_m, options.aspect, options.corner_radius_m)),
        odometry_noise_(
            Gaussian<2>::sigmas(Vec<2>(options.sigma_v_mps, options.sigma_omega_radps))) {
    const double step_length = options_.speed_mps * options_.dt_s;
    steps_per_lap_ = std::max(1, static_cast<int>(std::lround(path_.perimeter() / step_length)));
    step_length_ = path_.perimeter() / steps_per_lap_;
  }

  const LoopTrajectory2DOptions& options() const { return options_; }
  const LoopPath2D& path() const { return path_; }
  double dt() const { return options_.dt_s; }
  /// The speed actually driven (m/s): the requested one, adjusted so a lap is whole steps.
  double speed() const { return step_length_ / options_.dt_s; }
  int stepsPerLap() const { return steps_per_lap_; }
  Vec<3> startPose() const { return Vec<3>(0.0, 0.0, 0.0); }
  /// The odometry noise as the filter's `predict` takes it.
  const Gaussian<2>& odometryNoise() const { return odometry_noise_; }

  /// The true (noise-free) control of step k.
  Vec<2> trueControl(int k) const {
    const double s0 = k * step_length_;
    const double s1 = (k + 1) * step_length_;
    return Vec<2>(speed(), (path_.heading(s1) - path_.heading(s0)) / options_.dt_s);
  }

  /// `steps` steps from the start pose, drawing the odometry noise from `rng` (two normal
  /// draws per step: v then omega). Throws kInvalidArgument for steps <= 0.
  std::vector<TrajectoryStep2D> simulate(int steps, Rng& rng) const {
    if (steps <= 0) {
      std::ostringstream os;
      os << "LoopTrajectory2D::simulate: the number of steps must be > 0, got " << steps;
      fail(ErrorCode::kInvalidArgument, os.str());
    }
    std::vector<TrajectoryStep2D> out;
    out.reserve(static_cast<std::size_t>(steps));
    const Unicycle2D robot;
    Vec<3> pose = startPose();
    for (int k = 0; k < steps; ++k) {
      const Vec<2> u = trueControl(k);
      pose = robot(pose, u, options_.dt_s);
      Vec<2> odometry;
      odometry[0] = u[0] + options_.sigma_v_mps * rng.normal();
      odometry[1] = u[1] + options_.sigma_omega_radps * rng.normal();
      out.push_back(TrajectoryStep2D{(k + 1) * options_.dt_s, u, pose, odometry});
    }
    return out;
  }

  /// One lap.
  std::vector<TrajectoryStep2D> simulate(Rng& rng) const { return simulate(steps_per_lap_, rng); }

 private:
  static LoopTrajectory2DOptions validated(const LoopTrajectory2DOptions& o) {
    auto positive = [](double value, const char* name, const char* unit) {
      if (!std::isfinite(value) || !(value > 0.0)) {
        std::ostringstream os;
        os << "LoopTrajectory2D: " << name << " must be finite and > 0, got " << value << " "
           << unit;
        fail(ErrorCode::kInvalidArgument, os.str());
      }
    };
    positive(o.speed_mps, "speed", "m/s");
    positive(o.dt_s, "dt", "s");
    positive(o.sigma_v_mps, "sigma_v", "m/s");
    positive(o.sigma_omega_radps, "sigma_omega", "rad/s");
    // perimeter, aspect and corner radius are checked by LoopPath2D::withPerimeter.
    return o;
  }

  LoopTrajectory2DOptions options_;
  LoopPath2D path_;
  Gaussian<2> odometry_noise_;
  int steps_per_lap_ = 1;
  double step_length_ = 0.0;
};

}  // namespace sylva::sim
