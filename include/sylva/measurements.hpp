#pragma once
// IWYU pragma: begin_exports
#include "sylva/measurements/pinhole_camera.hpp"
#include "sylva/measurements/range_bearing.hpp"
#include "sylva/measurements/tree_width.hpp"
// IWYU pragma: end_exports
