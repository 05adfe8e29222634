// slam::MonocularTreeSlam compiled once for the module (monocular.cpp binds it).
#include "sylva/slam/monocular_tree_slam.hpp"
#include "sylva/slam/monocular_tree_slam_impl.hpp"

template class sylva::slam::BasicMonocularTreeSlam<sylva::ConstantVelocity3D>;
