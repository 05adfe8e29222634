#pragma once
/// @file
/// Umbrella header of data association: known ids, individual compatibility nearest
/// neighbour, the joint compatibility test and JCBB, and the compatibility table they share. Needs Boost.Math (header-only) for the
/// chi-square gates, through sylva/consistency/chi_square.hpp.
// IWYU pragma: begin_exports
#include "sylva/association/compatibility_table.hpp"
#include "sylva/association/jcbb.hpp"
#include "sylva/association/joint_compatibility.hpp"
#include "sylva/association/known_ids.hpp"
#include "sylva/association/nearest_neighbor.hpp"
#include "sylva/association/smallest_nis.hpp"
// IWYU pragma: end_exports
