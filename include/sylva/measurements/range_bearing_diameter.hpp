#pragma once
/// @file
/// `RangeBearingDiameter`: a horizontal laser's detection of a tree trunk, z = [range to the
/// trunk centre, bearing, trunk diameter] (m, rad, m), from a planar robot (any robot deriving
/// from `Pose2D`) to a `TreeXYR` landmark [x, y, r]; and `InverseRangeBearingDiameter`, the
/// landmark initialization from one detection. This is what the tree detector of the Victoria
/// Park experiments returns (Guivant and Nebot 2001; the diameter comes from the angular
/// width of the trunk's segment of the scan). It is the laser counterpart of the tree-width
/// idea of the monocular instance (`TreeWidth`): the trunk's size is measured and mapped.
///
/// With s the sensor position (`RangeBearing`, optional mount m in the robot frame):
///
///   z = [ |c - s|, wrap(atan2(c_y - s_y, c_x - s_x) - theta_r), 2 r ],   c = [x, y]
///
/// Jacobians (additive perturbations): the first two rows are those of `RangeBearing` with
/// the landmark's centre, the third is d(2r) = [0 0 0 | 0 0 2]:
///
///   J_z_x (3x3) = [ J_rb_x ; 0 0 0 ]          J_z_l (3x3) = [ J_rb_l  0 ; 0 0 2 ]
///
/// Inverse: l = [ s + r_z (cos(theta_r + b), sin(theta_r + b)),  d / 2 ], with the Jacobians
/// of `InverseRangeBearing` and dr/dd = 1/2.
///
/// Errors: a trunk centre on the sensor -> kDegenerateGeometry (as `RangeBearing`); the
/// inverse model refuses a range <= 0 (kDegenerateGeometry), a diameter <= 0 (kOutOfDomain:
/// the radius must stay > 0) and non-finite input (kNonFinite).
///
/// Common mistakes: the range to the trunk surface instead of its centre (the Victoria Park
/// detector already adds d / 2); a diameter noise that ignores the beam spacing (the
/// angular width is quantised, so the diameter's error grows with the range).

#include <cmath>
#include <sstream>

#include "sylva/core/error.hpp"
#include "sylva/core/jacobian_ref.hpp"
#include "sylva/core/types.hpp"
#include "sylva/landmarks/tree_xyr.hpp"
#include "sylva/measurements/range_bearing.hpp"
#include "sylva/motion/pose_2d.hpp"

namespace sylva {

struct RangeBearingDiameter {
  using Robot = Pose2D;
  using Landmark = TreeXYR;
  static constexpr int kDim = 3;  ///< [range_m, bearing_rad, diameter_m]
  static constexpr const char* kName = "RangeBearingDiameter";

  RangeBearingDiameter() = default;
  /// A sensor at `sensor_in_robot` (m, robot frame), axes parallel to the robot's.
  explicit RangeBearingDiameter(const Vec<2>& sensor_in_robot) : range_bearing_(sensor_in_robot) {}
  const Vec<2>& mount() const { return range_bearing_.mount(); }

  /// Predicted [range, bearing, diameter], generic in the scalar for autodiff.
  template <typename T>
  Vec<3, T> predict(const Vec<3, T>& robot, const Vec<3, T>& landmark) const {
    const Vec<2, T> rb = range_bearing_.predict<T>(robot, Vec<2, T>(landmark.template head<2>()));
    return Vec<3, T>(rb[0], rb[1], T(2.0) * landmark[2]);
  }

  /// Prediction with the analytic Jacobians (see the file comment).
  template <typename Tag = void>  // compiled only where called (core/deferred.hpp)
  Vec<3> operator()(const Vec<3>& robot,
                    const Vec<3>& landmark,
                    JacobianArg<3, 3, Tag> J_z_x = {},
                    JacobianArg<3, 3, Tag> J_z_l = {}) const {
    Mat<2, 3> J_rb_x;
    Mat<2, 2> J_rb_l;
    const Vec<2> rb = range_bearing_(robot, Vec<2>(landmark.head<2>()), J_rb_x, J_rb_l);
    if (J_z_x) {
      (*J_z_x).setZero();
      (*J_z_x).template topRows<2>() = J_rb_x;
    }
    if (J_z_l) {
      (*J_z_l).setZero();
      (*J_z_l).template topLeftCorner<2, 2>() = J_rb_l;
      (*J_z_l)(2, 2) = 2.0;
    }
    return Vec<3>(rb[0], rb[1], 2.0 * landmark[2]);
  }

  /// Innovation z - z_hat with the bearing difference wrapped to (-pi, pi].
  Vec<3> residual(const Vec<3>& z, const Vec<3>& z_hat) const {
    return Vec<3>(z[0] - z_hat[0], wrapAngle(z[1] - z_hat[1]), z[2] - z_hat[2]);
  }

 private:
  RangeBearing range_bearing_;
};

/// A `TreeXYR` from its first detection [range, bearing, diameter] (see the file comment).
struct InverseRangeBearingDiameter {
  using Robot = Pose2D;
  using Landmark = TreeXYR;
  static constexpr int kMeasurementDim = 3;
  static constexpr const char* kName = "InverseRangeBearingDiameter";

  InverseRangeBearingDiameter() = default;
  explicit InverseRangeBearingDiameter(const Vec<2>& sensor_in_robot) : inverse_(sensor_in_robot) {}
  const Vec<2>& mount() const { return inverse_.mount(); }

  /// The landmark [centre, d / 2], generic in the scalar for automatic differentiation. No
  /// checks: operator() validates z and returns this.
  template <typename T>
  Vec<3, T> initialize(const Vec<3, T>& robot, const Vec<3, T>& z) const {
    const Vec<2, T> centre = inverse_.initialize<T>(robot, Vec<2, T>(z.template head<2>()));
    return Vec<3, T>(centre[0], centre[1], T(0.5) * z[2]);
  }

  template <typename Tag = void>  // compiled only where called (core/deferred.hpp)
  Vec<3> operator()(const Vec<3>& robot,
                    const Vec<3>& z,
                    JacobianArg<3, 3, Tag> J_l_x = {},
                    JacobianArg<3, 3, Tag> J_l_z = {}) const {
    if (!z.allFinite()) fail(ErrorCode::kNonFinite, "InverseRangeBearingDiameter: measurement is not finite");
    if (!(z[2] > 0.0)) {
      std::ostringstream os;
      os << "InverseRangeBearingDiameter: diameter " << z[2] << " m must be > 0";
      fail(ErrorCode::kOutOfDomain, os.str());
    }
    Mat<2, 3> J_c_x;
    Mat<2, 2> J_c_z;
    inverse_(robot, Vec<2>(z.head<2>()), J_c_x, J_c_z);
    if (J_l_x) {
      (*J_l_x).setZero();
      (*J_l_x).template topRows<2>() = J_c_x;
    }
    if (J_l_z) {
      (*J_l_z).setZero();
      (*J_l_z).template topLeftCorner<2, 2>() = J_c_z;
      (*J_l_z)(2, 2) = 0.5;
    }
    return initialize<double>(robot, z);
  }

 private:
  InverseRangeBearing inverse_;
};

}  // namespace sylva
