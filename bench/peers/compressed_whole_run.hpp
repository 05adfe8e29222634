#pragma once
/// @file
/// `sylva_peers::runCompressedWhole`: every step of a circle world through sylva's replica of
/// MRPT's kfEKFAlaDavison fusion (sylva_peer.hpp) on a filter that may compress, then a final
/// `synchronize()`, with where the compressed run's time goes (`WholeRunSplit`). Shared by
/// bench_compressed_ekf (plain against compressed) and bench_peers (MRPT against compressed),
/// so that both report the same split and the same floor.
///
/// The floor: a global update with an active part of a rows and b rows outside it costs
/// b (b + 1) a flops for the lower triangle of (V psi) V^T and 4 b a^2 for V psi and V phi^T
/// (detail::CompressedRegion::globalUpdate), counted from the filter's sizes before the step
/// in which it runs. Those flops at the GEMM peak (common/machine_limit.hpp) are the least time the
/// run's global updates can take with Eigen's kernels on this build and machine.

#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <vector>

#include "common/machine_limit.hpp"
#include "sylva_peer.hpp"

namespace sylva_peers {

/// The compressed run's time split between steps without a global update and steps with one
/// (the final synchronize() among them), and its global updates' flops.
struct WholeRunSplit {
  double local_s = 0.0;
  double global_s = 0.0;
  double global_flops = 0.0;
  long global_updates = 0;
  long max_per_step = 0;  ///< most global updates in one step (their flops use the sizes before it)

  void addGlobalUpdates(int a, int n, long updates) {
    const double b = n - a;
    global_flops += static_cast<double>(updates) * (b * (b + 1.0) * a + 4.0 * b * a * a);
    global_updates += updates;
    max_per_step = std::max(max_per_step, updates);
  }
};

/// Runs every step of `steps` on `ekf` (plain or compressed) with the kfEKFAlaDavison fusion,
/// then `synchronize()` (a no-op for a plain filter); returns the seconds it took. With
/// `split`, each step is timed alone and sorted into it.
inline double runCompressedWhole(OdometrySlam& ekf, const std::vector<sylva_bench::SylvaStep>& steps,
                                 const sylva::Gaussian<3>& odometry_noise, double dt_s, WholeRunSplit* split) {
  using Clock = std::chrono::steady_clock;
  const auto since = [](Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); };
  PeerScratch scratch;
  const auto t0 = Clock::now();
  for (const sylva_bench::SylvaStep& step : steps) {
    const int a = ekf.activeDim(), n = ekf.dim();
    const long before = ekf.globalUpdates();
    const auto t_step = Clock::now();
    runPeerStep(ekf, step, odometry_noise, dt_s, SylvaFusion::kAlaDavison, scratch);
    if (split == nullptr) continue;
    const double s = since(t_step);
    const long updates = ekf.globalUpdates() - before;
    (updates > 0 ? split->global_s : split->local_s) += s;
    if (updates > 0) split->addGlobalUpdates(a, n, updates);
  }
  const int a = ekf.activeDim(), n = ekf.dim();
  const long before = ekf.globalUpdates();
  const auto t_sync = Clock::now();
  ekf.synchronize();
  if (split != nullptr) {
    split->global_s += since(t_sync);
    split->addGlobalUpdates(a, n, ekf.globalUpdates() - before);
  }
  return since(t0);
}

/// The split's counters on a benchmark, with the GEMM peak measured now and the floor:
/// local_steps_s, global_steps_s, global_flops, global_updates, max_global_updates_per_step,
/// gemm_gflops, global_floor_s (the flops at that peak).
inline void setSplitCounters(benchmark::State& state, const WholeRunSplit& split) {
  const double gflops = sylva_bench::gemmPeakGflops();
  state.counters["local_steps_s"] = split.local_s;
  state.counters["global_steps_s"] = split.global_s;
  state.counters["global_flops"] = split.global_flops;
  state.counters["global_updates"] = static_cast<double>(split.global_updates);
  state.counters["max_global_updates_per_step"] = static_cast<double>(split.max_per_step);
  state.counters["gemm_gflops"] = gflops;
  state.counters["global_floor_s"] = split.global_flops / (gflops * 1e9);
}

}  // namespace sylva_peers
