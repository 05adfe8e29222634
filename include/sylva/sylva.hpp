#pragma once
/// @file
/// Umbrella header: everything a user of sylva needs.
// IWYU pragma: begin_exports
#include "sylva/core.hpp"
#include "sylva/filter.hpp"
#include "sylva/landmarks.hpp"
#include "sylva/measurements.hpp"
#include "sylva/motion.hpp"
#include "sylva/noise.hpp"
#include "sylva/diff.hpp"
// IWYU pragma: end_exports
