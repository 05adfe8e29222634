#pragma once
/// @file
/// sylva on the circle world (circle_world.hpp): the filter type, the two models it needs
/// and the step drivers, shared by the benchmarks.
///
/// Robot: `sylva::Odometry2D` (the odometry increment composed with the pose, as MRPT's
/// CRangeBearingKFSLAM2D predicts), observed with `sylva::RangeBearing` and initialized with
/// `sylva::InverseRangeBearing` (both written for `Pose2D`, the base of `Odometry2D`).
///
/// One step (`runStep`), in MRPT's order (see bench/peers/README.md):
///   1. predict with the odometry, unless the step has no motion or the map is still empty
///      (MRPT skips the prediction while the map is empty, so that the first landmarks are
///      placed relative to an exactly known pose; we do the same so the filters agree);
///   2. update with every measurement of a landmark already in the map: all of them in one
///      batched update (`Fusion::kBatched`) or one 2-D update per measurement, each
///      linearized at the current estimate (`Fusion::kSequential`);
///   3. add every landmark seen for the first time, in measurement order, from the updated
///      estimate.

#include <map>
#include <memory>
#include <utility>
#include <vector>

#include "circle_world.hpp"
#include "sylva/filter/ekf.hpp"
#include "sylva/landmarks/point2.hpp"
#include "sylva/measurements/range_bearing.hpp"
#include "sylva/motion/odometry_2d.hpp"
#include "sylva/noise/gaussian.hpp"

namespace sylva_bench {

using OdometrySlam = sylva::Ekf<sylva::Odometry2D, sylva::Point2>;
using RangeBearingObservation = sylva::Observation<sylva::RangeBearing>;

/// Batched or sequential fusion of a step's observations (sylva::Fusion).
using Fusion = sylva::Fusion;

/// A step's inputs in sylva's types (built once, outside any timing).
struct SylvaStep {
  bool has_motion = false;
  sylva::Vec<3> odometry = sylva::Vec<3>::Zero();
  std::vector<RangeBearingObservation> observations;  ///< every measurement of the step
};

/// The world's steps in sylva's types.
inline std::vector<SylvaStep> sylvaSteps(const CircleWorld& world) {
  const sylva::Gaussian<2> noise = world.measurementNoise();
  std::vector<SylvaStep> out;
  out.reserve(world.steps().size());
  for (const Step& step : world.steps()) {
    SylvaStep s;
    s.has_motion = step.has_motion;
    s.odometry = step.odometry;
    s.observations.reserve(step.measurements.size());
    for (const Measurement& m : step.measurements) s.observations.push_back({m.id, m.z(), noise});
    out.push_back(std::move(s));
  }
  return out;
}

/// The filter at the start of the world: the exact start pose, zero covariance, storage
/// for the whole map reserved.
inline OdometrySlam makeOdometrySlam(const CircleWorld& world) {
  OdometrySlam ekf(world.initialPose(), sylva::Mat<3, 3>::Zero());
  ekf.reserve(sylva::Point2::kDim * world.landmarkCount());
  return ekf;
}

/// Reusable buffers of `runStep` (so that a step allocates nothing once they have grown).
struct StepScratch {
  std::vector<RangeBearingObservation> known;
  std::vector<const RangeBearingObservation*> fresh;
};

/// Step 1 of the file comment (shared with other fusions, e.g. bench/peers' replica of
/// MRPT's kfEKFAlaDavison).
template <typename Filter>
void predictStep(Filter& ekf, const SylvaStep& step, const sylva::Gaussian<3>& odometry_noise, double dt_s) {
  if (step.has_motion && ekf.landmarkCount() > 0) ekf.predict(step.odometry, dt_s, odometry_noise);
}

/// Splits the step's observations into landmarks in the map (`scratch.known`) and new ones
/// (`scratch.fresh`), keeping the measurement order.
template <typename Filter>
void splitObservations(const Filter& ekf, const SylvaStep& step, StepScratch& scratch) {
  scratch.known.clear();
  scratch.fresh.clear();
  for (const RangeBearingObservation& obs : step.observations) {
    if (ekf.contains(obs.id))
      scratch.known.push_back(obs);
    else
      scratch.fresh.push_back(&obs);
  }
}

/// Step 3 of the file comment.
template <typename Filter>
void addNewLandmarks(Filter& ekf, const StepScratch& scratch) {
  const sylva::InverseRangeBearing inverse;
  for (const RangeBearingObservation* obs : scratch.fresh) ekf.add(obs->id, inverse, obs->z, obs->noise);
}

/// One whole step (see the file comment).
template <typename Filter>
void runStep(Filter& ekf,
             const SylvaStep& step,
             const sylva::Gaussian<3>& odometry_noise,
             double dt_s,
             Fusion fusion,
             StepScratch& scratch) {
  predictStep(ekf, step, odometry_noise, dt_s);
  splitObservations(ekf, step, scratch);
  const sylva::RangeBearing model;
  if (fusion == Fusion::kBatched) {
    ekf.update(model, scratch.known);
  } else {
    for (const RangeBearingObservation& obs : scratch.known) ekf.update(model, obs.id, obs.z, obs.noise);
  }
  addNewLandmarks(ekf, scratch);
}

/// The world of N landmarks, its steps in sylva's types and where lap 2 starts.
struct World {
  explicit World(int landmarks) : world(config(landmarks)), steps(sylvaSteps(world)) {}
  static CircleWorldConfig config(int landmarks) {
    CircleWorldConfig c;
    c.landmarks = landmarks;
    return c;
  }
  CircleWorld world;
  std::vector<SylvaStep> steps;
};

/// The world of N landmarks, built once per N.
inline const World& worldOf(int landmarks) {
  static std::map<int, std::unique_ptr<World>> cache;
  auto& slot = cache[landmarks];
  if (!slot) slot = std::make_unique<World>(landmarks);
  return *slot;
}

/// The filter at the end of lap 1 (batched fusion while the map is built), built once per N
/// and filter type.
template <typename Filter>
const Filter& endOfLapOne(int landmarks) {
  static std::map<int, std::unique_ptr<Filter>> cache;
  auto& slot = cache[landmarks];
  if (!slot) {
    const World& w = worldOf(landmarks);
    Filter ekf(w.world.initialPose(), sylva::Mat<3, 3>::Zero());
    ekf.reserve(sylva::Point2::kDim * landmarks);
    StepScratch scratch;
    const auto noise = w.world.odometryNoise();
    for (int k = 0; k < w.world.lapBegin(1); ++k)
      runStep(ekf, w.steps[static_cast<std::size_t>(k)], noise, w.world.config().dt_s, sylva::Fusion::kBatched, scratch);
    slot = std::make_unique<Filter>(std::move(ekf));
  }
  return *slot;
}

}  // namespace sylva_bench
