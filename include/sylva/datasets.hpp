#pragma once
/// @file
/// Umbrella header of the dataset loaders (namespace sylva::datasets): readers of the plain
/// text formats of public SLAM datasets. The data themselves never ship with sylva; every
/// loader takes a path and reports a malformed file with its name and line number. Left out,
/// to keep this header light, are the loaders that bring a sensor's types
/// (`leg_tracker.hpp`: laser scans; `trunk_detections.hpp`: a camera's detections) and the
/// error of a path against Victoria Park's GPS (`victoria_park_gps.hpp`: Eigen's Geometry
/// module for the alignment).
// IWYU pragma: begin_exports
#include "sylva/datasets/numeric_table.hpp"
#include "sylva/datasets/utias_mrclam.hpp"
#include "sylva/datasets/victoria_park.hpp"
// IWYU pragma: end_exports
