#pragma once
/// @file
/// Angle helpers. `wrapAngle` maps any finite angle to (-pi, pi].

#include <cmath>

#include "sylva/core/scalar.hpp"

namespace sylva {

inline constexpr double kPi = 3.14159265358979323846;
/// Radians per degree: `30.0 * kRadPerDeg` is 30 degrees in radians.
inline constexpr double kRadPerDeg = kPi / 180.0;

/// Wraps an angle in radians to (-pi, pi]. Templated so that autodiff scalars pass through
/// (the wrap is a shift by a multiple of 2 pi, whose derivative is 1).
template <typename T>
T wrapAngle(const T& angle) {
  // a - 2 pi * ceil((a - pi) / (2 pi)) lies in (-pi, pi].
  const double a = static_cast<double>(scalarValue(angle));
  const double turns = std::ceil((a - kPi) / (2.0 * kPi));
  return angle - T(2.0 * kPi * turns);
}

}  // namespace sylva
