/// @file
/// One step of 2D EKF-SLAM against the map size N, beside this machine's bounds measured in
/// the same binary and run. The scenario is bench/scenario/circle_world.hpp: a robot on a
/// circle among N landmarks at constant density (about 12 in view per step), odometry
/// (`sylva::Odometry2D`) and range-bearing measurements with known ids. Lap 1 builds the map
/// (state dimension n = 3 + 2N); lap 2 is timed.
///
/// Families (the argument is N):
///   BM_StepBatched            `Ekf<Odometry2D, Point2>`: predict, then all of the step's
///                             observations in one batched update (`Fusion::kBatched`)
///   BM_StepSequential         the same filter, one update per observation
///                             (`Fusion::kSequential`)
///   BM_StepBatchedUnusedTypes `Ekf<Odometry2D, Point2, Point3, TreeXYZR>` on the same steps:
///                             the extra landmark types are present but unused, so any
///                             difference to BM_StepBatched is the price of generality
///   BM_PairedUnusedTypes      BM_StepBatched and BM_StepBatchedUnusedTypes paired step by step:
///                             each iteration runs the same step through both filters, in
///                             alternating order; counter `ratio` (the mixed filter's time over
///                             the plain one's, summed over the repetition)
///   BM_PairedThreads          the same pairing of BM_StepBatched on the calling thread alone and
///                             with a sylva::ThreadPool of 2 (Ekf::setParallel), in wall-clock
///                             time; counter `speedup` (one thread's time over two's)
///   BM_RankUpdateWallOneThread, BM_RankUpdateWallTwoThreads (the argument is n)
///                             the tiled rank-24 update of the lower triangle alone, on one
///                             thread and on two whatever n: where two start to pay
///   BM_BoundFullReadWrite     reads and writes every entry of an n x n matrix of doubles once,
///                             in place: the full-matrix bound of an update that touches all of P
///   BM_BoundLowerReadWrite    the same on the lower triangle only (half the bytes)
///   BM_GemmPeak               C += A B, 512 x 512 x 512 (argument unused): the compute peak,
///                             counter gflops
///   BM_PhasePredict, BM_PhaseLinearize, BM_PhaseRankUpdate
///                             prefixes of the batched step, for where its time goes (below)
///   BM_PhaseGain              the factor of S and the gain W = P H^T L^-T alone, at the step's
///                             n and rank (below)
///   BM_PairedGain             (the argument is n) the gain P H^T L^-T by a triangular solve
///                             and by L^-1 and a product, paired; counter `ratio`: evidence for
///                             SymmetricUpdate::kGainBySolve
///
/// One iteration of a step family is one step of lap 2: iteration i runs step i mod K of
/// lap 2 (K = min(lap length, 40)), starting again from a copy of the end-of-lap-1 filter
/// every K iterations (the copy is outside the timing). The end-of-lap-1 filter is built once
/// per N and filter type, outside the timing. Counters: n (state dimension) and observations
/// per step.

#include <benchmark/benchmark.h>

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <algorithm>
#include <chrono>
#include <vector>

#include "common/build_context.hpp"
#include "scenario/sylva_circle_slam.hpp"
#include "sylva/core/thread_pool.hpp"
#include "sylva/detail/lower_rank_update.hpp"
#include "sylva/filter/linearization.hpp"
#include "sylva/filter/update_form.hpp"
#include "sylva/landmarks/point3.hpp"
#include "sylva/landmarks/tree_xyzr.hpp"

namespace {

using sylva_bench::SylvaStep;

using PointFilter = sylva::Ekf<sylva::Odometry2D, sylva::Point2>;
using MixedFilter = sylva::Ekf<sylva::Odometry2D, sylva::Point2, sylva::Point3, sylva::TreeXYZR>;

constexpr int kMaxTimedSteps = 40;

using sylva_bench::endOfLapOne;
using sylva_bench::World;
using sylva_bench::worldOf;

/// Times `body(ekf, step, scratch)` on the timed steps of lap 2, restarting from a copy of
/// the end-of-lap-1 filter every K iterations (outside the timing).
template <typename Filter, typename Body>
void timeLapTwo(benchmark::State& state, sylva::Parallel* parallel, const Body& body) {
  const int landmarks = static_cast<int>(state.range(0));
  const World& w = worldOf(landmarks);
  const Filter& start = endOfLapOne<Filter>(landmarks);
  const int first = w.world.lapBegin(1);
  const int timed = std::min(kMaxTimedSteps, w.world.stepsPerLap());
  Filter ekf = start;
  ekf.setParallel(parallel);
  sylva_bench::StepScratch scratch;
  int k = 0;
  long observations = 0;
  for (auto _ : state) {
    if (k == timed) {
      state.PauseTiming();
      ekf = start;
      ekf.setParallel(parallel);  // the copy took start's (none)
      k = 0;
      state.ResumeTiming();
    }
    const SylvaStep& step = w.steps[static_cast<std::size_t>(first + k)];
    body(ekf, step, scratch);
    observations += static_cast<long>(step.observations.size());
    ++k;
    benchmark::ClobberMemory();
  }
  state.counters["N"] = landmarks;
  state.counters["n"] = start.dim();
  state.counters["observations_per_step"] =
      static_cast<double>(observations) / static_cast<double>(std::max<benchmark::IterationCount>(1, state.iterations()));
}

template <typename Filter>
void timeSteps(benchmark::State& state, sylva::Fusion fusion, sylva::Parallel* parallel = nullptr) {
  const World& w = worldOf(static_cast<int>(state.range(0)));
  const auto noise = w.world.odometryNoise();
  const double dt = w.world.config().dt_s;
  timeLapTwo<Filter>(state, parallel, [&](Filter& ekf, const SylvaStep& step, sylva_bench::StepScratch& scratch) {
    sylva_bench::runStep(ekf, step, noise, dt, fusion, scratch);
  });
}

void BM_StepBatched(benchmark::State& state) { timeSteps<PointFilter>(state, sylva::Fusion::kBatched); }
void BM_StepSequential(benchmark::State& state) { timeSteps<PointFilter>(state, sylva::Fusion::kSequential); }
void BM_StepBatchedUnusedTypes(benchmark::State& state) { timeSteps<MixedFilter>(state, sylva::Fusion::kBatched); }

/// Two filters run the same steps of lap 2, step by step: each iteration runs one step through
/// `a` and then `b`, or `b` and then `a` (alternating, so neither always finds the caches as the
/// other left them), each timed alone by a steady clock. Timing the two within milliseconds of
/// each other cancels what a shared machine does over seconds (another job's burst, frequency
/// changes), which separate benchmarks interleaved at random only spread over repetitions.
/// Counter `name`: the sum of a's times over the sum of b's; `a_seconds` and `b_seconds`: each
/// one's mean time per step. Both restart from their copies of the end of lap 1 every K steps,
/// outside the timing.
template <typename FilterA, typename FilterB>
void timePaired(benchmark::State& state, sylva::Parallel* parallel_a, sylva::Parallel* parallel_b, const char* name) {
  using Clock = std::chrono::steady_clock;
  const int landmarks = static_cast<int>(state.range(0));
  const World& w = worldOf(landmarks);
  const FilterA& start_a = endOfLapOne<FilterA>(landmarks);
  const FilterB& start_b = endOfLapOne<FilterB>(landmarks);
  const auto noise = w.world.odometryNoise();
  const double dt = w.world.config().dt_s;
  const int first = w.world.lapBegin(1);
  const int timed = std::min(kMaxTimedSteps, w.world.stepsPerLap());
  FilterA a = start_a;
  FilterB b = start_b;
  a.setParallel(parallel_a);
  b.setParallel(parallel_b);
  sylva_bench::StepScratch scratch_a;
  sylva_bench::StepScratch scratch_b;
  double seconds_a = 0.0;
  double seconds_b = 0.0;
  int k = 0;
  int cycle = 0;
  const auto run = [&](auto& ekf, sylva_bench::StepScratch& scratch, const SylvaStep& step) {
    const auto t0 = Clock::now();
    sylva_bench::runStep(ekf, step, noise, dt, sylva::Fusion::kBatched, scratch);
    benchmark::ClobberMemory();
    return std::chrono::duration<double>(Clock::now() - t0).count();
  };
  for (auto _ : state) {
    if (k == timed) {
      state.PauseTiming();
      a = start_a;
      b = start_b;
      a.setParallel(parallel_a);  // the copies took their starts' (none)
      b.setParallel(parallel_b);
      k = 0;
      ++cycle;
      state.ResumeTiming();
    }
    const SylvaStep& step = w.steps[static_cast<std::size_t>(first + k)];
    // Which goes first alternates from one iteration to the next and, for the same step, from
    // one pass over the K steps to the next (K may be even).
    if ((k + cycle) % 2 == 0) {
      seconds_a += run(a, scratch_a, step);
      seconds_b += run(b, scratch_b, step);
    } else {
      seconds_b += run(b, scratch_b, step);
      seconds_a += run(a, scratch_a, step);
    }
    ++k;
  }
  state.counters["N"] = landmarks;
  state.counters["n"] = start_a.dim();
  state.counters[name] = seconds_b > 0.0 ? seconds_a / seconds_b : 0.0;
  const double steps = static_cast<double>(std::max<benchmark::IterationCount>(1, state.iterations()));
  state.counters["a_seconds"] = seconds_a / steps;
  state.counters["b_seconds"] = seconds_b / steps;
}
void BM_PairedUnusedTypes(benchmark::State& state) {
  timePaired<MixedFilter, PointFilter>(state, nullptr, nullptr, "ratio");
}
void BM_PairedThreads(benchmark::State& state) {
  static sylva::ThreadPool pool(2);
  timePaired<PointFilter, PointFilter>(state, nullptr, &pool, "speedup");
}

/// Where the time of a batched step goes, on the steps BM_StepBatched times (restarted from
/// the end of lap 1 every K steps, as there). Each family runs a prefix of the step, so
/// that differences of families of the same run give the phases:
///   BM_PhasePredict     the prediction (and the split of the step's observations into known
///                       and new landmarks)
///   BM_PhaseLinearize   the prediction, then `linearize` for every observation of a known
///                       landmark: what the batched update does first
///   BM_PhaseRankUpdate  P -= W W^T on the lower triangle of the step's n x n P, with W of the
///                       step's own rank (2 per known observation): the part of the update
///                       whose flops are the compute floor of the machine limit
/// so that, with BM_StepBatched: linearization = Linearize - Predict; the update without its
/// rank update (P H^T, S and its factor, the gain, the mean) = StepBatched - Linearize -
/// RankUpdate. Counter flops_per_step: n (n + 1) k, the rank-k lower update's multiplies and
/// adds, averaged over the steps (with BM_GemmPeak's rate: the compute floor).
enum class Prefix { kPredict, kLinearize };

void timePrefix(benchmark::State& state, Prefix prefix) {
  const World& w = worldOf(static_cast<int>(state.range(0)));
  const auto noise = w.world.odometryNoise();
  const double dt = w.world.config().dt_s;
  std::vector<sylva::Linearization<sylva::RangeBearing, PointFilter::kRobotDim>> lins;
  lins.reserve(64);
  const sylva::RangeBearing model;
  timeLapTwo<PointFilter>(state, nullptr, [&](PointFilter& ekf, const SylvaStep& step, sylva_bench::StepScratch& scratch) {
    sylva_bench::predictStep(ekf, step, noise, dt);
    sylva_bench::splitObservations(ekf, step, scratch);
    if (prefix == Prefix::kLinearize) {
      lins.clear();
      for (const auto& obs : scratch.known) lins.push_back(ekf.linearize(model, obs.id));
      benchmark::DoNotOptimize(lins.data());
    }
  });
}
void BM_PhasePredict(benchmark::State& state) { timePrefix(state, Prefix::kPredict); }
void BM_PhaseLinearize(benchmark::State& state) { timePrefix(state, Prefix::kLinearize); }

/// The rank of each timed step of lap 2 at map size `landmarks`: 2 per observation of a
/// landmark already in the end-of-lap-1 map (what BM_PhaseRankUpdate and BM_PhaseGain replay).
std::vector<int> timedStepRanks(int landmarks) {
  const World& w = worldOf(landmarks);
  const PointFilter& start = endOfLapOne<PointFilter>(landmarks);
  const int first = w.world.lapBegin(1);
  const int timed = std::min(kMaxTimedSteps, w.world.stepsPerLap());
  std::vector<int> ranks;
  for (int k = 0; k < timed; ++k) {
    int known = 0;
    for (const auto& obs : w.steps[static_cast<std::size_t>(first + k)].observations) known += start.contains(obs.id) ? 1 : 0;
    ranks.push_back(2 * known);
  }
  return ranks;
}

void BM_PhaseRankUpdate(benchmark::State& state) {
  const int landmarks = static_cast<int>(state.range(0));
  const int n = endOfLapOne<PointFilter>(landmarks).dim();
  const std::vector<int> ranks = timedStepRanks(landmarks);
  const int timed = static_cast<int>(ranks.size());
  double flops = 0.0;
  for (int rank : ranks) flops += static_cast<double>(n) * (n + 1) * rank;
  Eigen::MatrixXd P = Eigen::MatrixXd::Identity(n, n);
  const Eigen::MatrixXd W = Eigen::MatrixXd::Constant(n, *std::max_element(ranks.begin(), ranks.end()), 1e-6);
  int k = 0;
  for (auto _ : state) {
    if (k == timed) k = 0;
    sylva::detail::subtractLowerRankUpdate(P, W.leftCols(ranks[static_cast<std::size_t>(k)]));
    ++k;
    benchmark::ClobberMemory();
  }
  state.counters["N"] = landmarks;
  state.counters["n"] = n;
  state.counters["flops_per_step"] = flops / timed;
  benchmark::DoNotOptimize(P.data());
}

/// The other dense kernel of the batched update, at the same n and ranks as
/// BM_PhaseRankUpdate: the Cholesky factor L of a k x k innovation covariance S, then
/// SymmetricUpdate::increment, the filter's own code for the gain W = P H^T L^-T (n x k, in the
/// form kGainBySolve picks) and the mean's increment. With BM_PhaseRankUpdate it is what any step of this
/// update form computes whatever its bookkeeping costs: their sum against the machine limit
/// says what the step can reach with these kernels (docs/step-limit.md).
void BM_PhaseGain(benchmark::State& state) {
  const int landmarks = static_cast<int>(state.range(0));
  const int n = endOfLapOne<PointFilter>(landmarks).dim();
  const std::vector<int> ranks = timedStepRanks(landmarks);
  const int timed = static_cast<int>(ranks.size());
  const int max_rank = std::max(1, *std::max_element(ranks.begin(), ranks.end()));
  // A well-conditioned S (diagonally dominant) and P H^T of the step's shape; the values do
  // not change the kernels' work.
  const Eigen::MatrixXd S_full = Eigen::MatrixXd::Constant(max_rank, max_rank, 0.1) +
                                 static_cast<double>(max_rank) * Eigen::MatrixXd::Identity(max_rank, max_rank);
  Eigen::MatrixXd PHt_full = Eigen::MatrixXd::Constant(n, max_rank, 1e-3);  // read, not written
  const Eigen::VectorXd nu_full = Eigen::VectorXd::Constant(max_rank, 0.01);
  Eigen::MatrixXd S_buffer(max_rank, max_rank);
  Eigen::VectorXd delta(n);
  sylva::detail::BatchWorkspace<> workspace;
  int k = 0;
  for (auto _ : state) {
    if (k == timed) k = 0;
    const int rank = ranks[static_cast<std::size_t>(k)];
    Eigen::Map<Eigen::MatrixXd> S(S_buffer.data(), rank, rank);
    S = S_full.topLeftCorner(rank, rank);
    Eigen::Map<Eigen::MatrixXd> PHt(PHt_full.data(), n, rank);
    Eigen::LLT<Eigen::Ref<Eigen::MatrixXd>> llt(S);
    const auto W = sylva::SymmetricUpdate::increment<Eigen::Dynamic>(PHt, llt, nu_full.head(rank), workspace, delta);
    benchmark::DoNotOptimize(W.data());
    benchmark::DoNotOptimize(delta.data());
    ++k;
    benchmark::ClobberMemory();
  }
  state.counters["N"] = landmarks;
  state.counters["n"] = n;
}

/// The gain W = P H^T L^-T (n x k, from the Cholesky factor L of a k x k S; the argument is n)
/// formed both ways SymmetricUpdate::increment can form it, paired: each iteration takes the
/// product (L^-1 explicitly, then P H^T (L^-1)^T) and the solve (a triangular solve with L^T on
/// the right, in place on a copy of P H^T), in alternating order, for a rank k cycling through
/// the small-map step's ranks 16-30. Counter `ratio`: the solve's time over the product's,
/// summed over the repetition; counter `filter_solves`: which of the two this build's filter
/// takes (SymmetricUpdate::kGainBySolve, chosen by the packet width on this evidence).
void BM_PairedGain(benchmark::State& state) {
  using Clock = std::chrono::steady_clock;
  const int n = static_cast<int>(state.range(0));
  constexpr int kMaxRank = 30;
  const Eigen::MatrixXd S = Eigen::MatrixXd::Constant(kMaxRank, kMaxRank, 0.1) + kMaxRank * Eigen::MatrixXd::Identity(kMaxRank, kMaxRank);
  const Eigen::MatrixXd L = Eigen::LLT<Eigen::MatrixXd>(S).matrixL();
  const Eigen::MatrixXd PHt = Eigen::MatrixXd::Constant(n, kMaxRank, 1e-3);
  Eigen::MatrixXd L_inv(kMaxRank, kMaxRank);
  Eigen::MatrixXd W_product(n, kMaxRank);
  Eigen::MatrixXd W_solve(n, kMaxRank);
  double seconds_product = 0.0;
  double seconds_solve = 0.0;
  int iteration = 0;
  const auto product = [&](int k) {
    const auto t0 = Clock::now();
    auto L_inv_k = L_inv.topLeftCorner(k, k);
    L_inv_k.setIdentity();
    L.topLeftCorner(k, k).triangularView<Eigen::Lower>().solveInPlace(L_inv_k);
    W_product.leftCols(k).noalias() = PHt.leftCols(k) * L_inv_k.transpose();
    benchmark::ClobberMemory();
    seconds_product += std::chrono::duration<double>(Clock::now() - t0).count();
  };
  const auto solve = [&](int k) {
    const auto t0 = Clock::now();
    auto W_k = W_solve.leftCols(k);
    W_k = PHt.leftCols(k);
    L.topLeftCorner(k, k).transpose().triangularView<Eigen::Upper>().solveInPlace<Eigen::OnTheRight>(W_k);
    benchmark::ClobberMemory();
    seconds_solve += std::chrono::duration<double>(Clock::now() - t0).count();
  };
  for (auto _ : state) {
    const int k = 16 + 2 * (iteration % 8);  // 16, 18, ..., 30
    if ((iteration / 8) % 2 == 0) {
      product(k);
      solve(k);
    } else {
      solve(k);
      product(k);
    }
    ++iteration;
  }
  state.counters["n"] = n;
  state.counters["ratio"] = seconds_product > 0.0 ? seconds_solve / seconds_product : 0.0;
  state.counters["filter_solves"] = sylva::SymmetricUpdate::kGainBySolve ? 1.0 : 0.0;
  benchmark::DoNotOptimize(W_product.data());
  benchmark::DoNotOptimize(W_solve.data());
}

/// P -= W W^T on the lower triangle (detail::subtractLowerRankUpdate) for a rank-24 W and an
/// n x n P (the argument is n), on one thread and with a ThreadPool of two whatever n: where
/// a second thread starts to pay (detail::kParallelMinRows).
void timeRankUpdate(benchmark::State& state, sylva::Parallel* parallel) {
  const int n = static_cast<int>(state.range(0));
  Eigen::MatrixXd P = Eigen::MatrixXd::Identity(n, n);
  const Eigen::MatrixXd W = Eigen::MatrixXd::Constant(n, 24, 1e-6);
  for (auto _ : state) {
    sylva::detail::subtractLowerRankUpdate(P, W, parallel, 0);
    benchmark::ClobberMemory();
  }
  state.counters["n"] = n;
  benchmark::DoNotOptimize(P.data());
}
void BM_RankUpdateWallOneThread(benchmark::State& state) { timeRankUpdate(state, nullptr); }
void BM_RankUpdateWallTwoThreads(benchmark::State& state) {
  static sylva::ThreadPool pool(2);
  timeRankUpdate(state, &pool);
}

/// In-place read-modify-write of an n x n matrix (all of it, or its lower triangle): the
/// bytes an update of P must move at least once. The factor alternates so the values stay put.
void timeReadWrite(benchmark::State& state, bool lower_only) {
  const int n = 3 + 2 * static_cast<int>(state.range(0));
  Eigen::MatrixXd P = Eigen::MatrixXd::Constant(n, n, 1.0);
  double factor = 1.0 + 1e-9;
  for (auto _ : state) {
    if (lower_only) {
      for (int j = 0; j < n; ++j) P.col(j).tail(n - j) *= factor;
    } else {
      P *= factor;
    }
    factor = 1.0 / factor;
    benchmark::ClobberMemory();
  }
  const double bytes = 2.0 * sizeof(double) * (lower_only ? 0.5 * n * (n + 1.0) : double(n) * n);
  state.counters["N"] = static_cast<double>(state.range(0));
  state.counters["n"] = n;
  state.counters["bytes_per_second"] = benchmark::Counter(bytes, benchmark::Counter::kIsIterationInvariantRate);
  benchmark::DoNotOptimize(P.data());
}

void BM_BoundFullReadWrite(benchmark::State& state) { timeReadWrite(state, false); }
void BM_BoundLowerReadWrite(benchmark::State& state) { timeReadWrite(state, true); }

void BM_GemmPeak(benchmark::State& state) {
  constexpr int kSize = 512;
  const Eigen::MatrixXd A = Eigen::MatrixXd::Constant(kSize, kSize, 1e-3);
  const Eigen::MatrixXd B = Eigen::MatrixXd::Constant(kSize, kSize, 1e-3);
  Eigen::MatrixXd C = Eigen::MatrixXd::Zero(kSize, kSize);
  for (auto _ : state) {
    C.noalias() += A * B;
    benchmark::ClobberMemory();
  }
  state.counters["gflops"] =
      benchmark::Counter(2e-9 * kSize * kSize * kSize, benchmark::Counter::kIsIterationInvariantRate);
  benchmark::DoNotOptimize(C.data());
}

void mapSizes(benchmark::internal::Benchmark* b) {
  for (int landmarks : {50, 100, 200, 500, 1000, 2000}) b->Arg(landmarks);
}

BENCHMARK(BM_StepBatched)->Apply(mapSizes)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_StepSequential)->Apply(mapSizes)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_StepBatchedUnusedTypes)->Apply(mapSizes)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_PairedUnusedTypes)->Apply(mapSizes)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_PairedThreads)->Apply(mapSizes)->UseRealTime()->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_RankUpdateWallOneThread)->DenseRange(64, 1024, 64)->Arg(2003)->Arg(4003)->UseRealTime()->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_RankUpdateWallTwoThreads)->DenseRange(64, 1024, 64)->Arg(2003)->Arg(4003)->UseRealTime()->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_PhasePredict)->Apply(mapSizes)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_PhaseLinearize)->Apply(mapSizes)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_PhaseRankUpdate)->Apply(mapSizes)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_PhaseGain)->Apply(mapSizes)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_PairedGain)->Arg(103)->Arg(203)->Arg(403)->Arg(1003)->Arg(2003)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_BoundFullReadWrite)->Apply(mapSizes)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_BoundLowerReadWrite)->Apply(mapSizes)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_GemmPeak)->Unit(benchmark::kMicrosecond);

}  // namespace

int main(int argc, char** argv) { return sylva_bench::runBenchmarks(argc, argv); }
