#pragma once
// The example's one declared configuration: noise model, gates and the landmark rule, the
// same for all five robots (docs/examples/utias.md explains where each number comes from;
// `utias --noise-study` prints the statistics they are read off).
//
// Commands. The odometry files hold velocity commands, not measured motion, and the robots
// slip, so the error of a command is modelled as white noise on [v, omega] whose spectral
// density grows with the commanded speed:
//
//   sqrt(q_v)     = k_v |v| + s_v          (m/s per sqrt(Hz), i.e. m / sqrt(s))
//   sqrt(q_omega) = k_w |omega| + s_w      (rad / sqrt(s))
//
// Over one prediction of dt seconds the control noise handed to `Unicycle2D` (which holds it
// constant over dt) is Q = diag(q_v, q_omega) / dt: then the pose variance it adds is
// J_n Q J_n^T ~ q dt, the same over one long step as over many short ones (the data are
// stepped from event to event, dt from 0 to 1.4 s). Read off the data: the error of the
// commands integrated over 1 s from the true pose has a standard deviation of about 1.3 cm
// along track at full speed (0.086 m/s: 15 % of the distance) and a heading error that grows
// from 0.6 deg driving straight to about 5 deg at 0.3 rad/s.
//
// Measurements. Robust spread (1.4826 MAD) of the residuals against the ground truth, all
// robots pooled: 0.13 m in range, 0.009 rad in bearing; 6-8 % of the residuals lie beyond 3
// robust sigmas (misdetections, partly seen tags), which a chi-square gate on the NIS keeps
// out of the filter.

#include <cmath>

#include <sylva/core/types.hpp>
#include <sylva/noise/gaussian.hpp>

namespace utias {

using sylva::Vec;

struct NoiseConfig {
  double command_delay_s = 0.2;   ///< a command logged at t acts from t + delay on
  double v_scale = 0.15;          ///< k_v (1 / sqrt(s))
  double v_floor = 0.003;         ///< s_v (m / sqrt(s))
  double omega_scale = 0.25;      ///< k_w (1 / sqrt(s))
  double omega_floor = 0.015;     ///< s_w (rad / sqrt(s))
  double sigma_range_m = 0.13;
  double sigma_bearing_rad = 0.01;
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

  sylva::Gaussian<2> measurementNoise() const {
    return sylva::Gaussian<2>::sigmas(Vec<2>(sigma_range_m, sigma_bearing_rad));
  }
};

}  // namespace utias
