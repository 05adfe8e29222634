#pragma once
// Test-only inverse model that puts a landmark with a chosen mean and covariance into a
// filter: the "measurement" z is the landmark itself (J_l_z = I). With kRelativeToCamera
// the first three entries (an anchor) are taken relative to the camera position, which
// correlates the new landmark with the camera (J_l_x = I in the position columns).

#include <sylva/core/jacobian_ref.hpp>
#include <sylva/core/types.hpp>

namespace sylva_test {

template <typename Robot_, typename Landmark_, bool kRelativeToCamera = false>
struct CopyInit {
  using Robot = Robot_;
  using Landmark = Landmark_;
  static constexpr int kMeasurementDim = Landmark::kDim;
  static constexpr const char* kName = "CopyInit";
  sylva::Vec<Landmark::kDim> operator()(const sylva::Vec<Robot::kDim>& x,
                                        const sylva::Vec<Landmark::kDim>& z,
                                        sylva::JacobianRef<Landmark::kDim, Robot::kDim> J_l_x = {},
                                        sylva::JacobianRef<Landmark::kDim, Landmark::kDim> J_l_z = {}) const {
    if (J_l_x) {
      (*J_l_x).setZero();
      if constexpr (kRelativeToCamera) (*J_l_x).template topLeftCorner<3, 3>().setIdentity();
    }
    if (J_l_z) (*J_l_z).setIdentity();
    sylva::Vec<Landmark::kDim> l = z;
    if constexpr (kRelativeToCamera) l.template head<3>() += x.template head<3>();
    return l;
  }
};

}  // namespace sylva_test
