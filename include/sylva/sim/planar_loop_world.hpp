#pragma once
/// @file
/// `sim::PlanarLoopWorld`: the simulated world of 2D range-bearing SLAM that
/// examples/range_bearing_slam and the `planar` suite of examples/consistency share: a robot
/// driving a rounded-rectangle loop with noisy odometry (`LoopTrajectory2D`), point landmarks
/// in a band along it (`landmarksAlongPath`) and a forward-looking range-bearing sensor
/// (`RangeBearingSensor2D`).
///
/// Defaults (`PlanarLoopWorldOptions`): a 120 m loop at 1 m/s, dt = 0.1 s; 120 landmarks at
/// least 1.5 m apart; the sensor of the multisensor thesis' Table 3.1 (5 cm, 1 deg) with 10 m
/// range and a +-90 deg field of view; odometry noise of 5 cm/s and 1 deg/s, ten and forty
/// times Table 3.1's, so that dead reckoning drifts visibly over a lap
/// (examples/range_bearing_slam/main.cpp says why).
///
/// `makePlanarLoopWorld(options, seed)` draws the landmarks from the stream deriveSeed(seed, 0);
/// a run's noise is the caller's (range_bearing_slam and the planar suite draw run i from
/// deriveSeed(seed, 1 + i)). Invalid options are refused by the parts (kInvalidArgument).

#include <cstdint>
#include <vector>

#include "sylva/core/angles.hpp"
#include "sylva/sim/landmarks_2d.hpp"
#include "sylva/sim/loop_trajectory_2d.hpp"
#include "sylva/sim/random.hpp"
#include "sylva/sim/range_bearing_sensor.hpp"

namespace sylva::sim {

struct PlanarLoopWorldOptions {
  LoopTrajectory2DOptions trajectory = [] {
    LoopTrajectory2DOptions o;
    o.sigma_v_mps = 0.05;
    o.sigma_omega_radps = 1.0 * kRadPerDeg;
    return o;
  }();
  LandmarkField2DOptions landmarks = [] {
    LandmarkField2DOptions o;
    o.count = 120;
    o.min_separation_m = 1.5;
    return o;
  }();
  RangeBearingSensor2DOptions sensor = [] {
    RangeBearingSensor2DOptions o;
    o.max_range_m = 10.0;
    return o;
  }();
};

struct PlanarLoopWorld {
  LoopTrajectory2D trajectory;
  RangeBearingSensor2D sensor;
  std::vector<TrueLandmark2D> landmarks;
};

inline PlanarLoopWorld makePlanarLoopWorld(const PlanarLoopWorldOptions& options, std::uint64_t seed) {
  LoopTrajectory2D trajectory(options.trajectory);
  Rng world_rng(deriveSeed(seed, 0));
  std::vector<TrueLandmark2D> landmarks = landmarksAlongPath(trajectory.path(), options.landmarks, world_rng);
  return PlanarLoopWorld{trajectory, RangeBearingSensor2D(options.sensor), std::move(landmarks)};
}

}  // namespace sylva::sim
