#pragma once
/// @file
/// Umbrella header of the dataset loaders (namespace sylva::datasets): readers of the plain
/// text formats of public SLAM datasets. The data themselves never ship with sylva; every
/// loader takes a path and reports a malformed file with its name and line number.
// IWYU pragma: begin_exports
#include "sylva/datasets/numeric_table.hpp"
#include "sylva/datasets/utias_mrclam.hpp"
#include "sylva/datasets/victoria_park.hpp"
// IWYU pragma: end_exports
