// sylva::slam::ManifoldTreeSlam (the camera on its manifold), compiled once for the programs
// of library forest_slam_pipeline; see monocular_tree_slam_quaternion.cpp.

#include <sylva/slam/monocular_tree_slam_impl.hpp>

#include "monocular_tree_slam.hpp"

template class sylva::slam::BasicMonocularTreeSlam<sylva::OnManifold<sylva::ConstantVelocity3D>>;
