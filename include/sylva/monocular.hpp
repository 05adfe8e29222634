#pragma once
/// @file
/// Umbrella header of the camera and tree stack (tree-width thesis): the 6-DOF camera with a
/// constant-velocity model (also on its manifold), the 3D landmark parametrizations (points,
/// inverse-depth points, trees with a radius), the pinhole and tree-width measurement models
/// with their inverse models and conversions, and the life cycle of a tree landmark. Brings
/// sylva/sylva.hpp's generic filter with it.
// IWYU pragma: begin_exports
#include "sylva/sylva.hpp"

#include "sylva/landmarks/inverse_depth.hpp"
#include "sylva/landmarks/inverse_depth_radius.hpp"
#include "sylva/landmarks/point3.hpp"
#include "sylva/landmarks/tree_xyzr.hpp"
#include "sylva/measurements/inverse_depth_initialization.hpp"
#include "sylva/measurements/inverse_depth_tree_width.hpp"
#include "sylva/measurements/inverse_tree_width.hpp"
#include "sylva/measurements/pinhole_camera.hpp"
#include "sylva/measurements/pinhole_point.hpp"
#include "sylva/measurements/tree_width.hpp"
#include "sylva/motion/constant_velocity_3d.hpp"
#include "sylva/motion/on_manifold.hpp"
#include "sylva/motion/pose_3d.hpp"
#include "sylva/slam/tree_life_cycle.hpp"
// IWYU pragma: end_exports
