#pragma once
// IWYU pragma: begin_exports
#include "sylva/landmarks/inverse_depth.hpp"
#include "sylva/landmarks/inverse_depth_radius.hpp"
#include "sylva/landmarks/point2.hpp"
#include "sylva/landmarks/point3.hpp"
#include "sylva/landmarks/tree_xyr.hpp"
#include "sylva/landmarks/tree_xyzr.hpp"
// IWYU pragma: end_exports
