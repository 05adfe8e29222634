/// @file
/// Cost of the EKF-SLAM update against the size of the map, for 2D range-bearing SLAM:
/// `Ekf<Unicycle2D, Point2>` observing `Point2` landmarks through `RangeBearing`, with N
/// landmarks, so the state dimension is n = 3 + 2N.
///
/// Families (the argument is N, the number of landmarks):
///   BM_UpdateEfficient   one single-observation update of `sylva::Ekf` (symmetric form
///                        P -= W W^T on one triangle): O(n^2)
///   BM_UpdateJoseph      the same with `sylva::JosephEkf` (Joseph form on the full matrix):
///                        O(n^2) with a larger constant
///   BM_UpdateNaive       the textbook filter with a dense 2 x n H and P = (I - K H) P,
///                        `sylva::testing::DenseReferenceEkf`: O(n^3)
///   BM_UpdateBatched     one batched update of kVisible observations in one call of
///                        `sylva::Ekf` (compare with kVisible x BM_UpdateEfficient)
///   BM_StepEfficient     one SLAM step with `sylva::Ekf`: predict, then kVisible
///                        sequential single-observation updates
///   BM_StepBatched       predict, then one batched update of the kVisible observations
///   BM_StepNaive         the dense textbook step: predict with a dense n x n F
///                        (P = F P F^T + G Q G^T), then one update with the stacked
///                        2 kVisible x n H of the kVisible observations
///
/// Setup (outside the timed loop, once per N and filter type, then copied): the robot drives
/// a circle of radius 2 m while the map is built with `InverseRangeBearing` from landmarks
/// drawn at 5-40 m around it, interleaved with predictions and re-observations, so the
/// covariance is dense and fully correlated like in a real run. The naive filter starts from
/// a copy of the same mean and covariance.
///
/// Timed loop: the kVisible visible landmarks are spread over the whole state (first, last
/// and evenly between). Each update measures z = z_hat +/- delta with a fixed small delta
/// whose sign alternates, so the mean stays bounded and the covariance only shrinks slowly
/// (S >= R keeps the innovation covariance positive definite however often it is repeated).
/// After the loop the joint covariance of the robot and the visible landmarks is checked
/// to be finite and positive definite; a failure marks the benchmark as an error.

#include <benchmark/benchmark.h>

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <cstdint>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "sylva/core/angles.hpp"
#include "sylva/filter/ekf.hpp"
#include "sylva/landmarks/point2.hpp"
#include "sylva/measurements/range_bearing.hpp"
#include "sylva/motion/unicycle_2d.hpp"
#include "sylva/noise/gaussian.hpp"
#include "sylva/sim/random.hpp"
#include "sylva/testing/dense_reference_ekf.hpp"

#include "common/build_context.hpp"

namespace {

using sylva::Id;
using sylva::Mat;
using sylva::Vec;
using Filter = sylva::Ekf<sylva::Unicycle2D, sylva::Point2>;
using JosephFilter = sylva::JosephEkf<sylva::Unicycle2D, sylva::Point2>;
using Reference = sylva::testing::DenseReferenceEkf<sylva::Unicycle2D>;
using Observation = sylva::Observation<sylva::RangeBearing>;

constexpr int kVisible = 5;         ///< observations per SLAM step
constexpr int kSetupSteps = 20;     ///< predict/add/re-observe rounds that build the map
constexpr std::uint64_t kSeed = 0x5eed'0b5e'2d5e'7a11ULL;
constexpr double kDt_s = 0.1;
constexpr double kMinRange_m = 5.0;
constexpr double kMaxRange_m = 40.0;
/// Offset added to / subtracted from the predicted measurement in the timed loop.
constexpr double kDeltaRange_m = 0.02;
constexpr double kDeltaBearing_rad = 0.002;

const Vec<2> kControl(1.0, 0.5);  ///< v = 1 m/s, omega = 0.5 rad/s: a circle of radius 2 m

const sylva::Gaussian<2>& motionNoise() {
  static const auto noise = sylva::Gaussian<2>::sigmas(Vec<2>(0.05, 0.02));  // m/s, rad/s
  return noise;
}

const sylva::Gaussian<2>& measurementNoise() {
  static const auto noise = sylva::Gaussian<2>::sigmas(Vec<2>(0.05, 0.01));  // m, rad
  return noise;
}

/// Builds the map of `landmarks` Point2 landmarks with filter type `F` (see file comment).
template <typename F>
F buildFilter(int landmarks) {
  sylva::sim::Rng rng(sylva::sim::deriveSeed(kSeed, static_cast<std::uint64_t>(landmarks)));
  const Mat<3, 3> P0 = Vec<3>(1e-4, 1e-4, 1e-5).asDiagonal();
  F ekf(Vec<3>::Zero(), P0);
  ekf.reserve(sylva::Point2::kDim * landmarks);
  const sylva::RangeBearing model;
  const sylva::InverseRangeBearing inverse;
  int added = 0;
  for (int step = 0; step < kSetupSteps; ++step) {
    ekf.predict(kControl, kDt_s, motionNoise());
    const int target = (step + 1) * landmarks / kSetupSteps;
    for (; added < target; ++added) {
      const double range_m = rng.uniform(kMinRange_m, kMaxRange_m);
      const double bearing_rad = rng.uniform(-sylva::kPi, sylva::kPi);
      ekf.add(added, inverse, Vec<2>(range_m, bearing_rad), measurementNoise());
    }
    for (int j = 0; j < kVisible && added > 0; ++j) {
      const Id id = static_cast<Id>(rng.engine()() % static_cast<std::uint64_t>(added));
      const Vec<2> z = ekf.linearize(model, id).z_hat + rng.sample(measurementNoise());
      ekf.update(model, id, z, measurementNoise());
    }
  }
  return ekf;
}

/// The built map for `landmarks`, made once per filter type and size and then copied.
template <typename F>
const F& prototype(int landmarks) {
  static std::map<int, F> cache;
  auto it = cache.find(landmarks);
  if (it == cache.end()) it = cache.emplace(landmarks, buildFilter<F>(landmarks)).first;
  return it->second;
}

/// The visible landmarks: first, last and evenly spread between, so that the observed
/// blocks sit all over the state.
std::vector<Id> visibleIds(int landmarks) {
  std::vector<Id> ids;
  for (int a = 0; a < kVisible; ++a)
    ids.push_back(static_cast<Id>(static_cast<long long>(a) * (landmarks - 1) / (kVisible - 1)));
  return ids;
}

/// +delta for even `round`, -delta for odd.
Vec<2> offset(int round) {
  const double sign = (round % 2 == 0) ? 1.0 : -1.0;
  return sign * Vec<2>(kDeltaRange_m, kDeltaBearing_rad);
}

/// Dense textbook filter holding the same mean and covariance as `ekf`.
Reference referenceFrom(const Filter& ekf) {
  Reference ref;
  ref.x = ekf.mean();
  ref.P = ekf.covariance();
  return ref;
}

/// Marks the run as failed unless the joint covariance of the robot and the visible
/// landmarks (rows `offsets`) is finite and positive definite and the mean is finite.
void checkHealthy(benchmark::State& state,
                  const Eigen::VectorXd& mean,
                  const Eigen::MatrixXd& P,
                  const std::vector<int>& offsets) {
  std::vector<int> rows = {0, 1, 2};
  for (int o : offsets) {
    rows.push_back(o);
    rows.push_back(o + 1);
  }
  const int m = static_cast<int>(rows.size());
  Eigen::MatrixXd joint(m, m);
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j) joint(i, j) = 0.5 * (P(rows[i], rows[j]) + P(rows[j], rows[i]));
  Eigen::LLT<Eigen::MatrixXd> llt(joint);
  if (!mean.allFinite() || !joint.allFinite() || llt.info() != Eigen::Success)
    state.SkipWithError("covariance of the robot and the visible landmarks lost definiteness");
}

template <typename F>
std::vector<int> offsetsOf(const F& ekf, const std::vector<Id>& ids) {
  std::vector<int> offsets;
  for (Id id : ids) offsets.push_back(ekf.slot(id).offset);
  return offsets;
}

void setCounters(benchmark::State& state, int landmarks, int observations_per_iteration) {
  state.counters["landmarks"] = landmarks;
  state.counters["state_dim"] = 3 + sylva::Point2::kDim * landmarks;
  state.counters["obs_per_iter"] = observations_per_iteration;
  state.SetItemsProcessed(state.iterations() * observations_per_iteration);
}

// ------------------------------------------------------------------ single updates

/// One single-observation update of `F` per iteration, cycling over the visible landmarks.
template <typename F>
void runSylvaUpdate(benchmark::State& state) {
  const int landmarks = static_cast<int>(state.range(0));
  F ekf = prototype<F>(landmarks);
  const sylva::RangeBearing model;
  const std::vector<Id> ids = visibleIds(landmarks);
  std::vector<Vec<2>> z[2];
  for (int round = 0; round < 2; ++round)
    for (Id id : ids) z[round].push_back(ekf.linearize(model, id).z_hat + offset(round));
  int i = 0;
  for (auto _ : state) {
    const int a = i % kVisible;
    const int round = (i / kVisible) % 2;
    auto innovation = ekf.update(model, ids[a], z[round][a], measurementNoise());
    benchmark::DoNotOptimize(innovation);
    ++i;
  }
  checkHealthy(state, ekf.mean(), ekf.covariance(), offsetsOf(ekf, ids));
  setCounters(state, landmarks, 1);
}

void BM_UpdateEfficient(benchmark::State& state) { runSylvaUpdate<Filter>(state); }
void BM_UpdateJoseph(benchmark::State& state) { runSylvaUpdate<JosephFilter>(state); }

void BM_UpdateNaive(benchmark::State& state) {
  const int landmarks = static_cast<int>(state.range(0));
  const Filter& source = prototype<Filter>(landmarks);
  Reference ref = referenceFrom(source);
  const sylva::RangeBearing model;
  const std::vector<Id> ids = visibleIds(landmarks);
  const std::vector<int> offsets = offsetsOf(source, ids);
  std::vector<Vec<2>> z[2];
  for (int round = 0; round < 2; ++round)
    for (Id id : ids) z[round].push_back(source.linearize(model, id).z_hat + offset(round));
  const Mat<2, 2> R = measurementNoise().covariance();
  int i = 0;
  for (auto _ : state) {
    const int a = i % kVisible;
    const int round = (i / kVisible) % 2;
    ref.update(model, offsets[a], z[round][a], R);
    benchmark::DoNotOptimize(ref.P.data());
    benchmark::ClobberMemory();
    ++i;
  }
  checkHealthy(state, ref.x, ref.P, offsets);
  setCounters(state, landmarks, 1);
}

void BM_UpdateBatched(benchmark::State& state) {
  const int landmarks = static_cast<int>(state.range(0));
  Filter ekf = prototype<Filter>(landmarks);
  const sylva::RangeBearing model;
  const std::vector<Id> ids = visibleIds(landmarks);
  std::vector<Observation> batch[2];
  for (int round = 0; round < 2; ++round)
    for (Id id : ids)
      batch[round].push_back(
          Observation{id, ekf.linearize(model, id).z_hat + offset(round), measurementNoise()});
  int i = 0;
  for (auto _ : state) {
    ekf.update(model, batch[i % 2]);
    benchmark::ClobberMemory();
    ++i;
  }
  checkHealthy(state, ekf.mean(), ekf.covariance(), offsetsOf(ekf, ids));
  setCounters(state, landmarks, kVisible);
}

// ------------------------------------------------------------------ full steps

void BM_StepEfficient(benchmark::State& state) {
  const int landmarks = static_cast<int>(state.range(0));
  Filter ekf = prototype<Filter>(landmarks);
  const sylva::RangeBearing model;
  const std::vector<Id> ids = visibleIds(landmarks);
  int i = 0;
  for (auto _ : state) {
    ekf.predict(kControl, kDt_s, motionNoise());
    for (Id id : ids) {
      const Vec<2> z = ekf.linearize(model, id).z_hat + offset(i);
      auto innovation = ekf.update(model, id, z, measurementNoise());
      benchmark::DoNotOptimize(innovation);
    }
    ++i;
  }
  checkHealthy(state, ekf.mean(), ekf.covariance(), offsetsOf(ekf, ids));
  setCounters(state, landmarks, kVisible);
}

void BM_StepBatched(benchmark::State& state) {
  const int landmarks = static_cast<int>(state.range(0));
  Filter ekf = prototype<Filter>(landmarks);
  const sylva::RangeBearing model;
  const std::vector<Id> ids = visibleIds(landmarks);
  std::vector<Observation> batch;
  for (Id id : ids) batch.push_back(Observation{id, Vec<2>::Zero(), measurementNoise()});
  int i = 0;
  for (auto _ : state) {
    ekf.predict(kControl, kDt_s, motionNoise());
    for (Observation& obs : batch) obs.z = ekf.linearize(model, obs.id).z_hat + offset(i);
    ekf.update(model, batch);
    benchmark::ClobberMemory();
    ++i;
  }
  checkHealthy(state, ekf.mean(), ekf.covariance(), offsetsOf(ekf, ids));
  setCounters(state, landmarks, kVisible);
}

void BM_StepNaive(benchmark::State& state) {
  const int landmarks = static_cast<int>(state.range(0));
  const Filter& source = prototype<Filter>(landmarks);
  Reference ref = referenceFrom(source);
  const sylva::RangeBearing model;
  const std::vector<Id> ids = visibleIds(landmarks);
  const std::vector<int> offsets = offsetsOf(source, ids);
  const Mat<2, 2> Q = motionNoise().covariance();
  const Mat<2, 2> R = measurementNoise().covariance();
  constexpr int M = sylva::RangeBearing::kDim;
  Eigen::MatrixXd R_stacked = Eigen::MatrixXd::Zero(kVisible * M, kVisible * M);
  for (int a = 0; a < kVisible; ++a) R_stacked.block<M, M>(a * M, a * M) = R;
  int i = 0;
  for (auto _ : state) {
    ref.predict(kControl, kDt_s, Q);
    Eigen::MatrixXd H(kVisible * M, ref.dim());
    Eigen::VectorXd nu(kVisible * M);
    for (int a = 0; a < kVisible; ++a) {
      Vec<M> z_hat;
      H.middleRows<M>(a * M) = ref.jacobian(model, offsets[a], &z_hat);
      nu.segment<M>(a * M) = model.residual(z_hat + offset(i), z_hat);
    }
    ref.updateLinear(H, nu, R_stacked);
    benchmark::DoNotOptimize(ref.P.data());
    benchmark::ClobberMemory();
    ++i;
  }
  checkHealthy(state, ref.x, ref.P, offsets);
  setCounters(state, landmarks, kVisible);
}

// ------------------------------------------------------------------ registration

/// Map sizes. 500..1000 is where the covariance (8-32 MB) no longer fits in a core's L2,
/// the range over which docs/update-benchmarks.md fits the scaling exponent.
const std::vector<int> kLandmarkCounts = {50, 100, 200, 300, 500, 700, 1000};

/// Every family runs each size for at least 0.3 s per repetition. The O(n^3) families need
/// no cap of their own: at N = 700 and 1000 a single naive iteration already takes longer
/// than that, so Google Benchmark stops after one iteration per repetition.
void sizes(benchmark::internal::Benchmark* b) {
  for (int n : kLandmarkCounts) b->Arg(n);
  b->MinTime(0.3)->Unit(benchmark::kMicrosecond);
}

BENCHMARK(BM_UpdateEfficient)->Apply(sizes);
BENCHMARK(BM_UpdateJoseph)->Apply(sizes);
BENCHMARK(BM_UpdateBatched)->Apply(sizes);
BENCHMARK(BM_UpdateNaive)->Apply(sizes);
BENCHMARK(BM_StepEfficient)->Apply(sizes);
BENCHMARK(BM_StepBatched)->Apply(sizes);
BENCHMARK(BM_StepNaive)->Apply(sizes);

}  // namespace

int main(int argc, char** argv) {
  // Recorded in the JSON context so that the reports can name the machine and build.
  return sylva_bench::runBenchmarks(argc, argv, {{"observations_per_step", std::to_string(kVisible)}});
}
