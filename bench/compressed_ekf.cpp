/// @file
/// The compressed EKF (`Ekf::setCompression`, Guivant and Nebot 2001) against the plain
/// filter on the circle world (bench/scenario/circle_world.hpp), over a stretch of lap 2
/// whole: the compressed filter's global updates and region changes are timed with its local
/// steps, so the time per step is its amortized cost.
///
/// Families (arguments: N, then the region's radius in m for the compressed one):
///   BM_LapTwoPlain       `Ekf<Odometry2D, Point2>`, batched updates: the first
///                        kStretch steps of lap 2 from the end-of-lap-1 filter
///   BM_LapTwoCompressed  the same filter and steps with `setCompression(withinRadius(r))`
///                        entered at the start of lap 2 (outside the timing), and a final
///                        `synchronize()` (inside it)
/// Counters: per_step_us (the iteration's time over its steps), global_updates, active_dim at
/// the end, and state_difference: after the stretch, the largest difference between the
/// compressed filter's mean and covariance and the plain filter's, relative to the largest
/// entry of each (computed outside the timing).

#include <benchmark/benchmark.h>

#include <Eigen/Core>
#include <algorithm>
#include <map>
#include <memory>
#include <vector>

#include "common/build_context.hpp"
#include "scenario/sylva_circle_slam.hpp"

namespace {

using Filter = sylva_bench::OdometrySlam;

constexpr int kStretch = 200;  // steps of lap 2 per iteration (lap 2 at N = 2000 has 1570)

int stretchOf(const sylva_bench::World& w) { return std::min(kStretch, w.world.stepsPerLap()); }

/// Runs the stretch on `ekf` (a copy of the end-of-lap-1 filter).
void runStretch(Filter& ekf, const sylva_bench::World& w, sylva_bench::StepScratch& scratch) {
  const int first = w.world.lapBegin(1);
  const auto noise = w.world.odometryNoise();
  for (int k = 0; k < stretchOf(w); ++k)
    sylva_bench::runStep(ekf, w.steps[static_cast<std::size_t>(first + k)], noise, w.world.config().dt_s,
                         sylva::Fusion::kBatched, scratch);
}

/// The plain filter after the stretch, once per N (the reference of state_difference).
const Filter& plainAfterStretch(int landmarks) {
  static std::map<int, std::unique_ptr<Filter>> cache;
  auto& slot = cache[landmarks];
  if (!slot) {
    const sylva_bench::World& w = sylva_bench::worldOf(landmarks);
    Filter ekf = sylva_bench::endOfLapOne<Filter>(landmarks);
    sylva_bench::StepScratch scratch;
    runStretch(ekf, w, scratch);
    slot = std::make_unique<Filter>(std::move(ekf));
  }
  return *slot;
}

double relativeDifference(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return (a - b).cwiseAbs().maxCoeff() / std::max(1e-300, b.cwiseAbs().maxCoeff());
}

/// The compressed filter's mean and covariance in the plain filter's order of landmarks.
double stateDifference(const Filter& compressed, const Filter& plain) {
  std::vector<int> rows{0, 1, 2};
  for (const sylva::LandmarkSlot& s : plain.slots())
    for (int i = 0; i < s.dim; ++i) rows.push_back(compressed.slot(s.id).offset + i);
  const auto n = static_cast<Eigen::Index>(rows.size());
  const Eigen::VectorXd x = compressed.mean();
  const Eigen::MatrixXd P = compressed.covariance();
  Eigen::VectorXd x_ordered(n);
  Eigen::MatrixXd P_ordered(n, n);
  for (Eigen::Index j = 0; j < n; ++j) {
    x_ordered[j] = x[rows[static_cast<std::size_t>(j)]];
    for (Eigen::Index i = 0; i < n; ++i) P_ordered(i, j) = P(rows[static_cast<std::size_t>(i)], rows[static_cast<std::size_t>(j)]);
  }
  return std::max(relativeDifference(x_ordered, plain.mean()), relativeDifference(P_ordered, plain.covariance()));
}

void BM_LapTwoPlain(benchmark::State& state) {
  const int landmarks = static_cast<int>(state.range(0));
  const sylva_bench::World& w = sylva_bench::worldOf(landmarks);
  const Filter& start = sylva_bench::endOfLapOne<Filter>(landmarks);
  sylva_bench::StepScratch scratch;
  for (auto _ : state) {
    state.PauseTiming();
    Filter ekf = start;
    state.ResumeTiming();
    runStretch(ekf, w, scratch);
    benchmark::ClobberMemory();
  }
  state.counters["N"] = landmarks;
  state.counters["steps"] = stretchOf(w);
  state.counters["per_step_us"] =
      benchmark::Counter(stretchOf(w) / 1e6, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

void BM_LapTwoCompressed(benchmark::State& state) {
  const int landmarks = static_cast<int>(state.range(0));
  const double radius = static_cast<double>(state.range(1));
  const sylva_bench::World& w = sylva_bench::worldOf(landmarks);
  const Filter& start = sylva_bench::endOfLapOne<Filter>(landmarks);
  sylva_bench::StepScratch scratch;
  Filter last = start;
  for (auto _ : state) {
    state.PauseTiming();
    Filter ekf = start;
    ekf.setCompression(Filter::withinRadius(radius));
    state.ResumeTiming();
    runStretch(ekf, w, scratch);
    ekf.synchronize();
    benchmark::ClobberMemory();
    state.PauseTiming();
    last = std::move(ekf);
    state.ResumeTiming();
  }
  state.counters["N"] = landmarks;
  state.counters["radius_m"] = radius;
  state.counters["steps"] = stretchOf(w);
  state.counters["per_step_us"] =
      benchmark::Counter(stretchOf(w) / 1e6, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.counters["global_updates"] = static_cast<double>(last.globalUpdates());
  state.counters["active_dim"] = last.activeDim();
  state.counters["state_difference"] = stateDifference(last, plainAfterStretch(landmarks));
}

}  // namespace

BENCHMARK(BM_LapTwoPlain)->Arg(200)->Arg(1000)->Arg(2000)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_LapTwoCompressed)
    ->ArgsProduct({{200, 1000, 2000}, {20, 30, 50, 80}})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);

int main(int argc, char** argv) { return sylva_bench::runBenchmarks(argc, argv); }
