#pragma once
/// @file
/// Consistency tests (NEES, NIS, NMEE), chi-square bounds, and paired tests for comparing
/// estimators on identical inputs (McNemar, Wilcoxon signed-rank, Wilson intervals). Needs Boost.Math (header-only).
// IWYU pragma: begin_exports
#include "sylva/consistency/camera_pose_nees.hpp"
#include "sylva/consistency/chi_square.hpp"
#include "sylva/consistency/monte_carlo.hpp"
#include "sylva/consistency/nees.hpp"
#include "sylva/consistency/paired_tests.hpp"
// IWYU pragma: end_exports
