#pragma once
/// @file
/// MRPT's 2D EKF-SLAM, `mrpt::slam::CRangeBearingKFSLAM2D`, driven by the circle world.
/// This header does not include MRPT (mrpt_peer.cpp does), so the rest of the peers' code
/// compiles without MRPT's headers.
///
/// Configuration (see README.md for what MRPT does with it):
///   - KF_options.method: kfEKFNaive (MRPT's default) or kfEKFAlaDavison;
///   - options.std_sensor_range / std_sensor_yaw: the world's measurement sigmas (MRPT keeps
///     them as float; the world's defaults are exact in float, which `MrptPeer` checks);
///   - per step: a CActionRobotMovement2D whose pose change is a CPosePDFGaussian (mean = the
///     measured increment, covariance = the world's odometry covariance), and a
///     CObservationBearingRange with the sensor at the robot's origin, the world's range
///     limits and field of view, and one entry per measurement with its landmark id, so
///     MRPT associates by id (no data association runs).

#include <memory>
#include <string>
#include <vector>

#include "circle_world.hpp"
#include "filter_state.hpp"

namespace sylva_peers {

enum class MrptMethod { kNaive, kAlaDavison };

inline const char* toString(MrptMethod m) { return m == MrptMethod::kNaive ? "kfEKFNaive" : "kfEKFAlaDavison"; }

class MrptPeer {
 public:
  /// A fresh filter (robot at the origin, zero covariance, empty map) for `world`, whose
  /// steps' MRPT inputs are built here once (outside any timing).
  MrptPeer(const sylva_bench::CircleWorld& world, MrptMethod method);
  ~MrptPeer();
  MrptPeer(const MrptPeer&) = delete;
  MrptPeer& operator=(const MrptPeer&) = delete;

  /// Runs step `k` of the world: one call of processActionObservation (predict, update,
  /// add new landmarks).
  void step(int k);

  /// Current state, landmarks in MRPT's state order.
  FilterState state() const;
  /// Only the mean (O(n)) and the ids in state order.
  void mean(Eigen::VectorXd& mean, std::vector<sylva::Id>& ids) const;
  /// Replaces the mean, covariance and id table (e.g. to start timed steps from a map built
  /// elsewhere). O(n^2).
  void setState(const FilterState& state);

  /// MRPT's version string, for the benchmark context.
  static std::string version();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace sylva_peers
