#pragma once
// Everything of the UTIAS configuration that is fitted to ground truth, as one procedure that
// can be run on any set of robots: `utias --leave-one-out` runs it on four robots and scores
// the fifth; run on all five it gives the default of noise_model.hpp.
//
//   1. Command delay: the lag in {0, 0.05, ..., 0.4} s at which the logged turn-rate command
//      best matches the Vicon turn rate, RMS pooled over the robots (residuals.hpp,
//      turnRateLagSums); a tie goes to the shorter lag.
//   2. Command calibration at that delay: the least squares of residuals.hpp
//      (commandCalibration over 1 s windows), the normal equations pooled over the robots,
//      each value rounded to 4 decimals (the precision --noise-study prints and
//      noise_model.hpp writes). With online gains the calibration is the prior mean of the
//      gains the filter estimates from the robot's own data, and the spread of the robots'
//      own calibrations (largest minus smallest, each robot fitted alone) their prior sigma.
//   3. Noise setting: the known-correspondence run of every robot for each of the 36
//      settings of the grid (selection.hpp) with that delay and calibration, and the declared
//      rule of selection.hpp (most targets met, then the largest smallest margin).
// Not fitted here (set once from all five robots of Dataset 7, see noise_model.hpp): the grid
// itself and its base values, the command jitter, the initial covariance, the gates and
// JCBB's noise scale.

#include <cmath>
#include <limits>
#include <vector>

#include <sylva/core/error.hpp>
#include <sylva/datasets/utias_mrclam.hpp>

#include "evaluation.hpp"
#include "ground_truth.hpp"
#include "residuals.hpp"
#include "selection.hpp"
#include "slam_run.hpp"

namespace utias {

using RobotSet = std::vector<const sylva::datasets::UtiasRobotData*>;

/// The fitted command model: delay and calibration.
struct CommandFit {
  double delay_s = 0.0;
  double v_gain = 1.0;
  double v_turn_loss = 0.0;  ///< m/rad
  double omega_gain = 1.0;
  double omega_bias = 0.0;  ///< rad/s
  long windows = 0;         ///< 1 s windows behind the calibration
  /// The spread (largest minus smallest) of [v_gain, omega_gain, omega_bias] calibrated on
  /// each robot alone at the pooled delay; zero for one robot. With online gains it is the
  /// prior sigma of the gains: how much one robot differs from the pooled calibration.
  Vec<3> spread = Vec<3>::Zero();
};

inline double roundTo4(double v) { return std::round(v * 1e4) / 1e4; }

/// Steps 1 and 2 of the file comment on `robots` (at least one).
inline CommandFit fitCommandModel(const RobotSet& robots, double window_s = 1.0) {
  if (robots.empty()) sylva::fail(sylva::ErrorCode::kInvalidArgument, "fitCommandModel: no robots");
  if (!(window_s > 0.0))
    sylva::fail(sylva::ErrorCode::kInvalidArgument, "fitCommandModel: the window must be > 0 s");
  CommandFit fit;
  double best = std::numeric_limits<double>::infinity();
  for (int ms = 0; ms <= 400; ms += 50) {
    TurnRateLagSums pooled;
    for (const auto* r : robots) pooled.add(turnRateLagSums(*r, ms / 1000.0));
    if (pooled.count > 0 && pooled.rms() < best) {
      best = pooled.rms();
      fit.delay_s = ms / 1000.0;
    }
  }
  CommandCalibration pooled;
  for (const auto* r : robots) pooled.add(commandCalibration(*r, window_s, fit.delay_s));
  if (pooled.windows == 0)
    sylva::fail(sylva::ErrorCode::kInvalidArgument,
                "fitCommandModel: no window of commands with ground truth");
  const Eigen::Vector2d turn = pooled.turn(window_s), distance = pooled.distance();
  fit.omega_gain = roundTo4(turn[0]);
  fit.omega_bias = roundTo4(turn[1]);
  fit.v_gain = roundTo4(distance[0]);
  fit.v_turn_loss = roundTo4(distance[1]);
  fit.windows = pooled.windows;
  if (robots.size() >= 2) {
    Vec<3> lowest = Vec<3>::Constant(std::numeric_limits<double>::infinity());
    Vec<3> highest = -lowest;
    for (const auto* r : robots) {
      const CommandCalibration own = commandCalibration(*r, window_s, fit.delay_s);
      if (own.windows == 0) continue;
      const Eigen::Vector2d t = own.turn(window_s), d = own.distance();
      const Vec<3> values(d[0], t[0], t[1]);
      lowest = lowest.cwiseMin(values);
      highest = highest.cwiseMax(values);
    }
    if (lowest.allFinite()) fit.spread = Vec<3>(roundTo4(highest[0] - lowest[0]), roundTo4(highest[1] - lowest[1]),
                                                roundTo4(highest[2] - lowest[2]));
  }
  return fit;
}

/// `base` with the fitted delay and calibration. With online gains (base.online_gains) the
/// calibration is the prior mean of the gains the filter estimates, and the spread of the
/// robots' own calibrations (when the fit saw two robots or more) their prior sigma, with a
/// floor of 1e-4.
inline NoiseConfig withCommandFit(NoiseConfig base, const CommandFit& fit) {
  base.command_delay_s = fit.delay_s;
  base.v_turn_loss = fit.v_turn_loss;
  base.v_gain = fit.v_gain;
  base.omega_gain = fit.omega_gain;
  base.omega_bias = fit.omega_bias;
  if (base.online_gains && fit.spread.maxCoeff() > 0.0) base.gain_sigma = fit.spread.cwiseMax(1e-4);
  return base;
}

/// Whether `c` holds exactly the delay and calibration of `fit` (as withCommandFit sets them).
inline bool hasCommandFit(const NoiseConfig& c, const CommandFit& fit) {
  const NoiseConfig fitted = withCommandFit(c, fit);
  return c.command_delay_s == fitted.command_delay_s && c.v_gain == fitted.v_gain &&
         c.v_turn_loss == fitted.v_turn_loss && c.omega_gain == fitted.omega_gain &&
         c.omega_bias == fitted.omega_bias && c.gain_sigma == fitted.gain_sigma;
}

inline RobotFigures figuresOf(const Scores& s) {
  return {s.aligned_rmse_m, s.rmse_m, s.landmark_aligned_rmse_m, s.nees_mean};
}

/// The known-correspondence run of one robot with `config`, scored.
inline Scores scoreKnown(const sylva::datasets::UtiasRobotData& robot,
                         const std::vector<sylva::datasets::UtiasLandmark>& landmarks,
                         const NoiseConfig& config,
                         double max_time_s) {
  const GroundTruth gt(robot.groundtruth);
  return score(runSlam(robot, config, Association::kKnown, max_time_s), gt, landmarks);
}

/// The summary of `robots` for every setting of the grid, everything else from `base`.
inline std::vector<TargetSummary> gridSummaries(
    const RobotSet& robots,
    const std::vector<sylva::datasets::UtiasLandmark>& landmarks,
    const NoiseConfig& base,
    double max_time_s) {
  std::vector<TargetSummary> out;
  for (const GridSetting& g : studyGrid()) {
    const NoiseConfig c = applySetting(base, g);
    std::vector<RobotFigures> figures;
    for (const auto* r : robots)
      figures.push_back(figuresOf(scoreKnown(*r, landmarks, c, max_time_s)));
    out.push_back(summarize(figures));
  }
  return out;
}

/// The whole procedure (file comment) on `robots`.
struct ConfigurationFit {
  CommandFit commands;
  std::vector<TargetSummary> grid;  ///< one summary per setting of studyGrid(), on `robots`
  std::size_t chosen = 0;           ///< index into studyGrid()
  GridSetting setting;
  NoiseConfig config;  ///< base with the fitted delay, calibration and setting
};

inline ConfigurationFit fitConfiguration(
    const RobotSet& robots,
    const std::vector<sylva::datasets::UtiasLandmark>& landmarks,
    const NoiseConfig& base,
    double max_time_s) {
  ConfigurationFit fit;
  fit.commands = fitCommandModel(robots);
  const NoiseConfig calibrated = withCommandFit(base, fit.commands);
  fit.grid = gridSummaries(robots, landmarks, calibrated, max_time_s);
  fit.chosen = selectSetting(fit.grid);
  fit.setting = studyGrid()[fit.chosen];
  fit.config = applySetting(calibrated, fit.setting);
  return fit;
}

}  // namespace utias
