#pragma once
/// @file
/// `LaserScanGeometry`: the beam angles and valid range interval of a planar laser scan,
/// shared by what reads a scan (`LaserCameraSensor`, the `sylva/laser` tools, which check it
/// with `laser::validateScanGeometry`) and the scanner simulator
/// (`sim::LaserScanner2D::geometry()`).

#include "sylva/core/angles.hpp"

namespace sylva {

/// The beams of a planar scan: a_k = angle_min + k * increment, k = 0 .. beams - 1.
struct LaserScanGeometry {
  double angle_min_rad = -0.5 * kPi;
  double angle_increment_rad = 0.5 * kRadPerDeg;
  int beams = 361;
  double min_range_m = 0.05;  ///< readings below are invalid
  double max_range_m = 8.0;   ///< readings above are "no return"

  double beamAngle(int k) const { return angle_min_rad + k * angle_increment_rad; }
  double angleMax() const { return beamAngle(beams - 1); }
};

}  // namespace sylva
