#pragma once
/// @file
/// Every motion model (planar and 3D). sylva/sylva.hpp brings the planar ones alone.
// IWYU pragma: begin_exports
#include "sylva/motion/ackermann_2d.hpp"
#include "sylva/motion/ackermann_2d_with_bias.hpp"
#include "sylva/motion/constant_velocity_3d.hpp"
#include "sylva/motion/odometry_2d.hpp"
#include "sylva/motion/on_manifold.hpp"
#include "sylva/motion/pose_2d.hpp"
#include "sylva/motion/pose_3d.hpp"
#include "sylva/motion/unicycle_2d.hpp"
#include "sylva/motion/unicycle_2d_with_bias.hpp"
// IWYU pragma: end_exports
