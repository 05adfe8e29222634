#pragma once
// One simulated parking attempt: the camera takes a frame, the controller turns it into a
// command, the robot follows the command until the next frame, and so on until the
// controller stops (parked or station lost), the robot bumps into the station, or time runs
// out.
//
// Robot (eq. 5.2): the unicycle x' = v cos(theta), y' = v sin(theta), theta' = omega,
// integrated with sylva::Unicycle2D (eq. 2.12-2.14 of the same thesis: the same model,
// discretized at the mid-point heading) in `substeps` steps per frame. The wheels do not
// follow a command at once: v and omega move towards it at most at max_accel_mps2 and
// max_alpha_radps2 (the default acceleration limits of a Pioneer 3-AT base; the thesis' Fig.
// 5.12-5.14 (d, e) show commanded and actual velocities apart). Zero limits mean "follow at
// once". After Stop the robot brakes to rest; the final pose is where it comes to rest.
// It bumps into the station when its centre comes closer than front_m to the line y = 0.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>
#include <vector>

#include <sylva/core/angles.hpp>
#include <sylva/motion/unicycle_2d.hpp>
#include <sylva/parking/hybrid_controller.hpp>
#include <sylva/sim/random.hpp>

#include "station_camera.hpp"

namespace parking {

using namespace sylva::parking;  // the hybrid controller (include/sylva/parking)
using sylva::kRadPerDeg;
using sylva::parking::toString;  // of State and Event, beside toString(Outcome) below

struct RobotParams {
  double max_accel_mps2 = 0.3;                ///< Pioneer 3-AT default, 300 mm/s^2
  double max_alpha_radps2 = 100 * kRadPerDeg;  ///< Pioneer 3-AT default, 100 deg/s^2
  int substeps = 10;                          ///< integration steps per frame
  double front_m = 0.0;  ///< bump check: closest allowed approach to the station line (0: off)

  void validate() const {
    const auto check = [](const char* name, double v, bool allow_zero) {
      if (!std::isfinite(v)) {
        std::ostringstream os;
        os << "robot: " << name << " must be finite, got " << v;
        sylva::fail(sylva::ErrorCode::kNonFinite, os.str());
      }
      if (v < 0.0 || (!allow_zero && v == 0.0)) {
        std::ostringstream os;
        os << "robot: " << name << " must be " << (allow_zero ? ">= 0" : "> 0") << ", got " << v;
        sylva::fail(sylva::ErrorCode::kInvalidArgument, os.str());
      }
    };
    check("max_accel_mps2", max_accel_mps2, true);
    check("max_alpha_radps2", max_alpha_radps2, true);
    check("front_m", front_m, true);
    if (substeps < 1 || substeps > 1000) {
      std::ostringstream os;
      os << "robot: substeps must be in [1, 1000], got " << substeps;
      sylva::fail(sylva::ErrorCode::kInvalidArgument, os.str());
    }
  }
};

enum class Outcome { kParked, kStationLost, kCollided, kTimedOut };

inline const char* toString(Outcome o) {
  switch (o) {
    case Outcome::kParked:
      return "parked";
    case Outcome::kStationLost:
      return "station lost";
    case Outcome::kCollided:
      return "bumped into the station";
    case Outcome::kTimedOut:
      return "timed out";
  }
  return "?";
}

/// One frame of a recorded episode.
struct Sample {
  double t_s = 0.0;
  Pose pose = Pose::Zero();
  std::array<double, 3> u_px{};         ///< measured u1..u3 (NaN where not seen)
  double v_cmd = 0.0, omega_cmd = 0.0;  ///< the command of this frame
  double v = 0.0, omega = 0.0;          ///< the robot's actual velocities at the frame
  State state = State::kStart;
  double c_px = 0.0;
  bool holds_right = false;  ///< Forward: P3 held at the right virtual edge (else P1 left)
};

struct EpisodeResult {
  Outcome outcome = Outcome::kTimedOut;
  double time_s = 0.0;  ///< time of the last frame (the Stop command when parked)
  Pose start = Pose::Zero();
  Pose final_pose = Pose::Zero();  ///< at rest
  Pose goal = Pose::Zero();
  Pose error = Pose::Zero();  ///< final - goal, heading wrapped
  int cycles = 0;             ///< forward-reverse cycles: the number of reverse moves
  int forward_moves = 0;
  int reverse_moves = 0;
  long frames = 0;
  double min_station_distance_m = 0.0;  ///< closest the robot centre came to the line y = 0
  std::vector<Transition> transitions;
  std::vector<Pose> transition_poses;  ///< the robot's pose at each transition's frame
  std::vector<Sample> samples;         ///< filled when asked for
};

struct EpisodeOptions {
  double max_time_s = 300.0;
  bool record = false;
};

namespace detail {

inline double approach(double value, double target, double max_step) {
  if (max_step <= 0.0) return target;
  return value + std::clamp(target - value, -max_step, max_step);
}

}  // namespace detail

/// Runs one parking attempt from `start`; the pixel noise comes from `seed` alone, so the
/// same arguments give the same result bit for bit.
inline EpisodeResult runEpisode(const StationCamera& camera,
                                const ControllerParams& controller_params,
                                const RobotParams& robot,
                                const Pose& start,
                                std::uint64_t seed,
                                const EpisodeOptions& options = {}) {
  robot.validate();
  if (!start.allFinite())
    sylva::fail(sylva::ErrorCode::kNonFinite, "episode: the start pose must be finite");
  if (!(options.max_time_s > 0.0) || !std::isfinite(options.max_time_s))
    sylva::fail(sylva::ErrorCode::kInvalidArgument, "episode: max_time_s must be finite and > 0");
  if (camera.params().image_width_px != controller_params.image_width_px)
    sylva::fail(sylva::ErrorCode::kInvalidArgument,
                "episode: the controller's image width differs from the camera's");

  HybridController controller(controller_params);
  sylva::sim::Rng rng(seed);
  const sylva::Unicycle2D unicycle;
  const double dt = 1.0 / camera.params().frame_rate_hz;
  const double h = dt / robot.substeps;

  EpisodeResult r;
  r.start = start;
  r.goal = camera.goalPose(controller_params.reference_px);
  Pose x = start;
  x[2] = sylva::wrapAngle(x[2]);
  double v = 0.0, omega = 0.0;
  r.min_station_distance_m = -x[1];
  const long max_frames = static_cast<long>(std::ceil(options.max_time_s / dt));
  bool collided = false;

  const auto drive = [&](double v_cmd, double omega_cmd) {
    for (int s = 0; s < robot.substeps; ++s) {
      v = detail::approach(v, v_cmd, robot.max_accel_mps2 * h);
      omega = detail::approach(omega, omega_cmd, robot.max_alpha_radps2 * h);
      x = unicycle(x, sylva::Vec<2>(v, omega), h);
      r.min_station_distance_m = std::min(r.min_station_distance_m, -x[1]);
      if (robot.front_m > 0.0 && -x[1] < robot.front_m) collided = true;
    }
  };

  for (long k = 0;; ++k) {
    const double t = static_cast<double>(k) * dt;
    const std::vector<double> z = camera.observe(x, rng);
    const Command cmd = controller.step(z);
    while (r.transition_poses.size() < controller.transitions().size())
      r.transition_poses.push_back(x);
    if (options.record) {
      Sample s;
      s.t_s = t;
      s.pose = x;
      const StationView truth = camera.view(x);
      std::size_t next = 0;
      for (std::size_t i = 0; i < 3; ++i)
        s.u_px[i] = truth.visible[i] && next < z.size() ? z[next++]
                                                        : std::numeric_limits<double>::quiet_NaN();
      s.v_cmd = cmd.v_mps;
      s.omega_cmd = cmd.omega_radps;
      s.v = v;
      s.omega = omega;
      s.state = cmd.state;
      s.c_px = controller.virtualEdgePx();
      s.holds_right = controller.holdsRightFeature();
      r.samples.push_back(s);
    }
    r.time_s = t;
    r.frames = k + 1;
    if (controller.isTerminal()) {
      r.outcome = controller.state() == State::kStop ? Outcome::kParked : Outcome::kStationLost;
      break;
    }
    if (k >= max_frames) {
      r.outcome = Outcome::kTimedOut;
      break;
    }
    drive(cmd.v_mps, cmd.omega_radps);
    if (collided) {
      r.outcome = Outcome::kCollided;
      r.time_s = t + dt;
      break;
    }
  }
  // Brake to rest (a few frames at most with the default limits).
  for (int k = 0; k < 1000 && (v != 0.0 || omega != 0.0); ++k) drive(0.0, 0.0);

  r.final_pose = x;
  r.error = sylva::Unicycle2D::difference(x, r.goal);
  r.forward_moves = controller.forwardMoves();
  r.reverse_moves = controller.reverseMoves();
  r.cycles = r.reverse_moves;
  r.transitions = controller.transitions();
  return r;
}

}  // namespace parking
