#pragma once
/// @file
/// Consistency tests (NEES, NIS, NMEE) and chi-square bounds. Needs Boost.Math (header-only).
// IWYU pragma: begin_exports
#include "sylva/consistency/camera_pose_nees.hpp"
#include "sylva/consistency/chi_square.hpp"
#include "sylva/consistency/monte_carlo.hpp"
#include "sylva/consistency/nees.hpp"
// IWYU pragma: end_exports
