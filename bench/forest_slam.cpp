/// @file
/// Cost of monocular tree SLAM at the default forest size (examples/forest_slam, its default seed):
/// the filter `Ekf<ConstantVelocity3D, InverseDepth, Point3, TreeXYZR>` as it stands after
/// the first lap of the default scenario (about 70 trees mapped, state dimension ~300).
///
///   BM_TreeWidthUpdate      one TreeWidth update ([u, v, w]) of an XYZ-R tree
///   BM_PinholePointUpdate   one PinholePoint<Point3> update ([u, v]) of an XYZ tree in the
///                           same filter: the baseline of the ratio
///   BM_FrameWithWidth       one full frame of the run with the tree-width sensor: predict,
///                           batched updates of every tree in view, life cycle, new trees
///   BM_FrameWithoutWidth    the same frame of the run without it (baseline)
///   BM_FrameSplit/<pipeline> the frames of lap 2 of a run (the thesis' pipeline, or the one
///                           without width), each timed by phase through
///                           MonocularTreeSlam::setProfile: counters predict_us, gating_us,
///                           point_updates_us, width_updates_us, reparametrize_us, add_us per
///                           frame (and their sum, profiled_us). One iteration is the whole lap.
///   BM_FrameFusion/<0|1>    the frames of lap 2 of the thesis' pipeline, fused batched (0) or
///                           sequentially (1), against the frame's machine limit (below); one
///                           iteration is the whole lap
///
/// Setup (outside the timed loop): the scenario is simulated and both runs are driven to the
/// end of lap 1. Updates measure z = z_hat +/- a small fixed offset with alternating sign so
/// the state stays bounded however often they repeat. Frames are timed on a fresh copy of
/// the runner each iteration (the copy is excluded with PauseTiming).

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdio>
#include <memory>

#include <sylva/sim/forest_scenario.hpp>

#include "common/machine_limit.hpp"
#include "monocular_tree_slam.hpp"

namespace {

using forest_slam::MonocularTreeSlam;
using sylva::Id;
using sylva::Mat;
using sylva::Vec;

struct Setup {
  sylva::sim::ForestScenario scenario;
  std::vector<std::vector<forest_slam::TrunkSighting>> sightings;  ///< per frame, the pipeline's input
  std::unique_ptr<MonocularTreeSlam> with_width, without_width;
  int next_frame = 0;

  Setup()
      : scenario(sylva::sim::makeForestScenario(sylva::sim::ForestScenarioOptions{}, forest_slam::kDefaultForestSeed)) {
    for (const auto& frame : scenario.observations) sightings.push_back(forest_slam::sightingsOf(frame));
    const Mat<13, 13> P0 = forest_slam::initialCameraCovariance();
    forest_slam::TreeSlamOptions options;
    options.pipeline = forest_slam::WidthPipeline::kAfterXyz;
    with_width = std::make_unique<MonocularTreeSlam>(options, scenario.frames.front().state, P0);
    options.pipeline = forest_slam::WidthPipeline::kNone;
    without_width = std::make_unique<MonocularTreeSlam>(options, scenario.frames.front().state, P0);
    const auto& frames = scenario.frames;
    for (int k = 0; k < static_cast<int>(frames.size()) && frames[k].lap == 0; ++k) {
      const double dt = k == 0 ? 0.0 : frames[k].t_s - frames[k - 1].t_s;
      with_width->processFrame(dt, sightings[k]);
      without_width->processFrame(dt, sightings[k]);
      next_frame = k + 1;
    }
  }
};

Setup& setup() {
  static Setup s;
  return s;
}

template <typename Landmark>
Id firstOfType(const MonocularTreeSlam::Filter& ekf) {
  for (const auto& s : ekf.slots())
    if (ekf.holds<Landmark>(s.id)) return s.id;
  return -1;
}

template <typename Model, typename Landmark>
void timeUpdate(benchmark::State& state, const Model& model) {
  MonocularTreeSlam::Filter ekf = setup().with_width->filter();
  const Id id = firstOfType<Landmark>(ekf);
  if (id < 0) {
    state.SkipWithError("no landmark of this type after lap 1");
    return;
  }
  Vec<Model::kDim> delta = Vec<Model::kDim>::Constant(0.3);
  const auto noise = sylva::Gaussian<Model::kDim>::sigmas(Vec<Model::kDim>::Constant(1.0));
  for (auto _ : state) {
    const Vec<Model::kDim> z = model(sylva::ConstantVelocity3D::pose(ekf.robotMean()), ekf.template landmarkMean<Landmark>(id)) + delta;
    ekf.update(model, id, z, noise);
    delta = -delta;
    benchmark::ClobberMemory();
  }
  state.counters["state_dim"] = ekf.dim();
  state.counters["landmarks"] = ekf.landmarkCount();
}

void BM_TreeWidthUpdate(benchmark::State& state) {
  timeUpdate<sylva::TreeWidth, sylva::TreeXYZR>(state, sylva::TreeWidth(forest_slam::TreeSlamOptions{}.camera));
}

void BM_PinholePointUpdate(benchmark::State& state) {
  timeUpdate<sylva::PinholePoint<sylva::Point3>, sylva::Point3>(
      state, sylva::PinholePoint<sylva::Point3>(forest_slam::TreeSlamOptions{}.camera));
}

void timeFrame(benchmark::State& state, const MonocularTreeSlam& start) {
  const Setup& s = setup();
  const int k = s.next_frame;
  const double dt = s.scenario.frames[k].t_s - s.scenario.frames[k - 1].t_s;
  for (auto _ : state) {
    state.PauseTiming();
    MonocularTreeSlam slam = start;
    state.ResumeTiming();
    benchmark::DoNotOptimize(slam.processFrame(dt, s.sightings[k]));
  }
  state.counters["state_dim"] = start.filter().dim();
  state.counters["trees_in_frame"] = static_cast<double>(s.scenario.observations[k].size());
}

void BM_FrameWithWidth(benchmark::State& state) { timeFrame(state, *setup().with_width); }
void BM_FrameWithoutWidth(benchmark::State& state) { timeFrame(state, *setup().without_width); }

/// Lap 2 of the scenario from the end-of-lap-1 state of `start`, profiled by phase.
void timeLapByPhase(benchmark::State& state, const MonocularTreeSlam& start) {
  const Setup& s = setup();
  const auto& frames = s.scenario.frames;
  forest_slam::FrameProfile profile;
  for (auto _ : state) {
    state.PauseTiming();
    MonocularTreeSlam slam = start;
    slam.setProfile(&profile);
    state.ResumeTiming();
    for (int k = s.next_frame; k < static_cast<int>(frames.size()) && frames[k].lap == 1; ++k)
      benchmark::DoNotOptimize(slam.processFrame(frames[k].t_s - frames[k - 1].t_s, s.sightings[k]));
  }
  const double per_frame_us = profile.frames > 0 ? 1e6 / profile.frames : 0.0;
  state.counters["frames_per_lap"] = static_cast<double>(profile.frames) / static_cast<double>(state.iterations());
  state.counters["predict_us"] = profile.predict_s * per_frame_us;
  state.counters["gating_us"] = profile.gating_s * per_frame_us;
  state.counters["point_updates_us"] = profile.point_updates_s * per_frame_us;
  state.counters["width_updates_us"] = profile.width_updates_s * per_frame_us;
  state.counters["reparametrize_us"] = profile.reparametrize_s * per_frame_us;
  state.counters["add_us"] = profile.add_s * per_frame_us;
  state.counters["profiled_us"] = profile.total_s() * per_frame_us;
  state.counters["state_dim"] = start.filter().dim();
}

/// Lap 2 of the thesis' pipeline from its end-of-lap-1 state, every frame fused as
/// `state.range(0)` says (0: batched, the default; 1: sequential), against the frame's machine
/// limit: the larger of the compute floor, the flops of one rank-k update of the lower
/// triangle per frame (n (n + 1) k, with k the frame's fused rows and n its state dimension),
/// at the GEMM peak, and the memory bound, one read and write of the lower triangle per
/// frame; both measured after the lap in the same program (common/machine_limit.hpp).
void BM_FrameFusion(benchmark::State& state) {
  const bool sequential = state.range(0) == 1;
  const Setup& s = setup();
  const auto& frames = s.scenario.frames;
  double floor_flops = 0.0, rows = 0.0, dims = 0.0;
  int frame_count = 0;
  for (auto _ : state) {
    state.PauseTiming();
    MonocularTreeSlam slam = *s.with_width;
    slam.setFusion(sequential ? sylva::Fusion::kSequential : sylva::Fusion::kBatched);
    floor_flops = rows = dims = 0.0;
    frame_count = 0;
    state.ResumeTiming();
    for (int k = s.next_frame; k < static_cast<int>(frames.size()) && frames[k].lap == 1; ++k) {
      const int n = slam.filter().dim();
      const forest_slam::FrameReport& report = slam.processFrame(frames[k].t_s - frames[k - 1].t_s, s.sightings[k]);
      floor_flops += static_cast<double>(n) * (n + 1.0) * report.fused_rows;  // a few flops: timed
      rows += report.fused_rows;
      dims += n;
      ++frame_count;
    }
  }
  const double gflops = sylva_bench::gemmPeakGflops();
  const int mean_dim = frame_count > 0 ? static_cast<int>(dims / frame_count + 0.5) : 0;
  const double memory_s = sylva_bench::lowerReadWriteSeconds(mean_dim);
  const double floor_s = frame_count > 0 ? floor_flops / frame_count / (gflops * 1e9) : 0.0;
  state.counters["frames_per_lap"] = frame_count;
  state.counters["per_frame_us"] = benchmark::Counter(frame_count / 1e6, benchmark::Counter::kIsIterationInvariantRate |
                                                                             benchmark::Counter::kInvert);
  state.counters["rows_per_frame"] = frame_count > 0 ? rows / frame_count : 0.0;
  state.counters["state_dim"] = mean_dim;
  state.counters["gemm_gflops"] = gflops;
  state.counters["compute_floor_us"] = 1e6 * floor_s;
  state.counters["memory_bound_us"] = 1e6 * memory_s;
  state.counters["limit_us"] = 1e6 * std::max(floor_s, memory_s);
}

void BM_FrameSplitWithWidth(benchmark::State& state) { timeLapByPhase(state, *setup().with_width); }
void BM_FrameSplitWithoutWidth(benchmark::State& state) { timeLapByPhase(state, *setup().without_width); }

BENCHMARK(BM_TreeWidthUpdate)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_PinholePointUpdate)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_FrameWithWidth)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_FrameWithoutWidth)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_FrameFusion)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FrameSplitWithWidth)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FrameSplitWithoutWidth)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
