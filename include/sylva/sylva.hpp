#pragma once
/// @file
/// Umbrella header: the generic filter, the planar robots, landmarks and sensors, and the
/// noise. Kept lean, since every translation unit that includes it pays for it
/// (docs/build-time.md). The rest has umbrellas of its own:
///
///   sylva/monocular.hpp      the 6-DOF camera, 3D and inverse-depth landmarks, tree width
///   sylva/laser_camera.hpp   the laser-camera sensor front end
///   sylva/association.hpp    data association (nearest neighbour, JCBB, ...)
///   sylva/consistency.hpp    NEES, chi-square bounds, Monte Carlo, paired tests
///   sylva/diff.hpp           numerical differentiation (to check a model's Jacobians)
///   sylva/core.hpp           also the quaternion helpers of the 3D models
///   sylva/eval.hpp, sylva/sim.hpp, sylva/datasets.hpp
///   sylva/filter/compression.hpp   the compressed EKF (Ekf::setCompression), for large maps
// IWYU pragma: begin_exports
#include "sylva/core/angles.hpp"
#include "sylva/core/error.hpp"
#include "sylva/core/jacobian_ref.hpp"
#include "sylva/core/scalar.hpp"
#include "sylva/core/types.hpp"
#include "sylva/diff/auto_diff.hpp"
#include "sylva/filter.hpp"
#include "sylva/noise.hpp"

#include "sylva/landmarks/point2.hpp"
#include "sylva/landmarks/tree_xyr.hpp"
#include "sylva/measurements/range_bearing.hpp"
#include "sylva/measurements/range_bearing_diameter.hpp"
#include "sylva/motion/ackermann_2d.hpp"
#include "sylva/motion/ackermann_2d_with_bias.hpp"
#include "sylva/motion/odometry_2d.hpp"
#include "sylva/motion/pose_2d.hpp"
#include "sylva/motion/unicycle_2d.hpp"
#include "sylva/motion/unicycle_2d_with_bias.hpp"
// IWYU pragma: end_exports
