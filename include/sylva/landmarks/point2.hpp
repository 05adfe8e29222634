#pragma once
/// @file
/// `Point2`: a landmark as a point [x, y] in the world frame (metres). Perturbations are
/// additive. This is the landmark of 2D range-bearing SLAM (multisensor thesis eq. 2.20).

#include "sylva/core/types.hpp"

namespace sylva {

struct Point2 {
  static constexpr int kDim = 2;
  static constexpr const char* kName = "Point2";
  static constexpr int kPlanarPosition = 0;  ///< [x, y] in the world (LinearizationPoint::kInvariant)
  using Mean = Vec<2>;
};

}  // namespace sylva
