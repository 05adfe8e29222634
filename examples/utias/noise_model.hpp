#pragma once
// The example's one declared configuration: noise model, gates and the landmark rule, the
// same for all five robots (docs/examples/utias.md explains where each number comes from;
// `utias --noise-study` prints the statistics they are read off).
//
// Command delay. The commanded turn rate logged at t matches the true (Vicon) turn rate best
// at t + 0.15 to 0.2 s for every robot (RMS difference 0.06-0.10 rad/s, against 0.10-0.15
// rad/s without delay): the robots follow their commands late. Default 0.2 s.
//
// Commands. The odometry files hold velocity commands, not measured motion, and the robots
// slip, so the error of a command is modelled as white noise on [v, omega] whose spectral
// density grows with the commanded speed:
//
//   sqrt(q_v)     = k_v |v| + s_v          (m / sqrt(s))
//   sqrt(q_omega) = k_w |omega| + s_w      (rad / sqrt(s))
//
// Over one prediction of dt seconds the control noise handed to `Unicycle2D` (which holds it
// constant over dt) is Q = diag(q_v, q_omega) / dt: then the pose variance it adds is
// J_n Q J_n^T ~ q dt, the same over one long step as over many short ones (the data are
// stepped from event to event, dt from 0 to 1.4 s). Read off the data (--noise-study: the
// commands, delayed, integrated over 1 s from the true pose, all robots pooled): along track
// 1.2 cm standard deviation above 0.06 m/s (the top speed is 0.086 m/s; 0.2 cm when
// stopped), so k_v = 0.13, s_v = 0.002; heading 0.010 rad driving straight, 0.035 rad at
// 0.02-0.2 rad/s and 0.056 rad above 0.2 rad/s (mean about 0.1 and 0.35 rad/s), so
// k_w = 0.15, s_w = 0.01.
//
// Measurements. Robust spread (1.4826 MAD) of the residuals against the ground truth, all
// robots pooled: 0.127 m in range, 0.0091 rad in bearing, so 0.13 m and 0.01 rad; 6-8 % of
// the residuals lie beyond 3 robust sigmas (misdetections, partly seen tags), which a
// chi-square gate on the NIS (probability 0.999, NIS 13.8) keeps out of the filter.

#include <algorithm>
#include <cmath>

#include <sylva/core/types.hpp>
#include <sylva/noise/gaussian.hpp>

namespace utias {

using sylva::Vec;

struct NoiseConfig {
  double command_delay_s = 0.2;   ///< a command logged at t acts from t + delay on
  double v_gain = 1.04;            ///< the robot drives v_gain x the commanded speed ...
  double v_turn_loss = 0.092;       ///< ... less this x |omega| when driving (m/rad: wheel speed saturation)
  double omega_gain = 0.93;        ///< ... and turns omega_gain x the commanded turn rate ...
  double omega_bias = -0.002;        ///< ... plus this (rad/s)
  double v_scale = 0.26;          ///< k_v (1 / sqrt(s))
  double v_floor = 0.004;         ///< s_v (m / sqrt(s))
  double omega_scale = 0.30;      ///< k_w (1 / sqrt(s))
  double omega_floor = 0.02;     ///< s_w (rad / sqrt(s))
  double command_jitter_s = 0.2;  ///< timing uncertainty of a command change: adds |delta u| x this to the pose
  double sigma_range_m = 0.2;        ///< range sigma at zero range (m)
  double sigma_range_per_m = 0.2;    ///< ... plus this per metre of measured range
  double sigma_bearing_rad = 0.03;
  double landmark_interval_s = 0.0;  ///< fuse a landmark at most once per this many seconds (0: every reading)
  Vec<3> initial_sigma = Vec<3>(0.01, 0.01, 0.01);  ///< P0 around the first Vicon pose (m, m, rad)
  double outlier_gate_probability = 0.999;  ///< known ids: an observation with NIS above this chi2(2) quantile is rejected
  double jcbb_gate_probability = 0.99;      ///< individual and joint gates of JCBB
  double new_landmark_probability = 0.999999;  ///< JCBB: unpaired and NIS above this to every candidate -> new landmark
  double candidate_range_m = 10.0;       ///< JCBB candidates: predicted range below this ...
  double candidate_half_fov_rad = 0.8;   ///< ... and |bearing| below this (camera: +-0.6 rad)

  /// The control noise of one prediction over dt > 0 seconds with command u (see above).
  sylva::Gaussian<2> controlNoise(const Vec<2>& u, double dt) const {
    const double sv = v_scale * std::abs(u[0]) + v_floor;
    const double sw = omega_scale * std::abs(u[1]) + omega_floor;
    return sylva::Gaussian<2>::sigmas(Vec<2>(sv, sw) / std::sqrt(dt));
  }

  /// The motion a logged command produces (calibration of the commands, see above).
  Vec<2> effectiveCommand(const Vec<2>& logged) const {
    const double v = logged[0] > 0.0 ? std::max(0.0, v_gain * logged[0] - v_turn_loss * std::abs(logged[1])) : v_gain * logged[0];
    const bool stopped = logged[0] == 0.0 && logged[1] == 0.0;  // a stopped robot does not drift
    return Vec<2>(v, stopped ? 0.0 : omega_gain * logged[1] + omega_bias);
  }

  /// The noise of a reading at measured range `range_m`.
  sylva::Gaussian<2> measurementNoise(double range_m) const {
    return sylva::Gaussian<2>::sigmas(Vec<2>(sigma_range_m + sigma_range_per_m * range_m, sigma_bearing_rad));
  }
};

}  // namespace utias
