/// @file
/// Side-by-side step times of sylva and MRPT's EKF-SLAM (`mrpt::slam::CRangeBearingKFSLAM2D`)
/// on the circle world (bench/scenario/circle_world.hpp), for N landmarks.
///
/// Families (one benchmark per family and N; N in --peers_sizes, default 50,100,...,2000):
///   mrpt_naive        MRPT, KF_options.method = kfEKFNaive (MRPT's default)
///   mrpt_davison      MRPT, kfEKFAlaDavison
///   sylva_batched     sylva, all of a step's measurements in one `Ekf::update` (the estimator
///                     of kfEKFNaive)
///   sylva_davison     sylva, the scalar-by-scalar fusion of kfEKFAlaDavison reproduced
///                     through sylva's API (sylva_peer.hpp)
///   sylva_sequential  sylva, one 2-D update per measurement (a third estimator, for reference)
/// sylva's families exist in two builds of this file: bench_peers_native (-O3 -march=native)
/// and bench_peers_baseline (-O3 -march=x86-64, the instruction set Debian builds MRPT for).
/// MRPT is the same Debian library in both.
///
/// What one "step" is: everything a filter does with one step of the world: the prediction
/// with the odometry increment, the update with the step's measurements of landmarks in the
/// map (about 12), and the augmentation with landmarks seen for the first time (none in
/// lap 2, whose steps are timed). For MRPT that is one call of processActionObservation with
/// the step's action and sensory frame, built beforehand; for sylva, `runPeerStep` with the
/// step's observations, converted beforehand.
///
/// Timing: the timed window is --peers_steps (default 10) consecutive lap-2 steps, chosen as
/// the window whose mean number of measurements is closest to the lap's mean (about 12; the
/// choice depends only on the world, never on timings), so every N is timed on typical steps.
/// Setup (not timed) runs sylva batched from the start up to the window (lap 1 builds the
/// map) and keeps that state (the "snapshot"); MRPT gets the same state through
/// MrptPeer::setState. Each iteration restores the snapshot (not timed), then times the
/// window's steps with a steady clock (manual time), so every iteration starts from the same
/// state and runs the same steps. The reported time of an iteration is the whole window; the
/// counter ms_per_step is the mean time of one step, obs_per_step the window's mean number of
/// measurements.
///
/// Checks (a benchmark that fails one reports an error instead of a time):
///   - before anything at a given N is timed, MRPT kfEKFNaive and sylva batched run the first
///     step of the window from the snapshot, as do MRPT kfEKFAlaDavison and sylva's replica of it,
///     and their states must agree (mean to 1e-9, covariance to 1e-9 of max |P|);
///   - after every timed iteration, the filter's mean must match the reference run of the same
///     steps (sylva batched for the naive pair, sylva's AlaDavison replica for the other pair,
///     sylva sequential for itself) to 1e-9.
///
/// Whole runs (registered only for the sizes of --peers_whole_sizes; none by default, since
/// MRPT's whole run at N = 2000 takes over half an hour): every step of both laps from an empty map, one
/// iteration per repetition, timed as a whole.
///   mrpt_davison_whole             MRPT kfEKFAlaDavison
///   sylva_davison_compressed_whole sylva's replica of that fusion (kAlaDavison above) through
///                                  the compressed EKF, `setCompression(withinRadius(50, 40))`:
///                                  a region of radius 50 m centred 40 m ahead of the robot, the
///                                  region of docs/compressed-ekf.md that saved most on lap 2 of
///                                  this world at N = 2000 (chosen on those lap-2 runs)
/// The compressed run's final state is compared, by landmark id, with MRPT's final state from
/// the same program (mean to 1e-9 of its largest coordinate, covariance to 1e-9 of max |P|;
/// counters max_mean_relative_diff and max_cov_relative_diff; states_agree is 1 within both
/// tolerances, else 0, and the run keeps its time). Counter ms_per_run. The compressed run
/// ends with its final global update (synchronize()) inside the timing, and also reports
/// where its time went and the floor of its global updates at the GEMM peak measured after
/// it (local_steps_s, global_steps_s, global_flops, gemm_gflops, global_floor_s:
/// compressed_whole_run.hpp).
///
/// Extra flags (before Google Benchmark's own):
///   --peers_sizes=50,100,200,500,1000,2000   map sizes N
///   --peers_steps=10                          lap-2 steps per timed iteration
///   --peers_mrpt_max_n=2000                   skip MRPT families above this N
///   --peers_naive_max_n=2000                  skip mrpt_naive above this N (O(n^3) per step)
///   --peers_whole_sizes=                      map sizes N of the whole runs (e.g. 2000)
/// Google Benchmark's --benchmark_min_time applies to the timed (manual) time; a benchmark
/// whose first iteration exceeds it (MRPT at large N) runs that one iteration only.

#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "circle_world.hpp"
#include "compressed_whole_run.hpp"
#include "filter_state.hpp"
#include "mrpt_peer.hpp"
#include "sylva/filter/compression.hpp"
#include "sylva_circle_slam.hpp"
#include "sylva_peer.hpp"

#if defined(__clang__)
#define SYLVA_PEERS_COMPILER "clang++ " __clang_version__
#elif defined(__GNUC__)
#define SYLVA_PEERS_COMPILER "g++ " __VERSION__
#else
#define SYLVA_PEERS_COMPILER "unknown"
#endif
#ifndef SYLVA_PEERS_VARIANT
#define SYLVA_PEERS_VARIANT "unknown"
#endif
#ifndef SYLVA_PEERS_CXX_FLAGS
#define SYLVA_PEERS_CXX_FLAGS "unknown"
#endif

namespace {

using sylva_peers::FilterState;
using sylva_peers::MrptMethod;
using sylva_peers::MrptPeer;
using sylva_peers::SylvaFusion;

constexpr double kMeanTolerance = 1e-9;
constexpr double kCovarianceTolerance = 1e-9;

struct Options {
  std::vector<int> sizes = {50, 100, 200, 500, 1000, 2000};
  int steps = 10;
  int mrpt_max_n = 2000;
  int naive_max_n = 2000;
  std::vector<int> whole_sizes;
};
Options g_options;

enum class Family { kMrptNaive, kMrptDavison, kSylvaBatched, kSylvaDavison, kSylvaSequential };

const char* familyName(Family f) {
  switch (f) {
    case Family::kMrptNaive: return "mrpt_naive";
    case Family::kMrptDavison: return "mrpt_davison";
    case Family::kSylvaBatched: return "sylva_batched";
    case Family::kSylvaDavison: return "sylva_davison";
    case Family::kSylvaSequential: return "sylva_sequential";
  }
  return "?";
}

/// The reference run of the timed steps from the snapshot with one of sylva's fusions.
struct Reference {
  FilterState after_first;          ///< after the first timed step (full state; freed after the check)
  Eigen::VectorXd mean_after_all;   ///< after all timed steps
};

/// Everything for one N, built once (one N at a time is kept: the maps are large).
struct Setup {
  explicit Setup(int landmarks) : world(makeConfig(landmarks)), steps(sylva_bench::sylvaSteps(world)) {
    count = std::min(g_options.steps, world.stepsPerLap());
    first = typicalWindow(world, count);
    auto ekf = sylva_bench::makeOdometrySlam(world);
    sylva_peers::PeerScratch scratch;
    for (int k = 0; k < first; ++k)
      sylva_peers::runPeerStep(ekf, steps[static_cast<std::size_t>(k)], world.odometryNoise(), world.config().dt_s,
                               SylvaFusion::kBatched, scratch);
    snapshot = std::make_unique<sylva_bench::OdometrySlam>(ekf);
    snapshot_state = sylva_peers::stateOf(ekf);
    int measured = 0;
    for (int k = first; k < first + count; ++k)
      measured += static_cast<int>(world.steps()[static_cast<std::size_t>(k)].measurements.size());
    measurements_per_step = static_cast<double>(measured) / count;
    for (SylvaFusion f : {SylvaFusion::kBatched, SylvaFusion::kAlaDavison, SylvaFusion::kSequential})
      references[static_cast<int>(f)] = reference(f);
  }

  /// First step of the `count` consecutive lap-2 steps whose mean number of measurements is
  /// closest to the lap's mean (the earliest such window).
  static int typicalWindow(const sylva_bench::CircleWorld& world, int count) {
    const double target = world.meanMeasurementsPerStep(1);
    const auto size = [&](int k) { return static_cast<double>(world.steps()[static_cast<std::size_t>(k)].measurements.size()); };
    const int begin = world.lapBegin(1);
    const int last = world.lapBegin(2) - count;
    double sum = 0.0;
    for (int k = begin; k < begin + count; ++k) sum += size(k);
    int best = begin;
    double best_gap = std::abs(sum / count - target);
    for (int w = begin + 1; w <= last; ++w) {
      sum += size(w + count - 1) - size(w - 1);
      const double gap = std::abs(sum / count - target);
      if (gap < best_gap - 1e-12) {
        best_gap = gap;
        best = w;
      }
    }
    return best;
  }

  static sylva_bench::CircleWorldConfig makeConfig(int landmarks) {
    sylva_bench::CircleWorldConfig config;
    config.landmarks = landmarks;
    return config;
  }

  Reference reference(SylvaFusion fusion) const {
    Reference r;
    sylva_bench::OdometrySlam ekf = *snapshot;
    sylva_peers::PeerScratch scratch;
    for (int k = first; k < first + count; ++k) {
      runStep(ekf, k, fusion, scratch);
      if (k == first && fusion != SylvaFusion::kSequential) r.after_first = sylva_peers::stateOf(ekf);
    }
    r.mean_after_all = ekf.mean();
    return r;
  }

  void runStep(sylva_bench::OdometrySlam& ekf, int k, SylvaFusion fusion, sylva_peers::PeerScratch& scratch) const {
    sylva_peers::runPeerStep(ekf, steps[static_cast<std::size_t>(k)], world.odometryNoise(), world.config().dt_s, fusion,
                             scratch);
  }

  MrptPeer& mrpt(MrptMethod method) {
    auto& slot = method == MrptMethod::kNaive ? mrpt_naive : mrpt_davison;
    if (!slot) slot = std::make_unique<MrptPeer>(world, method);
    return *slot;
  }

  /// The quick agreement check of the file comment (once per N); empty when they agree.
  const std::string& agreement() {
    if (checked) return disagreement;
    checked = true;
    std::ostringstream os;
    const std::pair<MrptMethod, SylvaFusion> pairs[] = {{MrptMethod::kNaive, SylvaFusion::kBatched},
                                                        {MrptMethod::kAlaDavison, SylvaFusion::kAlaDavison}};
    for (const auto& [method, fusion] : pairs) {
      if (world.landmarkCount() > g_options.mrpt_max_n) continue;
      if (method == MrptMethod::kNaive && world.landmarkCount() > g_options.naive_max_n) continue;
      MrptPeer& peer = mrpt(method);
      peer.setState(snapshot_state);
      peer.step(first);
      const auto d = sylva_peers::compareStates(references[static_cast<int>(fusion)].after_first, peer.state());
      std::fprintf(stderr, "peers: N = %d, step %d, MRPT %s vs sylva %s: %s\n", world.landmarkCount(), first,
                   sylva_peers::toString(method), sylva_peers::toString(fusion), d.summary().c_str());
      if (!d.same_landmarks || d.max_mean > kMeanTolerance || d.max_cov_relative > kCovarianceTolerance)
        os << "MRPT " << sylva_peers::toString(method) << " and sylva " << sylva_peers::toString(fusion)
           << " disagree after one step: " << d.summary() << "; ";
    }
    disagreement = os.str();
    for (Reference& r : references) r.after_first = FilterState{};  // large at N = 2000; not needed again
    return disagreement;
  }

  sylva_bench::CircleWorld world;
  std::vector<sylva_bench::SylvaStep> steps;
  int first = 0;
  int count = 0;
  double measurements_per_step = 0.0;
  std::unique_ptr<sylva_bench::OdometrySlam> snapshot;
  FilterState snapshot_state;
  Reference references[3];
  std::unique_ptr<MrptPeer> mrpt_naive;
  std::unique_ptr<MrptPeer> mrpt_davison;
  bool checked = false;
  std::string disagreement;
};

Setup& setupFor(int landmarks) {
  static std::unique_ptr<Setup> current;
  if (!current || current->world.landmarkCount() != landmarks) {
    current.reset();  // free the previous N's maps first
    current = std::make_unique<Setup>(landmarks);
  }
  return *current;
}

void setCounters(benchmark::State& state, const Setup& s, double total_s, double total_cpu_s, std::int64_t iterations) {
  state.counters["N"] = s.world.landmarkCount();
  state.counters["state_dim"] = s.snapshot->dim();
  state.counters["obs_per_step"] = s.measurements_per_step;
  state.counters["steps_per_iteration"] = s.count;
  state.counters["first_step"] = s.first;
  const double steps = static_cast<double>(iterations) * s.count;
  state.counters["ms_per_step"] = iterations > 0 ? 1e3 * total_s / steps : 0.0;
  // Processor time of the same steps: on a shared machine it excludes the time the process
  // waited for a core (but not memory contention).
  state.counters["cpu_ms_per_step"] = iterations > 0 ? 1e3 * total_cpu_s / steps : 0.0;
}

double seconds(std::chrono::steady_clock::duration d) { return std::chrono::duration<double>(d).count(); }

double cpuSeconds(std::clock_t begin, std::clock_t end) {
  return static_cast<double>(end - begin) / CLOCKS_PER_SEC;
}

void runBenchmark(benchmark::State& state, Family family, int landmarks) {
  Setup& s = setupFor(landmarks);
  if (const std::string& why = s.agreement(); !why.empty()) {
    state.SkipWithError(("refusing to time: " + why).c_str());
    for (auto _ : state) {
    }
    return;
  }
  const bool is_mrpt = family == Family::kMrptNaive || family == Family::kMrptDavison;
  SylvaFusion fusion = SylvaFusion::kBatched;
  if (family == Family::kMrptDavison || family == Family::kSylvaDavison) fusion = SylvaFusion::kAlaDavison;
  if (family == Family::kSylvaSequential) fusion = SylvaFusion::kSequential;
  const Reference& ref = s.references[static_cast<int>(fusion)];

  MrptPeer* peer = is_mrpt ? &s.mrpt(family == Family::kMrptNaive ? MrptMethod::kNaive : MrptMethod::kAlaDavison)
                           : nullptr;
  sylva_bench::OdometrySlam ekf = *s.snapshot;
  sylva_peers::PeerScratch scratch;
  Eigen::VectorXd mean;
  std::vector<sylva::Id> ids;
  double total_s = 0.0;
  double total_cpu_s = 0.0;
  for (auto _ : state) {
    if (peer) {
      peer->setState(s.snapshot_state);
      const std::clock_t c0 = std::clock();
      const auto t0 = std::chrono::steady_clock::now();
      for (int k = s.first; k < s.first + s.count; ++k) peer->step(k);
      const double dt = seconds(std::chrono::steady_clock::now() - t0);
      total_cpu_s += cpuSeconds(c0, std::clock());
      state.SetIterationTime(dt);
      total_s += dt;
      peer->mean(mean, ids);
    } else {
      ekf = *s.snapshot;
      const std::clock_t c0 = std::clock();
      const auto t0 = std::chrono::steady_clock::now();
      for (int k = s.first; k < s.first + s.count; ++k) s.runStep(ekf, k, fusion, scratch);
      const double dt = seconds(std::chrono::steady_clock::now() - t0);
      total_cpu_s += cpuSeconds(c0, std::clock());
      state.SetIterationTime(dt);
      total_s += dt;
      mean = ekf.mean();
      ids = s.snapshot_state.ids;  // sylva added no landmark in lap 2 (checked by the size)
    }
    const double diff = sylva_peers::maxMeanDifference(mean, ids, ref.mean_after_all, s.snapshot_state.ids);
    if (!(diff <= kMeanTolerance)) {
      std::ostringstream os;
      os << familyName(family) << ": after the timed steps the mean differs from the reference by " << diff;
      state.SkipWithError(os.str().c_str());
      break;
    }
  }
  setCounters(state, s, total_s, total_cpu_s, state.iterations());
}

// ---- whole runs ----------------------------------------------------------------------------

enum class WholeRun { kMrptDavison, kSylvaDavisonCompressed };

const char* wholeRunName(WholeRun w) {
  return w == WholeRun::kMrptDavison ? "mrpt_davison_whole" : "sylva_davison_compressed_whole";
}

/// The world of the whole runs at one N, and MRPT's final state once it has run.
struct WholeSetup {
  explicit WholeSetup(int landmarks)
      : world(Setup::makeConfig(landmarks)), steps(sylva_bench::sylvaSteps(world)) {}
  sylva_bench::CircleWorld world;
  std::vector<sylva_bench::SylvaStep> steps;
  std::unique_ptr<FilterState> mrpt_final;
};

WholeSetup& wholeSetupFor(int landmarks) {
  static std::unique_ptr<WholeSetup> current;
  if (!current || current->world.landmarkCount() != landmarks) {
    current.reset();
    current = std::make_unique<WholeSetup>(landmarks);
  }
  return *current;
}

void runWhole(benchmark::State& state, WholeRun which, int landmarks) {
  WholeSetup& s = wholeSetupFor(landmarks);
  const int total = static_cast<int>(s.world.steps().size());
  double total_s = 0.0;
  FilterState final_state;
  sylva_peers::WholeRunSplit split;  // the compressed run's (the last iteration's)
  for (auto _ : state) {
    if (which == WholeRun::kMrptDavison) {
      MrptPeer peer(s.world, MrptMethod::kAlaDavison);  // built outside the timed window
      const auto t0 = std::chrono::steady_clock::now();
      for (int k = 0; k < total; ++k) peer.step(k);
      const double dt = seconds(std::chrono::steady_clock::now() - t0);
      state.SetIterationTime(dt);
      total_s += dt;
      final_state = peer.state();
    } else {
      using Filter = sylva_bench::OdometrySlam;
      Filter ekf = sylva_bench::makeOdometrySlam(s.world);
      ekf.setCompression(Filter::withinRadius(50.0, 40.0));
      // Every step, then the final global update (synchronize()): all of it timed.
      split = sylva_peers::WholeRunSplit{};
      const double dt = sylva_peers::runCompressedWhole(ekf, s.steps, s.world.odometryNoise(), s.world.config().dt_s, &split);
      state.SetIterationTime(dt);
      total_s += dt;
      final_state = sylva_peers::stateOf(ekf);
    }
  }
  const std::int64_t iterations = state.iterations();
  state.counters["N"] = landmarks;
  state.counters["steps_per_run"] = total;
  state.counters["ms_per_run"] = iterations > 0 ? 1e3 * total_s / static_cast<double>(iterations) : 0.0;
  if (which == WholeRun::kMrptDavison) {
    s.mrpt_final = std::make_unique<FilterState>(std::move(final_state));
  } else {
    // Where the compressed run's time went, and the floor of its global updates at the GEMM
    // peak measured now (compressed_whole_run.hpp): the least sylva's run could take with
    // Eigen's kernels, so MRPT's time over it bounds the ratio this region can reach.
    sylva_peers::setSplitCounters(state, split);
  }
  if (which == WholeRun::kSylvaDavisonCompressed && s.mrpt_final) {
    const auto d = sylva_peers::compareStates(*s.mrpt_final, final_state);
    std::fprintf(stderr, "peers: N = %d, whole run, MRPT kfEKFAlaDavison vs sylva compressed: %s\n", landmarks,
                 d.summary().c_str());
    // Relative to the largest coordinate: over a whole run the landmarks lie hundreds of metres
    // from the origin (N = 1000: the means differed by 9.8e-10 m, 4e-12 of the largest).
    const double mean_scale = std::max(1.0, s.mrpt_final->mean.cwiseAbs().maxCoeff());
    const double mean_relative = d.max_mean / mean_scale;
    state.counters["max_mean_relative_diff"] = mean_relative;
    state.counters["max_cov_relative_diff"] = d.max_cov_relative;
    // Whether the states agree is a counter, not an error: an error would discard the time of a
    // run that MRPT's side took over half an hour to pair with (N = 2000). The report
    // (scripts/step_report.py) counts the criterion met only where they agree.
    state.counters["states_agree"] =
        d.same_landmarks && mean_relative <= kMeanTolerance && d.max_cov_relative <= kCovarianceTolerance ? 1.0 : 0.0;
    if (state.counters["states_agree"] == 0.0)
      std::fprintf(stderr, "peers: N = %d, whole run: the final states disagree beyond the tolerances (%g, %g)\n",
                   landmarks, kMeanTolerance, kCovarianceTolerance);
  }
}

std::vector<int> parseSizes(const char* text) {
  std::vector<int> sizes;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    const int n = std::atoi(item.c_str());
    if (n <= 0) {
      std::fprintf(stderr, "bench_peers: bad size '%s' in --peers_sizes\n", item.c_str());
      std::exit(2);
    }
    sizes.push_back(n);
  }
  return sizes;
}

/// Consumes the --peers_* flags, leaving Google Benchmark's in argv.
void parseOptions(int& argc, char** argv) {
  int out = 1;
  for (int i = 1; i < argc; ++i) {
    const char* a = argv[i];
    auto value = [&](const char* flag) -> const char* {
      const std::size_t len = std::strlen(flag);
      return std::strncmp(a, flag, len) == 0 && a[len] == '=' ? a + len + 1 : nullptr;
    };
    if (const char* v = value("--peers_sizes")) {
      g_options.sizes = parseSizes(v);
    } else if (const char* v2 = value("--peers_steps")) {
      g_options.steps = std::max(1, std::atoi(v2));
    } else if (const char* v3 = value("--peers_mrpt_max_n")) {
      g_options.mrpt_max_n = std::atoi(v3);
    } else if (const char* v4 = value("--peers_naive_max_n")) {
      g_options.naive_max_n = std::atoi(v4);
    } else if (const char* v5 = value("--peers_whole_sizes")) {
      g_options.whole_sizes = *v5 ? parseSizes(v5) : std::vector<int>{};
    } else if (std::strncmp(a, "--peers_", 8) == 0) {
      std::fprintf(stderr, "bench_peers: unknown flag %s\n", a);
      std::exit(2);
    } else {
      argv[out++] = argv[i];
    }
  }
  argc = out;
}

}  // namespace

int main(int argc, char** argv) {
  parseOptions(argc, argv);
  const Family families[] = {Family::kMrptNaive, Family::kMrptDavison, Family::kSylvaBatched,
                             Family::kSylvaDavison, Family::kSylvaSequential};
  for (int n : g_options.sizes) {  // N-major: one map in memory at a time
    for (Family f : families) {
      const bool is_mrpt = f == Family::kMrptNaive || f == Family::kMrptDavison;
      if (is_mrpt && n > g_options.mrpt_max_n) continue;
      if (f == Family::kMrptNaive && n > g_options.naive_max_n) continue;
      const std::string name = std::string(familyName(f)) + "/" + std::to_string(n);
      benchmark::RegisterBenchmark(name.c_str(), runBenchmark, f, n)
          ->UseManualTime()
          ->Unit(benchmark::kMillisecond);
    }
  }
  for (int n : g_options.whole_sizes) {  // MRPT first: the compressed run compares with its final state
    for (WholeRun w : {WholeRun::kMrptDavison, WholeRun::kSylvaDavisonCompressed}) {
      if (w == WholeRun::kMrptDavison && n > g_options.mrpt_max_n) continue;
      const std::string name = std::string(wholeRunName(w)) + "/" + std::to_string(n);
      benchmark::RegisterBenchmark(name.c_str(), runWhole, w, n)
          ->UseManualTime()
          ->Iterations(1)
          ->Unit(benchmark::kMillisecond);
    }
  }
  benchmark::AddCustomContext("peers_variant", SYLVA_PEERS_VARIANT);
  benchmark::AddCustomContext("peers_cxx_flags", SYLVA_PEERS_CXX_FLAGS);
  benchmark::AddCustomContext("peers_compiler", SYLVA_PEERS_COMPILER);
  benchmark::AddCustomContext("mrpt_version", MrptPeer::version());
  benchmark::AddCustomContext("peers_steps_per_iteration", std::to_string(g_options.steps));
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
