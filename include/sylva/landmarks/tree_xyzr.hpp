#pragma once
/// @file
/// `TreeXYZR`: a tree trunk as the centre [x, y, z] of its base circle in the world frame
/// and its trunk radius r (metres). The base circle lies in the plane z = const, parallel to
/// the world x-y plane (z up). Additive perturbations. The "XYZ-R" parametrization of the
/// tree-width thesis (Sec. 3.5); measured by `sylva::TreeWidth`. The domain is r > 0: the
/// filter rejects an update that would make a radius zero or negative (kOutOfDomain).

#include "sylva/core/gauge.hpp"
#include "sylva/core/types.hpp"

namespace sylva {

struct TreeXYZR {
  static constexpr int kDim = 4;  ///< [x_m, y_m, z_m, radius_m]
  static constexpr const char* kName = "TreeXYZR";
  using Mean = Vec<4>;

  /// How moving, turning (about world z) and scaling the world move the tree: its base
  /// centre like a point, its radius with the scale (core/gauge.hpp).
  static Mat<4, kGaugeDim> gaugeDirections(const Vec<4>& l) {
    Mat<4, kGaugeDim> N = Mat<4, kGaugeDim>::Zero();
    N.topLeftCorner<3, 3>().setIdentity();
    N.block<3, 1>(0, 3) << -l.y(), l.x(), 0.0;  // e_z x c
    N.col(4) = l;                                // c and r both scale
    return N;
  }

  /// nullptr for r > 0, else the reason (see detail::HasDomain).
  static const char* domainViolation(const Vec<4>& l) {
    return l[3] > 0.0 ? nullptr : "the trunk radius would become zero or negative";
  }
};

}  // namespace sylva
