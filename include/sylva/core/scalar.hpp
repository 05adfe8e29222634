#pragma once
/// @file
/// `scalarValue(x)`: the double value of a plain number or of an automatic-differentiation
/// scalar (anything with `.value()`), so branches inside Scalar-generic models can look at
/// values without caring about derivatives.

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

}  // namespace sylva
