/// @file
/// The compressed EKF's kernel (sylva::detail::CompressedRegion) against the plain batched
/// update's kernel, on the sizes of the circle world's step (bench/slam_step.cpp): N landmarks
/// of 2 coordinates (n = 3 + 2N), 12 observations of 2 rows a step (m = 24), and an active
/// region of the robot and 20 landmarks (a = 43). Kernels only: they bound what a compressed
/// step can gain; bench/slam_step.cpp times the filter's compressed steps.
///
/// Families (the argument is N):
///   BM_PlainRankUpdate        P -= W W^T on the n x n lower triangle, W n x 24: the part of
///                             a plain batched step that grows as n^2
///   BM_CompressedLocalStep    what a compressed step does instead: the active block's own
///                             update (S, K_A, P_AA -= K_A S K_A^T, a x a) and the region's
///                             accumulators (CompressedRegion::stageUpdate); independent of N
///   BM_CompressedGlobalUpdate CompressedRegion::globalUpdate after a local phase: once per
///                             region change, O(n^2 a)
/// A compressed run whose regions last L steps costs about
/// (LocalStep + GlobalUpdate / L) per step, against PlainRankUpdate (plus the costs both share).

#include <benchmark/benchmark.h>

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <random>

#include "common/build_context.hpp"
#include "sylva/detail/compressed_region.hpp"
#include "sylva/detail/lower_rank_update.hpp"

namespace {

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

int main(int argc, char** argv) { return sylva_bench::runBenchmarks(argc, argv); }
