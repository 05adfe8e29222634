#pragma once
/// @file
/// Umbrella header of the simulators (namespace sylva::sim): seeded random numbers, a loop
/// path and the robot driving it with noisy odometry, a landmark field along the path and a
/// range-bearing sensor; a planar laser scanner casting beams into scenes of circles and
/// segments with moving objects and walking people. Everything is reproducible bit for bit
/// from one seed.
// IWYU pragma: begin_exports
#include "sylva/sim/bezier_loop_2d.hpp"
#include "sylva/sim/dynamic_scene_2d.hpp"
#include "sylva/sim/forest_scenario.hpp"
#include "sylva/sim/forest_trajectory.hpp"
#include "sylva/sim/landmarks_2d.hpp"
#include "sylva/sim/laser_scanner_2d.hpp"
#include "sylva/sim/laser_scene_2d.hpp"
#include "sylva/sim/loop_path_2d.hpp"
#include "sylva/sim/loop_trajectory_2d.hpp"
#include "sylva/sim/planar_loop_world.hpp"
#include "sylva/sim/random.hpp"
#include "sylva/sim/range_bearing_sensor.hpp"
#include "sylva/sim/tree_forest.hpp"
#include "sylva/sim/tree_observer.hpp"
#include "sylva/sim/vertical_edge_camera.hpp"
#include "sylva/sim/walking_person_2d.hpp"
// IWYU pragma: end_exports
