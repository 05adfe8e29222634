#pragma once
/// @file
/// `TreeXYR`: a tree trunk in a planar map, as the centre [x, y] of its cross-section in the
/// world frame and its trunk radius r (metres). Additive perturbations. The 2D counterpart
/// of `TreeXYZR` for a horizontal laser that measures a trunk's range, bearing and
/// diameter (`RangeBearingDiameter`, e.g. the Victoria Park data set). The domain is r > 0:
/// the filter rejects an initialization or an update that would make the radius zero or
/// negative (kOutOfDomain) and stays unchanged.

#include "sylva/core/types.hpp"

namespace sylva {

struct TreeXYR {
  static constexpr int kDim = 3;  ///< [x_m, y_m, radius_m]
  static constexpr const char* kName = "TreeXYR";
  /// [x_m, y_m] in the world (LinearizationPoint::kInvariant); the radius is frame-free.
  static constexpr int kPlanarPosition = 0;
  using Mean = Vec<3>;

  /// nullptr for r > 0, else the reason (see detail::HasDomain).
  static const char* domainViolation(const Vec<3>& l) {
    return l[2] > 0.0 ? nullptr : "the trunk radius would become zero or negative";
  }
};

}  // namespace sylva
