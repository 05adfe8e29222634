#pragma once
/// @file
/// Fixed-size Eigen aliases used throughout sylva, and the landmark id type.

#include <Eigen/Core>
#include <cstdint>

namespace sylva {

/// Column vector of N doubles (N known at compile time wherever possible).
template <int N, typename Scalar_ = double>
using Vec = Eigen::Matrix<Scalar_, N, 1>;

/// R x C matrix of doubles.
template <int R, int C, typename Scalar_ = double>
using Mat = Eigen::Matrix<Scalar_, R, C>;

/// A user-chosen landmark identifier (e.g. the simulator's or a detector's id).
using Id = std::int64_t;

}  // namespace sylva
