#pragma once
// A second 2D landmark parametrization for the filter tests: a point stored as its anchor
// (the robot position when first seen), world bearing alpha and inverse distance rho, the
// 2D analogue of an inverse-depth point. It lets the tests put two landmark types side by
// side in one state, exercise automatic differentiation (its measurement model has no
// analytic Jacobian) and reparametrize one type into the other.

#include <cmath>

#include <sylva/core/angles.hpp>
#include <sylva/core/jacobian_ref.hpp>
#include <sylva/core/scalar.hpp>
#include <sylva/core/types.hpp>
#include <sylva/landmarks/point2.hpp>
#include <sylva/motion/unicycle_2d.hpp>

namespace sylva_test {

using sylva::JacobianRef;
using sylva::Mat;
using sylva::Vec;

struct InverseDistance2 {
  static constexpr int kDim = 4;  // [anchor_x, anchor_y, alpha, rho]
  static constexpr const char* kName = "InverseDistance2";
  static void normalize(Eigen::Ref<Vec<4>> l) { l[2] = sylva::wrapAngle(l[2]); }
};

/// Range and bearing to an InverseDistance2 landmark; prediction only, so the filter
/// differentiates it automatically.
struct RangeBearingToInverseDistance {
  using Robot = sylva::Unicycle2D;
  using Landmark = InverseDistance2;
  static constexpr int kDim = 2;
  static constexpr const char* kName = "RangeBearingToInverseDistance";

  template <typename T>
  Vec<2, T> predict(const Vec<3, T>& x, const Vec<4, T>& l) const {
    using std::cos;
    using std::sin;
    using std::sqrt;
    const T px = l[0] + cos(l[2]) / l[3];
    const T py = l[1] + sin(l[2]) / l[3];
    const T dx = px - x[0];
    const T dy = py - x[1];
    Vec<2, T> z;
    z[0] = sqrt(dx * dx + dy * dy);
    z[1] = sylva::wrapAngle(T(sylva::atan2Generic(dy, dx) - x[2]));
    return z;
  }

  Vec<2> residual(const Vec<2>& z, const Vec<2>& z_hat) const {
    return Vec<2>(z[0] - z_hat[0], sylva::wrapAngle(z[1] - z_hat[1]));
  }
};

/// Initialization of an InverseDistance2 landmark from [range, bearing].
struct InverseDistanceFromRangeBearing {
  using Robot = sylva::Unicycle2D;
  using Landmark = InverseDistance2;
  static constexpr int kMeasurementDim = 2;
  static constexpr const char* kName = "InverseDistanceFromRangeBearing";

  Vec<4> operator()(const Vec<3>& x, const Vec<2>& z, JacobianRef<4, 3> J_l_x = {},
                    JacobianRef<4, 2> J_l_z = {}) const {
    if (J_l_x) {
      *J_l_x << 1, 0, 0,  //
          0, 1, 0,        //
          0, 0, 1,        //
          0, 0, 0;
    }
    if (J_l_z) {
      *J_l_z << 0, 0,  //
          0, 0,        //
          0, 1,        //
          -1.0 / (z[0] * z[0]), 0;
    }
    return Vec<4>(x[0], x[1], sylva::wrapAngle(x[2] + z[1]), 1.0 / z[0]);
  }
};

/// InverseDistance2 -> Point2 (does not depend on the robot).
struct InverseDistanceToPoint {
  using From = InverseDistance2;
  using To = sylva::Point2;
  static constexpr const char* kName = "InverseDistanceToPoint";

  Vec<2> operator()(const Vec<3>& /*robot*/, const Vec<4>& l, JacobianRef<2, 3> J_to_x = {},
                    JacobianRef<2, 4> J_to_l = {}) const {
    const double c = std::cos(l[2]);
    const double s = std::sin(l[2]);
    const double d = 1.0 / l[3];
    if (J_to_x) (*J_to_x).setZero();
    if (J_to_l) {
      *J_to_l << 1, 0, -s * d, -c * d * d,  //
          0, 1, c * d, -s * d * d;
    }
    return Vec<2>(l[0] + c * d, l[1] + s * d);
  }
};

/// Point2 -> InverseDistance2 anchored at the current robot position (depends on the robot,
/// so the conversion's robot Jacobian is exercised).
struct PointToInverseDistance {
  using From = sylva::Point2;
  using To = InverseDistance2;
  static constexpr const char* kName = "PointToInverseDistance";

  Vec<4> operator()(const Vec<3>& x, const Vec<2>& p, JacobianRef<4, 3> J_to_x = {},
                    JacobianRef<4, 2> J_to_l = {}) const {
    const double dx = p[0] - x[0];
    const double dy = p[1] - x[1];
    const double d2 = dx * dx + dy * dy;
    const double d = std::sqrt(d2);
    const double d3 = d2 * d;
    if (J_to_x) {
      *J_to_x << 1, 0, 0,        //
          0, 1, 0,               //
          dy / d2, -dx / d2, 0,  //
          dx / d3, dy / d3, 0;
    }
    if (J_to_l) {
      *J_to_l << 0, 0,      //
          0, 0,             //
          -dy / d2, dx / d2,  //
          -dx / d3, -dy / d3;
    }
    return Vec<4>(x[0], x[1], std::atan2(dy, dx), 1.0 / d);
  }
};

}  // namespace sylva_test
