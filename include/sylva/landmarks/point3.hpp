#pragma once
/// @file
/// `Point3`: a landmark as a point [x, y, z] in the world frame (metres, z up). Additive
/// perturbations. The "XYZ" parametrization of the tree-width thesis (Sec. 3.5).

#include "sylva/core/types.hpp"

namespace sylva {

struct Point3 {
  static constexpr int kDim = 3;
  static constexpr const char* kName = "Point3";
  using Mean = Vec<3>;
};

}  // namespace sylva
