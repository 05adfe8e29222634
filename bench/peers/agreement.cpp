// Agreement of sylva and MRPT's CRangeBearingKFSLAM2D on the circle world: both filters run
// the same two laps (lap 1 builds the map, lap 2 re-observes it) and their states are
// compared after every step, landmarks matched by id.
//
//   sylva batched                vs MRPT kfEKFNaive       mean to 1e-9, covariance to 1e-9 of max |P|
//   sylva kfEKFAlaDavison fusion vs MRPT kfEKFAlaDavison  the same
//   sylva sequential             vs both                  reported only: a different estimator
//
// Exit status 0 when every gated pair agrees, 1 otherwise (with the offending step).
// Usage: peers_agreement [N ...]   (default: 50 200)

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <vector>

#include "circle_world.hpp"
#include "filter_state.hpp"
#include "mrpt_peer.hpp"
#include "sylva_circle_slam.hpp"
#include "sylva_peer.hpp"

namespace {

using sylva_peers::compareStates;
using sylva_peers::FilterState;
using sylva_peers::MrptMethod;
using sylva_peers::MrptPeer;
using sylva_peers::StateDifference;
using sylva_peers::SylvaFusion;

constexpr double kMeanTolerance = 1e-9;        // absolute, metres and radians
constexpr double kCovarianceTolerance = 1e-9;  // relative to the largest |P| entry

/// Worst differences of one pair over all steps, and where the worst mean difference was.
struct PairRecord {
  PairRecord(const char* name_, bool gated_) : name(name_), gated(gated_) {}

  const char* name;
  bool gated;
  StateDifference worst;
  int worst_step = -1;
  bool maps_differ = false;
  std::string map_message;

  void record(const StateDifference& d, int step) {
    if (!d.same_landmarks) {
      if (!maps_differ) map_message = "step " + std::to_string(step) + ": " + d.why;
      maps_differ = true;
      return;
    }
    if (d.max_mean > worst.max_mean) {
      worst.max_mean = d.max_mean;
      worst_step = step;
    }
    worst.max_robot_mean = std::max(worst.max_robot_mean, d.max_robot_mean);
    worst.max_cov = std::max(worst.max_cov, d.max_cov);
    worst.max_cov_relative = std::max(worst.max_cov_relative, d.max_cov_relative);
  }

  bool ok() const {
    return !maps_differ && worst.max_mean <= kMeanTolerance && worst.max_cov_relative <= kCovarianceTolerance;
  }
};

/// Robot position error and landmark RMS error against the truth (sanity of the run).
void printAccuracy(const char* name, const FilterState& s, const sylva_bench::CircleWorld& world) {
  const sylva::Vec<3>& truth = world.steps().back().true_pose;
  const double robot_m = std::hypot(s.mean[0] - truth[0], s.mean[1] - truth[1]);
  double sum2 = 0.0;
  for (std::size_t i = 0; i < s.ids.size(); ++i) {
    const sylva::Vec<2> est(s.mean[static_cast<Eigen::Index>(3 + 2 * i)], s.mean[static_cast<Eigen::Index>(4 + 2 * i)]);
    sum2 += (est - world.landmarks()[static_cast<std::size_t>(s.ids[i])]).squaredNorm();
  }
  std::printf("    %-34s final robot position error %.3f m, landmark RMS error %.3f m\n", name, robot_m,
              std::sqrt(sum2 / static_cast<double>(s.ids.size())));
}

bool checkSize(int landmarks) {
  sylva_bench::CircleWorldConfig config;
  config.landmarks = landmarks;
  const sylva_bench::CircleWorld world(config);
  const auto steps = sylva_bench::sylvaSteps(world);
  const sylva::Gaussian<3> odometry_noise = world.odometryNoise();
  const double dt = config.dt_s;

  std::printf("N = %d: circle radius %.1f m, %d steps per lap, %.2f measurements per step, %d laps\n",
              landmarks, world.radiusM(), world.stepsPerLap(), world.meanMeasurementsPerStep(1), config.laps);

  const SylvaFusion fusions[] = {SylvaFusion::kBatched, SylvaFusion::kAlaDavison, SylvaFusion::kSequential};
  std::vector<sylva_bench::OdometrySlam> sylva_filters;
  std::vector<sylva_peers::PeerScratch> scratch(3);
  for (int i = 0; i < 3; ++i) sylva_filters.push_back(sylva_bench::makeOdometrySlam(world));
  MrptPeer naive(world, MrptMethod::kNaive);
  MrptPeer davison(world, MrptMethod::kAlaDavison);

  PairRecord pairs[] = {
      {"sylva batched vs MRPT kfEKFNaive", true},
      {"sylva AlaDavison fusion vs MRPT kfEKFAlaDavison", true},
      {"sylva sequential vs MRPT kfEKFNaive", false},
      {"sylva sequential vs MRPT kfEKFAlaDavison", false},
  };
  for (std::size_t k = 0; k < steps.size(); ++k) {
    for (int i = 0; i < 3; ++i)
      sylva_peers::runPeerStep(sylva_filters[static_cast<std::size_t>(i)], steps[k], odometry_noise, dt, fusions[i],
                               scratch[static_cast<std::size_t>(i)]);
    naive.step(static_cast<int>(k));
    davison.step(static_cast<int>(k));
    const FilterState naive_state = naive.state();
    const FilterState davison_state = davison.state();
    const FilterState sequential = sylva_peers::stateOf(sylva_filters[2]);
    const int step = static_cast<int>(k);
    pairs[0].record(compareStates(sylva_peers::stateOf(sylva_filters[0]), naive_state), step);
    pairs[1].record(compareStates(sylva_peers::stateOf(sylva_filters[1]), davison_state), step);
    pairs[2].record(compareStates(sequential, naive_state), step);
    pairs[3].record(compareStates(sequential, davison_state), step);
  }

  bool ok = true;
  const int map_size = sylva_filters[0].landmarkCount();
  if (map_size != landmarks) {
    std::printf("  FAIL: the map holds %d landmarks, the world %d\n", map_size, landmarks);
    ok = false;
  }
  for (const PairRecord& p : pairs) {
    const bool pass = p.ok();
    const char* verdict = p.gated ? (pass ? "ok" : "FAIL") : "info";
    if (p.maps_differ)
      std::printf("  %-4s %-48s maps differ (%s)\n", verdict, p.name, p.map_message.c_str());
    else
      std::printf("  %-4s %-48s over all %zu steps: %s (worst mean at step %d)\n", verdict, p.name, steps.size(),
                  p.worst.summary().c_str(), p.worst_step);
    if (p.gated && !pass) ok = false;
  }
  printAccuracy("sylva batched", sylva_peers::stateOf(sylva_filters[0]), world);
  printAccuracy("MRPT kfEKFNaive", naive.state(), world);
  printAccuracy("sylva AlaDavison fusion", sylva_peers::stateOf(sylva_filters[1]), world);
  printAccuracy("MRPT kfEKFAlaDavison", davison.state(), world);
  printAccuracy("sylva sequential", sylva_peers::stateOf(sylva_filters[2]), world);
  return ok;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<int> sizes;
  for (int i = 1; i < argc; ++i) sizes.push_back(std::atoi(argv[i]));
  if (sizes.empty()) sizes = {50, 200};
  std::printf("sylva vs MRPT %s CRangeBearingKFSLAM2D; tolerances: mean %.0e, covariance %.0e of max |P|\n",
              MrptPeer::version().c_str(), kMeanTolerance, kCovarianceTolerance);
  bool ok = true;
  try {
    for (int n : sizes) ok = checkSize(n) && ok;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "peers_agreement: %s\n", e.what());
    return 1;
  }
  std::printf(ok ? "AGREE\n" : "DISAGREE: see FAIL above\n");
  return ok ? 0 : 1;
}
