/// @file
/// The compressed EKF (`Ekf::setCompression`, Guivant and Nebot 2001) against the plain
/// filter on the circle world (bench/scenario/circle_world.hpp), over a stretch of lap 2
/// whole: the compressed filter's global updates and region changes are timed with its local
/// steps, so the time per step is its amortized cost.
///
/// Families (arguments: N; for the compressed one the region's radius r and the distance of
/// its centre ahead of the robot, in m):
///   BM_LapTwoPlain       `Ekf<Odometry2D, Point2>`, batched updates: the first
///                        kStretch steps of lap 2 from the end-of-lap-1 filter
///   BM_LapOnePlain, BM_LapOneCompressed
///                        lap 1 whole from the empty map, where every landmark is added (the
///                        compressed one from `setCompression(withinRadius(r, ahead))` on the
///                        empty filter, its final synchronize() timed; state_difference against
///                        the plain end of lap 1)
///   BM_LapTwoCompressed  the same filter and steps with `setCompression(withinRadius(r, ahead))`
///                        entered at the start of lap 2 (outside the timing), and a final
///                        `synchronize()` (inside it)
///   BM_WholeRunAgreement both laps from the empty map (every step of the world), with the
///                        fusion of MRPT's kfEKFAlaDavison (bench/peers/sylva_peer.hpp: two
///                        scalar updates per observation, so a region holds about a
///                        thousand local updates), plain and compressed on the same inputs,
///                        one run each: the whole-run state check of issue 19 without MRPT.
///                        Counters: mean_difference and covariance_difference (relative to
///                        the largest entry of the plain filter's), plain_s, compressed_s,
///                        global_updates; the compressed run split into local_steps_s and
///                        global_steps_s (the steps in which a global update ran, and the
///                        final synchronize), global_flops, gemm_gflops (measured after the
///                        runs) and global_floor_s, the flops at that peak
///                        (bench/peers/compressed_whole_run.hpp). Its time is the two runs
///                        together.
///   BM_WholeRunRegions   the compressed whole run alone (same fusion, same counters) for
///                        several regions at N = 2000: how the global updates' flops, and so
///                        their floor, depend on the region
/// Counters: per_step_us (the iteration's time over its steps), global_updates, active_dim at
/// the end, and state_difference: after the stretch, the largest difference between the
/// compressed filter's mean and covariance and the plain filter's, relative to the largest
/// entry of each (computed outside the timing).
///
/// The kernel alone (detail::CompressedRegion) against the plain batched update's kernel, on
/// the sizes of the circle world's step: N landmarks of 2 coordinates (n = 3 + 2N), 12
/// observations of 2 rows a step (m = 24), an active part of the robot and 20 landmarks
/// (a = 43); the argument is N:
///   BM_PlainRankUpdate        P -= W W^T on the n x n lower triangle, W n x 24: the part of
///                             a plain batched step that grows as n^2
///   BM_CompressedLocalStep    what a compressed step does instead: the active block's own
///                             update (S, K_A, P_AA -= K_A S K_A^T, a x a) and the region's
///                             accumulators (CompressedRegion::stageUpdate); independent of N
///   BM_CompressedGlobalUpdate CompressedRegion::globalUpdate after 10 local updates: once
///                             per region change, O(n^2 a)
/// A compressed run whose regions last L steps costs about (LocalStep + GlobalUpdate / L) per
/// step against PlainRankUpdate (plus the costs both share).

#include <benchmark/benchmark.h>

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <algorithm>
#include <chrono>
#include <map>
#include <memory>
#include <random>
#include <vector>

#include "common/build_context.hpp"
#include "peers/compressed_whole_run.hpp"
#include "peers/sylva_peer.hpp"
#include "scenario/sylva_circle_slam.hpp"
#include "sylva/detail/compressed_region.hpp"
#include "sylva/filter/compression.hpp"
#include "sylva/detail/lower_rank_update.hpp"

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

/// How far the compressed filter's mean and covariance are from the plain filter's, each
/// relative to the plain filter's largest entry, landmarks matched by id.
struct Difference {
  double mean = 0.0;
  double covariance = 0.0;
};

Difference stateDifferences(const Filter& compressed, const Filter& plain) {
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
  return {relativeDifference(x_ordered, plain.mean()), relativeDifference(P_ordered, plain.covariance())};
}

double stateDifference(const Filter& compressed, const Filter& plain) {
  const Difference d = stateDifferences(compressed, plain);
  return std::max(d.mean, d.covariance);
}

/// Lap 1 whole, from the empty map: every landmark is added during it (the add path).
void runLapOne(Filter& ekf, const sylva_bench::World& w, sylva_bench::StepScratch& scratch) {
  const auto noise = w.world.odometryNoise();
  for (int k = 0; k < w.world.lapBegin(1); ++k)
    sylva_bench::runStep(ekf, w.steps[static_cast<std::size_t>(k)], noise, w.world.config().dt_s, sylva::Fusion::kBatched,
                         scratch);
}

enum class Lap { kOne, kTwo };

/// One timed run per iteration: lap 1 from the empty map, or the stretch of lap 2 from the
/// end of lap 1; plain, or (with a region's radius and centre ahead as arguments 1 and 2)
/// compressed, its region entered outside the timing and its final synchronize() inside it.
void timeLap(benchmark::State& state, Lap lap, bool compressed) {
  const int landmarks = static_cast<int>(state.range(0));
  const double radius = compressed ? static_cast<double>(state.range(1)) : 0.0;
  const double ahead = compressed ? static_cast<double>(state.range(2)) : 0.0;
  const sylva_bench::World& w = sylva_bench::worldOf(landmarks);
  const Filter start = lap == Lap::kOne ? sylva_bench::makeOdometrySlam(w.world) : sylva_bench::endOfLapOne<Filter>(landmarks);
  const int steps = lap == Lap::kOne ? w.world.lapBegin(1) : stretchOf(w);
  sylva_bench::StepScratch scratch;
  Filter last = start;
  for (auto _ : state) {
    state.PauseTiming();
    Filter ekf = start;
    if (compressed) ekf.setCompression(Filter::withinRadius(radius, ahead));
    state.ResumeTiming();
    if (lap == Lap::kOne)
      runLapOne(ekf, w, scratch);
    else
      runStretch(ekf, w, scratch);
    ekf.synchronize();  // a no-op for the plain filter
    benchmark::ClobberMemory();
    state.PauseTiming();
    last = std::move(ekf);
    state.ResumeTiming();
  }
  state.counters["N"] = landmarks;
  state.counters["steps"] = steps;
  state.counters["per_step_us"] =
      benchmark::Counter(steps / 1e6, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  if (!compressed) return;
  state.counters["radius_m"] = radius;
  state.counters["ahead_m"] = ahead;
  state.counters["global_updates"] = static_cast<double>(last.globalUpdates());
  state.counters["active_dim"] = last.activeDim();
  const Filter& plain = lap == Lap::kOne ? sylva_bench::endOfLapOne<Filter>(landmarks) : plainAfterStretch(landmarks);
  state.counters["state_difference"] = stateDifference(last, plain);
}

void BM_LapOnePlain(benchmark::State& state) { timeLap(state, Lap::kOne, false); }
void BM_LapOneCompressed(benchmark::State& state) { timeLap(state, Lap::kOne, true); }
void BM_LapTwoPlain(benchmark::State& state) { timeLap(state, Lap::kTwo, false); }
void BM_LapTwoCompressed(benchmark::State& state) { timeLap(state, Lap::kTwo, true); }

/// BM_WholeRunAgreement (see the file comment): arguments N, the region's radius and its
/// centre ahead of the robot.
void BM_WholeRunAgreement(benchmark::State& state) {
  const int landmarks = static_cast<int>(state.range(0));
  const sylva_bench::World& w = sylva_bench::worldOf(landmarks);
  const auto runAll = [&](Filter& ekf, sylva_peers::WholeRunSplit* split) {
    return sylva_peers::runCompressedWhole(ekf, w.steps, w.world.odometryNoise(), w.world.config().dt_s, split);
  };
  Filter plain = sylva_bench::makeOdometrySlam(w.world);
  Filter compressed = sylva_bench::makeOdometrySlam(w.world);
  double plain_s = 0.0, compressed_s = 0.0;
  sylva_peers::WholeRunSplit split;
  for (auto _ : state) {
    plain = sylva_bench::makeOdometrySlam(w.world);
    compressed = sylva_bench::makeOdometrySlam(w.world);
    compressed.setCompression(Filter::withinRadius(static_cast<double>(state.range(1)), static_cast<double>(state.range(2))));
    plain_s = runAll(plain, nullptr);
    split = sylva_peers::WholeRunSplit{};
    compressed_s = runAll(compressed, &split);
  }
  const Difference d = stateDifferences(compressed, plain);
  state.counters["N"] = landmarks;
  state.counters["steps"] = static_cast<double>(w.steps.size());
  state.counters["radius_m"] = static_cast<double>(state.range(1));
  state.counters["ahead_m"] = static_cast<double>(state.range(2));
  state.counters["mean_difference"] = d.mean;
  state.counters["covariance_difference"] = d.covariance;
  state.counters["plain_s"] = plain_s;
  state.counters["compressed_s"] = compressed_s;
  sylva_peers::setSplitCounters(state, split);
}

/// BM_WholeRunRegions (see the file comment): the compressed whole run alone, arguments N,
/// the region's radius and its centre ahead of the robot.
void BM_WholeRunRegions(benchmark::State& state) {
  const int landmarks = static_cast<int>(state.range(0));
  const sylva_bench::World& w = sylva_bench::worldOf(landmarks);
  sylva_peers::WholeRunSplit split;
  double seconds = 0.0;
  for (auto _ : state) {
    Filter ekf = sylva_bench::makeOdometrySlam(w.world);
    ekf.setCompression(Filter::withinRadius(static_cast<double>(state.range(1)), static_cast<double>(state.range(2))));
    split = sylva_peers::WholeRunSplit{};
    seconds = sylva_peers::runCompressedWhole(ekf, w.steps, w.world.odometryNoise(), w.world.config().dt_s, &split);
  }
  state.counters["N"] = landmarks;
  state.counters["radius_m"] = static_cast<double>(state.range(1));
  state.counters["ahead_m"] = static_cast<double>(state.range(2));
  state.counters["compressed_s"] = seconds;
  sylva_peers::setSplitCounters(state, split);
}

// ---------------------------------------------------------------- the kernel alone

constexpr int kRows = 24;         // 12 range-bearing observations
constexpr int kActiveLandmarks = 20;
constexpr int kActive = 3 + 2 * kActiveLandmarks;

int stateDim(const benchmark::State& state) { return 3 + 2 * static_cast<int>(state.range(0)); }

/// A positive-definite n x n covariance with some correlation (lower triangle authoritative).
Eigen::MatrixXd covariance(int n) {
  Eigen::MatrixXd P = Eigen::MatrixXd::Identity(n, n);
  for (int j = 0; j + 1 < n; ++j) P(j + 1, j) = 0.2;
  return P;
}

Eigen::MatrixXd randomMatrix(int rows, int cols, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  Eigen::MatrixXd m(rows, cols);
  for (int j = 0; j < cols; ++j)
    for (int i = 0; i < rows; ++i) m(i, j) = normal(rng);
  return m;
}

void BM_PlainRankUpdate(benchmark::State& state) {
  const int n = stateDim(state);
  Eigen::MatrixXd P = covariance(n);
  const Eigen::MatrixXd W = 1e-6 * randomMatrix(n, kRows, 1);
  for (auto _ : state) {
    sylva::detail::subtractLowerRankUpdate(P.topLeftCorner(n, n), W);
    benchmark::DoNotOptimize(P.data());
    benchmark::ClobberMemory();
  }
  state.counters["n"] = n;
}

void BM_CompressedLocalStep(benchmark::State& state) {
  const Eigen::MatrixXd P_AA0 = covariance(kActive);
  const Eigen::MatrixXd H_A = randomMatrix(kRows, kActive, 2);
  const Eigen::MatrixXd R = Eigen::MatrixXd::Identity(kRows, kRows);
  const Eigen::VectorXd nu = 0.01 * randomMatrix(kRows, 1, 3);
  sylva::detail::CompressedRegion region;
  Eigen::MatrixXd P_AA = P_AA0;
  Eigen::MatrixXd PHt(kActive, kRows), S(kRows, kRows), K(kActive, kRows), W(kActive, kRows);
  Eigen::LLT<Eigen::MatrixXd> S_llt(kRows);
  for (auto _ : state) {
    // Every iteration starts from the same state (outside the timing), so that it times the
    // same arithmetic on the same numbers.
    state.PauseTiming();
    P_AA = P_AA0;
    region.begin(kActive);
    state.ResumeTiming();
    PHt.noalias() = P_AA.selfadjointView<Eigen::Lower>() * H_A.transpose();
    S = R;
    S.noalias() += H_A * PHt;
    S_llt.compute(S);
    K = PHt.transpose();
    S_llt.solveInPlace(K);
    K.transposeInPlace();
    W.noalias() = K * S_llt.matrixL();
    region.hphiTransposed(kRows).noalias() = region.phiTransposed() * H_A.transpose();
    region.stageUpdate(S_llt.matrixL(), nu, W);
    region.commitUpdate();
    P_AA.triangularView<Eigen::Lower>() -= K * PHt.transpose();  // P_AA -= K S K^T
    benchmark::DoNotOptimize(P_AA.data());
    benchmark::ClobberMemory();
  }
  state.counters["n"] = stateDim(state);
  state.counters["a"] = kActive;
}

void BM_CompressedGlobalUpdate(benchmark::State& state) {
  const int n = stateDim(state);
  const Eigen::MatrixXd P0 = covariance(n);
  const Eigen::VectorXd x0 = Eigen::VectorXd::Zero(n);
  const Eigen::MatrixXd H_A = randomMatrix(kRows, kActive, 4);
  const Eigen::MatrixXd W = 1e-3 * randomMatrix(kActive, kRows, 5);
  const Eigen::LLT<Eigen::MatrixXd> S_llt(Eigen::MatrixXd::Identity(kRows, kRows) * 4.0);
  const Eigen::VectorXd nu = 0.01 * randomMatrix(kRows, 1, 6);
  sylva::detail::CompressedRegion region;
  Eigen::MatrixXd P = P0;
  Eigen::VectorXd x = x0;
  for (auto _ : state) {
    state.PauseTiming();
    P = P0;
    x = x0;
    region.begin(kActive);
    for (int step = 0; step < 10; ++step) {
      region.hphiTransposed(kRows).noalias() = region.phiTransposed() * H_A.transpose();
      region.stageUpdate(S_llt.matrixL(), nu, W);
      region.commitUpdate();
    }
    state.ResumeTiming();
    region.globalUpdate(P, x);
    benchmark::DoNotOptimize(P.data());
    benchmark::ClobberMemory();
  }
  state.counters["n"] = n;
  state.counters["a"] = kActive;
}

void mapSizes(benchmark::internal::Benchmark* b) {
  for (int N : {50, 200, 500, 1000, 2000}) b->Arg(N);
}

}  // namespace

BENCHMARK(BM_PlainRankUpdate)->Apply(mapSizes)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_CompressedLocalStep)->Apply(mapSizes)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_CompressedGlobalUpdate)->Apply(mapSizes)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_LapOnePlain)->Arg(2000)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_LapOneCompressed)->Args({2000, 50, 40})->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_WholeRunAgreement)->Args({1000, 50, 40})->Args({2000, 50, 40})->Unit(benchmark::kSecond)->Iterations(1);
// Regions whose centre lies 10 m short of their edge (the sensor's range) ahead of the robot:
// a region entered there holds what the robot sees, and is left after r + ahead metres.
BENCHMARK(BM_WholeRunRegions)
    ->Args({2000, 30, 20})
    ->Args({2000, 40, 30})
    ->Args({2000, 50, 40})
    ->Args({2000, 60, 50})
    ->Args({2000, 80, 70})
    ->Args({2000, 100, 90})
    ->Args({2000, 120, 110})
    ->Unit(benchmark::kSecond)
    ->Iterations(1);
BENCHMARK(BM_LapTwoPlain)->Arg(200)->Arg(2000)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_LapTwoCompressed)
    ->Args({200, 30, 0})
    ->Args({2000, 20, 0})
    ->Args({2000, 30, 0})
    ->Args({2000, 50, 0})
    ->Args({2000, 80, 0})
    ->Args({2000, 30, 20})
    ->Args({2000, 50, 40})
    ->Args({2000, 80, 70})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);

int main(int argc, char** argv) { return sylva_bench::runBenchmarks(argc, argv); }
