#pragma once
/// @file
/// `Point3`: a landmark as a point [x, y, z] in the world frame (metres, z up). Additive
/// perturbations. The "XYZ" parametrization of the tree-width thesis (Sec. 3.5).

#include "sylva/core/gauge.hpp"
#include "sylva/core/types.hpp"

namespace sylva {

struct Point3 {
  static constexpr int kDim = 3;
  static constexpr const char* kName = "Point3";
  using Mean = Vec<3>;

  /// How moving, turning (about world z) and scaling the world move the point (core/gauge.hpp).
  static Mat<3, kGaugeDim> gaugeDirections(const Vec<3>& p) {
    Mat<3, kGaugeDim> N;
    N.leftCols<3>().setIdentity();
    N.col(3) << -p.y(), p.x(), 0.0;  // e_z x p
    N.col(4) = p;
    return N;
  }
};

}  // namespace sylva
