// The member functions of sylva::slam::MonocularTreeSlam, compiled once for forest_slam,
// tree_width_study, consistency and bench_forest_slam (library forest_slam_pipeline).

#include <sylva/slam/monocular_tree_slam_impl.hpp>

#include "monocular_tree_slam.hpp"

template class sylva::slam::BasicMonocularTreeSlam<sylva::ConstantVelocity3D>;
template class sylva::slam::BasicMonocularTreeSlam<sylva::OnManifold<sylva::ConstantVelocity3D>>;
