#pragma once
// The forest examples' use of sylva::slam::MonocularTreeSlam (include/sylva/slam/
// monocular_tree_slam.hpp): its names in this namespace, the default forest, and the
// simulator's sightings and trees in the pipeline's input types. The class is compiled once
// per camera, in monocular_tree_slam_quaternion.cpp and monocular_tree_slam_manifold.cpp
// (library forest_slam_pipeline), for forest_slam, tree_width_study, consistency and
// bench/forest_slam.cpp.

#include <cstdint>
#include <vector>

#include <sylva/sim/tree_forest.hpp>
#include <sylva/sim/tree_observer.hpp>
#include <sylva/slam/monocular_tree_slam.hpp>

extern template class sylva::slam::BasicMonocularTreeSlam<sylva::ConstantVelocity3D>;
extern template class sylva::slam::BasicMonocularTreeSlam<sylva::OnManifold<sylva::ConstantVelocity3D>>;

namespace forest_slam {

using sylva::Id;
using sylva::Mat;
using sylva::Vec;
using sylva::slam::FrameProfile;
using sylva::slam::FrameReport;
using sylva::slam::FrameTruth;
using sylva::slam::initialCameraCovariance;
using sylva::slam::ManifoldTreeSlam;
using sylva::slam::MonocularTreeSlam;
using sylva::slam::pipelineName;
using sylva::slam::TreeSlamOptions;
using sylva::slam::TrunkSighting;
using sylva::slam::WidthPipeline;

/// The default forest. Seed 26 is the representative one of seeds 1..30 under the default
/// settings: the median of the trajectory error of the run WITHOUT the width sensor, so the
/// choice says nothing about the sensor (scripts/forest_slam_seeds.py finds it and
/// docs/forest-slam-results.md lists all 30 seeds).
constexpr std::uint64_t kDefaultForestSeed = 26;

/// The simulator's observations of one frame as the pipeline's sightings (id and noisy
/// [u, v, w]).
inline std::vector<TrunkSighting> sightingsOf(const std::vector<sylva::sim::TreeObservation>& observations) {
  std::vector<TrunkSighting> out;
  out.reserve(observations.size());
  for (const auto& o : observations) out.push_back(TrunkSighting{o.id, o.z});
  return out;
}

/// The noise-free [u, v, w] of each observation (FrameTruth::noise_free).
inline std::vector<Vec<3>> noiseFreeOf(const std::vector<sylva::sim::TreeObservation>& observations) {
  std::vector<Vec<3>> out;
  out.reserve(observations.size());
  for (const auto& o : observations) out.push_back(o.z_true);
  return out;
}

/// The forest as FrameTruth::trees: [x, y, z, r] at index id (the simulator's trees[id].id == id).
inline std::vector<Vec<4>> treesOf(const std::vector<sylva::sim::Tree>& trees) {
  std::vector<Vec<4>> out;
  out.reserve(trees.size());
  for (const auto& t : trees) out.push_back(t.xyzr());
  return out;
}

}  // namespace forest_slam
