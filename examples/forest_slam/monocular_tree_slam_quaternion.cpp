// sylva::slam::MonocularTreeSlam (the camera's quaternion in the state), compiled once for
// forest_slam, tree_width_study, consistency and bench_forest_slam (library
// forest_slam_pipeline). The camera on its manifold is in monocular_tree_slam_manifold.cpp:
// g++ 12 takes longer for the two classes in one unit than for each in a unit of its own, and
// two units build in parallel.

#include <sylva/slam/monocular_tree_slam_impl.hpp>

#include "monocular_tree_slam.hpp"

template class sylva::slam::BasicMonocularTreeSlam<sylva::ConstantVelocity3D>;
