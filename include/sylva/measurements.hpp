#pragma once
// IWYU pragma: begin_exports
#include "sylva/measurements/inverse_depth_initialization.hpp"
#include "sylva/measurements/inverse_depth_tree_width.hpp"
#include "sylva/measurements/inverse_tree_width.hpp"
#include "sylva/measurements/pinhole_camera.hpp"
#include "sylva/measurements/pinhole_point.hpp"
#include "sylva/measurements/range_bearing.hpp"
#include "sylva/measurements/range_bearing_diameter.hpp"
#include "sylva/measurements/tree_width.hpp"
// IWYU pragma: end_exports
