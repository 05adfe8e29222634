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
///
/// Setup (outside the timed loop): the scenario is simulated and both runs are driven to the
/// end of lap 1. Updates measure z = z_hat +/- a small fixed offset with alternating sign so
/// the state stays bounded however often they repeat. Frames are timed on a fresh copy of
/// the runner each iteration (the copy is excluded with PauseTiming).

#include <benchmark/benchmark.h>

#include <cstdio>
#include <memory>

#include <sylva/sim/forest_scenario.hpp>

#include "../examples/forest_slam/monocular_tree_slam.hpp"

namespace {

using forest_slam::MonocularTreeSlam;
using sylva::Id;
using sylva::Mat;
using sylva::Vec;

struct Setup {
  sylva::sim::ForestScenario scenario;
  std::unique_ptr<MonocularTreeSlam> with_width, without_width;
  int next_frame = 0;

  Setup()
      : scenario(sylva::sim::makeForestScenario(sylva::sim::ForestScenarioOptions{}, forest_slam::kDefaultForestSeed)) {
    const Mat<13, 13> P0 = forest_slam::initialCameraCovariance();
    forest_slam::TreeSlamOptions options;
    options.pipeline = forest_slam::WidthPipeline::kAfterXyz;
    with_width = std::make_unique<MonocularTreeSlam>(options, scenario.frames.front().state, P0);
    options.pipeline = forest_slam::WidthPipeline::kNone;
    without_width = std::make_unique<MonocularTreeSlam>(options, scenario.frames.front().state, P0);
    const auto& frames = scenario.frames;
    for (int k = 0; k < static_cast<int>(frames.size()) && frames[k].lap == 0; ++k) {
      const double dt = k == 0 ? 0.0 : frames[k].t_s - frames[k - 1].t_s;
      with_width->processFrame(dt, scenario.observations[k]);
      without_width->processFrame(dt, scenario.observations[k]);
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
    const Vec<Model::kDim> z = model(ekf.robotMean(), ekf.template landmarkMean<Landmark>(id)) + delta;
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
    benchmark::DoNotOptimize(slam.processFrame(dt, s.scenario.observations[k]));
  }
  state.counters["state_dim"] = start.filter().dim();
  state.counters["trees_in_frame"] = static_cast<double>(s.scenario.observations[k].size());
}

void BM_FrameWithWidth(benchmark::State& state) { timeFrame(state, *setup().with_width); }
void BM_FrameWithoutWidth(benchmark::State& state) { timeFrame(state, *setup().without_width); }

BENCHMARK(BM_TreeWidthUpdate)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_PinholePointUpdate)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_FrameWithWidth)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_FrameWithoutWidth)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
