#pragma once
/// @file
/// Umbrella header of the laser scan tools: scans placed in the world by their sensor pose,
/// continuous segments, the moving-object detector of the multisensor thesis (Ch. 4), object
/// positions and tracks, and point features for range-bearing SLAM (poles and corners). They
/// need only `sylva/core`; nothing in the filter depends on them.
// IWYU pragma: begin_exports
#include "sylva/laser/corner_features.hpp"
#include "sylva/laser/moving_object_detector.hpp"
#include "sylva/laser/object_position.hpp"
#include "sylva/laser/object_tracker.hpp"
#include "sylva/laser/pole_features.hpp"
#include "sylva/laser/scan.hpp"
#include "sylva/laser/scan_matching.hpp"
#include "sylva/laser/segments.hpp"
// IWYU pragma: end_exports
