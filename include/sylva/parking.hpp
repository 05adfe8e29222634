#pragma once
/// @file
/// Umbrella header of the vision-based parking controller of the multisensor thesis (Ch. 5):
/// the hybrid controller that turns the image positions of a parking station's three features
/// into a robot command. It needs only `sylva/core`; nothing else in sylva depends on it.
// IWYU pragma: begin_exports
#include "sylva/parking/hybrid_controller.hpp"
// IWYU pragma: end_exports
