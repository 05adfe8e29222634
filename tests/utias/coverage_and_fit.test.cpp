// The UTIAS example scores a robot only where its ground truth exists (ground_truth.hpp,
// evaluation.hpp), and its command-model fit (fit.hpp) recovers a delay and a calibration it
// is given; on the real Dataset 7, when present, the fit on all five robots is the compiled
// default.
#include "sylva_catch.hpp"

#include <cmath>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "error_helpers.hpp"
#include "utias/fit.hpp"

namespace unity_utias_coverage_and_fit {

using sylva::Mat;
using sylva::Vec;
using sylva::datasets::UtiasPose;

/// Truth along x at 1 m/s, sampled every 0.1 s from 0 to end_s.
std::vector<UtiasPose> straightTruth(double end_s) {
  std::vector<UtiasPose> out;
  for (int k = 0; k * 0.1 <= end_s + 1e-9; ++k) out.push_back({k * 0.1, Vec<3>(k * 0.1, 0.0, 0.0)});
  return out;
}

/// A run along the truth every 0.05 s until run_end_s, exact while t <= truth_end_s and 5 m off
/// after.
utias::RunResult runBeside(double truth_end_s, double run_end_s) {
  utias::RunResult run;
  for (int k = 0; k * 0.05 <= run_end_s + 1e-9; ++k) {
    const double t = k * 0.05;
    const Vec<3> pose(t, t <= truth_end_s ? 0.0 : 5.0, 0.0);
    run.samples.push_back({t, pose, Mat<3, 3>::Identity() * 0.01});
    run.dead_reckoning.push_back(pose);
  }
  return run;
}

/// A robot whose motion follows its commands `delay_s` late with the given calibration:
/// commands at 100 Hz (each held for much less than the 0.05 s steps of the delay search), a
/// smooth turn rate (two sines) and a speed between 0.02 and 0.1 m/s, never standing still;
/// Vicon sampled every 10 ms.
sylva::datasets::UtiasRobotData syntheticRobot(
    double delay_s, double v_gain, double v_turn_loss, double omega_gain, double omega_bias) {
  sylva::datasets::UtiasRobotData robot;
  robot.robot = 1;
  const double duration = 600.0, command_step = 0.01, two_pi = 6.283185307179586;
  for (int k = 0; k * command_step < duration; ++k) {
    const double t = k * command_step;
    const double v = 0.06 + 0.04 * std::sin(two_pi * t / 11.0);
    const double omega = 0.3 * std::sin(two_pi * t / 7.0) + 0.1 * std::sin(two_pi * t / 3.1);
    robot.odometry.push_back({t, Vec<2>(v, omega)});
  }
  const double dt = 0.01;
  Vec<3> x = Vec<3>::Zero();
  const sylva::Unicycle2D unicycle;
  for (int k = 0; k * dt <= duration + delay_s; ++k) {
    const double t = k * dt;
    robot.groundtruth.push_back({t, x});
    // The command acting over [t, t + dt): the last one logged at or before t - delay.
    Vec<2> u = Vec<2>::Zero();
    const double logged = t - delay_s;
    if (logged >= -1e-9) {
      const auto index = static_cast<std::size_t>(std::floor(logged / command_step + 1e-6));
      u = robot.odometry[std::min(index, robot.odometry.size() - 1)].u;
    }
    const Vec<2> effective(u[0] > 0.0 ? v_gain * u[0] - v_turn_loss * std::abs(u[1]) : 0.0,
                           u.isZero() ? 0.0 : omega_gain * u[1] + omega_bias);
    x = unicycle(x, effective, dt);
  }
  return robot;
}

/// Dataset 7 from the data folder, or nothing (with a message that the test skipped) when the
/// folder is absent.
std::optional<sylva::datasets::UtiasDataset> loadDataset7OrSkip() {
  const std::string folder = SYLVA_DATA_DIR "/utias-mrclam/MRCLAM_Dataset7";
  if (!std::filesystem::exists(folder + "/Barcodes.dat")) {
    WARN("skipped: UTIAS MRCLAM Dataset 7 not found in " << folder);
    SUCCEED("skipped");
    return std::nullopt;
  }
  return sylva::datasets::loadUtiasMrclam(folder);
}

}  // namespace unity_utias_coverage_and_fit

using namespace unity_utias_coverage_and_fit;

TEST_CASE("UTIAS ground truth covers only its span and no long gap", "[utias]") {
  std::vector<UtiasPose> truth = straightTruth(10.0);
  truth.push_back({12.0, Vec<3>(12.0, 0.0, 0.0)});  // a gap of 2 s
  const utias::GroundTruth gt(truth);
  CHECK(gt.covers(0.0));
  CHECK(gt.covers(5.05));
  CHECK(gt.covers(10.0));
  CHECK_FALSE(gt.covers(10.5));  // inside the 2 s gap
  CHECK(gt.covers(12.0));        // on a sample
  CHECK_FALSE(gt.covers(12.01));
  CHECK_FALSE(gt.covers(-0.01));
  const utias::GroundTruth lenient(truth, 3.0);
  CHECK(lenient.covers(10.5));
  CHECK(sylva_test::throwsCode([&] { utias::GroundTruth bad(truth, 0.0); },
                               sylva::ErrorCode::kInvalidArgument));
}

TEST_CASE("UTIAS scores stop where the ground truth stops, and say so", "[utias]") {
  const std::vector<UtiasPose> truth = straightTruth(10.0);
  const utias::GroundTruth gt(truth);
  const utias::RunResult run = runBeside(10.0, 20.0);  // the truth stops halfway
  const utias::Scores s = utias::score(run, gt, {});
  CHECK(s.samples == 401);
  CHECK(s.samples_scored == 201);  // t = 0, 0.05, ..., 10
  CHECK(s.samples_after_truth == 200);
  CHECK(s.samplesInGaps() == 0);
  CHECK(s.truthEndsEarly());
  CHECK(s.truth_end_s == Approx(10.0));
  CHECK(s.last_scored_s == Approx(10.0));
  CHECK(s.run_end_s == Approx(20.0));
  // Only the exact part is scored: the 5 m offset after the truth ends does not count.
  CHECK(s.rmse_m == Approx(0.0).margin(1e-12));
  CHECK(s.final_error_m == Approx(0.0).margin(1e-12));
  CHECK(s.nees_mean == Approx(0.0).margin(1e-12));

  // A tail shorter than the truth's largest gap (1 s) is not scored either, but is no "early end".
  const utias::Scores tail = utias::score(runBeside(10.0, 10.5), gt, {});
  CHECK(tail.samples_after_truth == 10);
  CHECK_FALSE(tail.truthEndsEarly());
  CHECK(tail.rmse_m == Approx(0.0).margin(1e-12));

  // Truth over the whole run: everything is scored, including the offset part.
  const utias::Scores whole =
      utias::score(runBeside(10.0, 20.0), utias::GroundTruth(straightTruth(20.0)), {});
  CHECK_FALSE(whole.truthEndsEarly());
  CHECK(whole.samples_scored == whole.samples);
  CHECK(whole.rmse_m > 3.0);
}

TEST_CASE("UTIAS command fit recovers the delay and calibration of a synthetic robot", "[utias]") {
  const auto robot = syntheticRobot(0.2, 1.05, 0.09, 0.92, -0.003);
  const utias::CommandFit fit = utias::fitCommandModel({&robot});
  CHECK(fit.delay_s == Approx(0.2));
  CHECK(fit.omega_gain == Approx(0.92).margin(0.005));
  CHECK(fit.omega_bias == Approx(-0.003).margin(0.001));
  // The distance is the chord of each 1 s window, a little shorter than the arc.
  CHECK(fit.v_gain == Approx(1.05).margin(0.02));
  CHECK(fit.v_turn_loss == Approx(0.09).margin(0.02));
  CHECK(fit.windows > 500);
  // Rounded to 4 decimals.
  CHECK(fit.v_gain * 1e4 == Approx(std::round(fit.v_gain * 1e4)).margin(1e-6));

  const utias::NoiseConfig c = utias::withCommandFit(utias::NoiseConfig{}, fit);
  CHECK(utias::hasCommandFit(c, fit));
  CHECK(c.command_delay_s == fit.delay_s);
  CHECK(c.omega_bias == fit.omega_bias);

  CHECK(sylva_test::throwsCode([] { utias::fitCommandModel({}); },
                               sylva::ErrorCode::kInvalidArgument));
}

TEST_CASE("UTIAS command fit on all five robots of Dataset 7 is the compiled default",
          "[utias][data]") {
  const std::optional<sylva::datasets::UtiasDataset> dataset7 = loadDataset7OrSkip();
  if (!dataset7) return;
  const auto& data = *dataset7;
  utias::RobotSet robots;
  for (const auto& r : data.robots) {
    robots.push_back(&r);
    const utias::GroundTruth gt(r.groundtruth);
    INFO("robot " << r.robot);
    // Dataset 7's truth covers every robot's readings, and its commands but the last few ms.
    CHECK(gt.covers(r.landmark_observations.back().time_s));
    CHECK(r.odometry.back().time_s - gt.end() < 0.01);
  }
  const utias::CommandFit fit = utias::fitCommandModel(robots);
  const utias::NoiseConfig compiled;
  CHECK(fit.delay_s == compiled.command_delay_s);
  CHECK(fit.v_gain == compiled.v_gain);
  CHECK(fit.v_turn_loss == compiled.v_turn_loss);
  CHECK(fit.omega_gain == compiled.omega_gain);
  CHECK(fit.omega_bias == compiled.omega_bias);
  CHECK(compiled.online_gains);
  CHECK(fit.spread == compiled.gain_sigma);
}

TEST_CASE("UTIAS online gains: the fit sets their prior, and on Dataset 7 each robot learns them from scratch",
          "[utias][data][slow]") {
  utias::NoiseConfig online;
  online.online_gains = true;
  utias::CommandFit fit;
  fit.delay_s = 0.15;
  fit.v_gain = 1.05;
  fit.v_turn_loss = 0.09;
  fit.omega_gain = 0.93;
  fit.omega_bias = -0.003;
  fit.spread = Vec<3>(0.01, 0.02, 0.0);
  const utias::NoiseConfig fitted = utias::withCommandFit(online, fit);
  CHECK(fitted.command_delay_s == 0.15);
  CHECK(fitted.v_turn_loss == 0.09);
  CHECK((fitted.gainPrior() - Vec<3>(0.05, -0.07, -0.003)).norm() < 1e-15);
  CHECK(fitted.gain_sigma == Vec<3>(0.01, 0.02, 1e-4));  // the spread, with its floor
  CHECK(utias::hasCommandFit(fitted, fit));
  CHECK_FALSE(utias::hasCommandFit(utias::withCommandFit(utias::NoiseConfig{}, fit), utias::CommandFit{}));
  utias::NoiseConfig fixed = online;
  fixed.online_gains = false;
  CHECK(utias::withCommandFit(fixed, fit).gain_sigma == fixed.gain_sigma);

  const std::optional<sylva::datasets::UtiasDataset> dataset7 = loadDataset7OrSkip();
  if (!dataset7) return;
  // Starting at gain 1 and bias 0, every robot's filter learns its gains from its landmark
  // readings alone: each final sigma is below the prior's, and the speed and turn-rate gains
  // lie within 3 of their sigmas of the pooled calibration that the Vicon truth gives (the
  // robots' own calibrations differ from the pooled one by much less than those sigmas).
  const auto& data = *dataset7;
  const utias::NoiseConfig calibrated;
  utias::NoiseConfig uncalibrated = calibrated;
  uncalibrated.online_gains = true;
  uncalibrated.v_gain = 1.0;
  uncalibrated.omega_gain = 1.0;
  uncalibrated.omega_bias = 0.0;
  uncalibrated.gain_sigma = Vec<3>(0.1, 0.1, 0.01);  // a tenth of the command either way
  const Vec<3> pooled(calibrated.v_gain - 1.0, calibrated.omega_gain - 1.0, calibrated.omega_bias);
  for (const auto& robot : data.robots) {
    INFO("robot " << robot.robot);
    const utias::RunResult run = utias::runSlam(robot, uncalibrated, utias::Association::kKnown);
    REQUIRE(run.online_gains);
    INFO("gains " << run.gains.transpose() << " +- " << run.gain_sigmas.transpose());
    for (int i = 0; i < 3; ++i) CHECK(run.gain_sigmas[i] < uncalibrated.gain_sigma[i]);
    for (int i = 0; i < 2; ++i) CHECK(std::abs(run.gains[i] - pooled[i]) < 3.0 * run.gain_sigmas[i]);
  }
}
