#pragma once
/// @file
/// Umbrella header of the laser-camera sensor front end (multisensor thesis, Ch. 3): the
/// calibrated sensor that turns a vertical image line and a laser scan into a range-bearing
/// measurement, its calibration curve and the range interpolation between beams. Its
/// measurements feed `RangeBearing` (sylva/sylva.hpp).
// IWYU pragma: begin_exports
#include "sylva/laser_camera/calibration.hpp"
#include "sylva/laser_camera/range_interpolation.hpp"
#include "sylva/laser_camera/sensor.hpp"
#include "sylva/measurements/laser_scan_geometry.hpp"
// IWYU pragma: end_exports
