#pragma once
/// @file
/// `scalarValue(x)`: the double value of a plain number or of an automatic-differentiation
/// scalar (anything with `.value()`), so branches inside Scalar-generic models can look at
/// values without caring about derivatives. `atan2Generic(y, x)`: atan2 for both.

#include <cmath>
#include <type_traits>

namespace sylva {

template <typename T>
double scalarValue(const T& x) {
  if constexpr (std::is_arithmetic_v<T>) {
    return static_cast<double>(x);
  } else {
    return scalarValue(x.value());
  }
}

/// atan2(y, x) for a plain number or an automatic-differentiation scalar, with
/// d atan2 = (x dy - y dx) / (x^2 + y^2). Eigen's own atan2 for `AutoDiffScalar` returns a
/// derivative vector of dynamic size (a heap allocation on every call); this one keeps the
/// arguments' fixed-size type.
template <typename T>
T atan2Generic(const T& y, const T& x) {
  if constexpr (std::is_arithmetic_v<T>) {
    return std::atan2(y, x);
  } else {
    const auto yv = y.value();
    const auto xv = x.value();
    const auto r2 = xv * xv + yv * yv;
    return T(atan2Generic(yv, xv), (xv / r2) * y.derivatives() - (yv / r2) * x.derivatives());
  }
}

}  // namespace sylva
