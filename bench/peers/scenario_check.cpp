// Checks of the shared circle world (bench/scenario/circle_world.hpp) and of sylva's step
// drivers on it; needs neither MRPT nor Google Benchmark, so CI runs it.
//
//   - the world is reproducible (same configuration -> bit-identical steps) and the seed
//     matters;
//   - at every benchmark size the measurements per step average about 12, the circle grows
//     with N, every landmark is seen in lap 1, and lap 2 re-observes only mapped landmarks;
//   - measurements are float-exact, bearings in (-pi, pi], within range;
//   - sylva's batched and sequential steps over two laps map every landmark and end close to
//     the truth, and close to each other.
// Exit status 0 when everything holds. Usage: peers_scenario_check [N ...]

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "circle_world.hpp"
#include "sylva_circle_slam.hpp"

namespace {

int g_failures = 0;

void check(bool ok, const std::string& what) {
  if (!ok) {
    ++g_failures;
    std::printf("  FAIL: %s\n", what.c_str());
  }
}

bool sameSteps(const sylva_bench::CircleWorld& a, const sylva_bench::CircleWorld& b) {
  if (a.steps().size() != b.steps().size() || a.landmarks() != b.landmarks()) return false;
  for (std::size_t k = 0; k < a.steps().size(); ++k) {
    const auto& x = a.steps()[k];
    const auto& y = b.steps()[k];
    if (x.odometry != y.odometry || x.true_pose != y.true_pose || x.measurements.size() != y.measurements.size())
      return false;
    for (std::size_t i = 0; i < x.measurements.size(); ++i) {
      const auto& p = x.measurements[i];
      const auto& q = y.measurements[i];
      if (p.id != q.id || p.range_m != q.range_m || p.bearing_rad != q.bearing_rad) return false;
    }
  }
  return true;
}

void checkWorld(int landmarks, double& previous_radius) {
  sylva_bench::CircleWorldConfig config;
  config.landmarks = landmarks;
  const sylva_bench::CircleWorld world(config);
  const double per_step = world.meanMeasurementsPerStep(1);
  std::printf("N = %d: radius %.1f m, %d steps per lap of %.3f m, %.2f measurements per step (max %d)\n",
              landmarks, world.radiusM(), world.stepsPerLap(), world.stepLengthM(), per_step,
              world.maxMeasurementsPerStep());
  check(std::abs(per_step - config.visible_per_step) < 0.1 * config.visible_per_step,
        "mean measurements per step " + std::to_string(per_step) + " is not about " +
            std::to_string(config.visible_per_step));
  check(world.radiusM() > previous_radius, "the circle does not grow with N");
  previous_radius = world.radiusM();
  check(world.landmarksUnseenInFirstLap() == 0,
        std::to_string(world.landmarksUnseenInFirstLap()) + " landmarks are never seen in lap 1");
  check(static_cast<int>(world.steps().size()) == config.laps * world.stepsPerLap(), "wrong number of steps");
  check(sameSteps(world, sylva_bench::CircleWorld(config)), "two worlds from one configuration differ");

  // The robot returns to the start after each lap.
  const sylva::Vec<3> end_of_lap = world.steps()[static_cast<std::size_t>(world.lapBegin(1))].true_pose;
  check(end_of_lap.head<2>().norm() < 1e-9 * world.radiusM() && std::abs(sylva::wrapAngle(end_of_lap[2])) < 1e-9,
        "lap 2 does not start at the start pose");

  for (const sylva_bench::Step& step : world.steps()) {
    check(step.has_motion == (step.index > 0), "only step 0 has no motion");
    for (const sylva_bench::Measurement& m : step.measurements) {
      const bool exact = static_cast<double>(static_cast<float>(m.range_m)) == m.range_m &&
                         static_cast<double>(static_cast<float>(m.bearing_rad)) == m.bearing_rad;
      const bool in_range = m.range_m > 0.5 * config.min_range_m && m.range_m < config.max_range_m + 1.0;
      const bool wrapped = m.bearing_rad > -sylva::kPi && m.bearing_rad <= sylva::kPi;
      if (!exact || !in_range || !wrapped) {
        check(false, "step " + std::to_string(step.index) + ": measurement of landmark " + std::to_string(m.id) +
                         " is not float-exact, in range and wrapped");
        return;
      }
    }
  }
}

/// sylva's batched and sequential drivers over both laps.
void checkSylvaRun(int landmarks) {
  sylva_bench::CircleWorldConfig config;
  config.landmarks = landmarks;
  const sylva_bench::CircleWorld world(config);
  const auto steps = sylva_bench::sylvaSteps(world);
  auto batched = sylva_bench::makeOdometrySlam(world);
  auto sequential = sylva_bench::makeOdometrySlam(world);
  sylva_bench::StepScratch scratch;
  int lap2_new = 0;
  for (const auto& step : steps) {
    const int before = batched.landmarkCount();
    sylva_bench::runStep(batched, step, world.odometryNoise(), config.dt_s, sylva_bench::Fusion::kBatched, scratch);
    sylva_bench::runStep(sequential, step, world.odometryNoise(), config.dt_s, sylva_bench::Fusion::kSequential,
                         scratch);
    if (&step - steps.data() >= world.lapBegin(1)) lap2_new += batched.landmarkCount() - before;
  }
  check(batched.landmarkCount() == landmarks, "sylva batched did not map every landmark");
  check(lap2_new == 0, "landmarks were added in lap 2");
  const sylva::Vec<3> truth = world.steps().back().true_pose;
  const double error_m = (batched.robotMean().head<2>() - truth.head<2>()).norm();
  const double sigma_m = std::sqrt(batched.robotCovariance().topLeftCorner<2, 2>().trace());
  const double apart_m = (batched.mean() - sequential.mean()).cwiseAbs().maxCoeff();
  std::printf("  sylva two laps: robot error %.3f m (1-sigma %.3f m); batched vs sequential max |mean diff| %.2e\n",
              error_m, sigma_m, apart_m);
  check(error_m < 5.0 * sigma_m + 0.05, "robot error is not within 5 sigma");
  check(apart_m < 1e-2, "batched and sequential estimates are far apart");
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<int> sizes;
  for (int i = 1; i < argc; ++i) sizes.push_back(std::atoi(argv[i]));
  if (sizes.empty()) sizes = {50, 100, 200, 500, 1000, 2000};
  try {
    double radius = 0.0;
    for (int n : sizes) checkWorld(n, radius);
    sylva_bench::CircleWorldConfig a;
    a.landmarks = 100;
    sylva_bench::CircleWorldConfig b = a;
    b.seed += 1;
    check(!sameSteps(sylva_bench::CircleWorld(a), sylva_bench::CircleWorld(b)), "the seed does not change the world");
    checkSylvaRun(sizes.front());
  } catch (const std::exception& e) {
    std::printf("peers_scenario_check: %s\n", e.what());
    return 1;
  }
  if (g_failures == 0)
    std::printf("OK\n");
  else
    std::printf("%d FAILURES\n", g_failures);
  return g_failures == 0 ? 0 : 1;
}
