#pragma once
/// @file
/// `RangeBearing`: range and bearing from a planar robot (any robot deriving from `Pose2D`:
/// `Unicycle2D`, `Odometry2D`) to a `Point2` landmark (multisensor thesis, Amarasinghe 2008,
/// eq. 2.15-2.17), and `InverseRangeBearing`, the landmark initialization from one such
/// measurement (eq. 2.33, 2.37-2.38).
///
///   dx = x_l - x_r,  dy = y_l - y_r,  d = sqrt(dx^2 + dy^2)
///   z  = [ d, wrap(atan2(dy, dx) - theta_r) ]                      (2.16, 2.17)
///
/// Jacobians (eq. 2.30; additive perturbations of robot and landmark):
///
///   J_z_x (2x3) = [ -dx/d    -dy/d     0 ]     J_z_l (2x2) = [  dx/d    dy/d   ]
///                 [  dy/d^2  -dx/d^2  -1 ]                   [ -dy/d^2  dx/d^2 ]
///
/// (The thesis prints dx/d twice in the landmark columns of the first row; the second is
/// dy/d, as the derivative shows and the tests check.)
///
/// The bearing is wrapped to (-pi, pi] (the thesis states [-pi/2, pi/2] for a forward-looking
/// sensor; the model itself is defined all around). `residual` wraps the bearing
/// difference so an innovation never jumps by 2 pi.
///
/// Sensor mount. Both models take an optional sensor position m = [m_x, m_y] in the robot
/// frame (x forward, y left; default zero), for a sensor whose axes are parallel to the
/// robot's but which sits away from the robot's origin (the laser at the front corner of a
/// car whose state is its rear axle). Range and bearing are then measured from the sensor
/// position s = p_r + R(theta_r) m, the bearing still relative to the robot heading:
///
///   dx = x_l - s_x,  dy = y_l - s_y,   z as above
///   J_z_x = [ -J_z_l  | -J_z_l ds/dtheta + (0, -1)^T ],  ds/dtheta = R'(theta_r) m
///   l = s + r [cos(theta_r + b), sin(theta_r + b)],   J_l_x = [ I | ds/dtheta + r (-sin, cos)^T ]
///
/// With m = 0 (the default) the code takes the path without the mount, so results are
/// bit-identical to the unmounted model and cost nothing extra.
///
/// Common mistakes: a landmark at the sensor's position has no bearing; `RangeBearing`
/// throws `ErrorCode::kDegenerateGeometry` for d < 1e-9 m rather than return garbage. A
/// mount given in the world frame, or a bearing measured from the sensor's own axis when the
/// sensor is rotated (only a translated sensor is modelled here).

#include <cmath>
#include <sstream>
#include <string>

#include "sylva/core/angles.hpp"
#include "sylva/core/deferred.hpp"
#include "sylva/core/error.hpp"
#include "sylva/core/jacobian_ref.hpp"
#include "sylva/core/scalar.hpp"
#include "sylva/core/types.hpp"
#include "sylva/landmarks/point2.hpp"
#include "sylva/motion/pose_2d.hpp"

namespace sylva {

struct RangeBearing {
  using Robot = Pose2D;  // serves Unicycle2D, Odometry2D, ...
  using Landmark = Point2;
  static constexpr int kDim = 2;  ///< [range_m, bearing_rad]
  static constexpr const char* kName = "RangeBearing";
  /// Below this distance (m) the bearing is undefined.
  static constexpr double kMinRange = 1e-9;

  RangeBearing() = default;
  /// A sensor at `sensor_in_robot` (m, robot frame x forward, y left), axes parallel to the
  /// robot's. Throws kNonFinite for a non-finite mount.
  template <typename Tag = void>  // compiled only where called (core/deferred.hpp)
  explicit RangeBearing(const detail::Deferred<Vec<2>, Tag>& sensor_in_robot) : mount_(sensor_in_robot) {
    if (!mount_.allFinite()) fail(ErrorCode::kNonFinite, "RangeBearing: the sensor mount is not finite");
  }
  const Vec<2>& mount() const { return mount_; }
  /// False for the default sensor at the robot's origin (the code then skips the mount).
  bool mounted() const { return mount_[0] != 0.0 || mount_[1] != 0.0; }

  /// ds/dtheta = R'(theta) m: how the sensor position moves with the robot heading.
  Vec<2> mountRate(double theta) const {
    const double c = std::cos(theta);
    const double s = std::sin(theta);
    return Vec<2>(-s * mount_[0] - c * mount_[1], c * mount_[0] - s * mount_[1]);
  }

  /// The sensor position in the world frame, generic in the scalar.
  template <typename T>
  Vec<2, T> sensorPosition(const Vec<3, T>& robot) const {
    if (!mounted()) return robot.template head<2>();
    using std::cos;
    using std::sin;
    const T c = cos(robot[2]);
    const T s = sin(robot[2]);
    return Vec<2, T>(robot[0] + c * mount_[0] - s * mount_[1], robot[1] + s * mount_[0] + c * mount_[1]);
  }

  /// Predicted [range, bearing] (eq. 2.16-2.17), generic in the scalar for autodiff.
  template <typename T>
  Vec<2, T> predict(const Vec<3, T>& robot, const Vec<2, T>& landmark) const {
    using std::sqrt;
    const Vec<2, T> sensor = sensorPosition(robot);
    const T dx = landmark[0] - sensor[0];
    const T dy = landmark[1] - sensor[1];
    const T d2 = dx * dx + dy * dy;
    if (!(scalarValue(d2) >= kMinRange * kMinRange)) {
      std::ostringstream os;
      os << "RangeBearing: landmark (" << scalarValue(landmark[0]) << ", "
         << scalarValue(landmark[1]) << ") coincides with the " << (mounted() ? "sensor" : "robot")
         << " position; bearing undefined";
      fail(std::isfinite(scalarValue(d2)) ? ErrorCode::kDegenerateGeometry : ErrorCode::kNonFinite,
           os.str());
    }
    Vec<2, T> z;
    z[0] = sqrt(d2);
    z[1] = wrapAngle(T(atan2Generic(dy, dx) - robot[2]));
    return z;
  }

  /// Prediction with the analytic Jacobians of eq. 2.30.
  template <typename Tag = void>  // compiled only where called (core/deferred.hpp)
  Vec<2> operator()(const Vec<3>& robot,
                    const Vec<2>& landmark,
                    JacobianArg<2, 3, Tag> J_z_x = {},
                    JacobianArg<2, 2, Tag> J_z_l = {}) const {
    const Vec<2> z = predict<double>(robot, landmark);
    const Vec<2> sensor = sensorPosition<double>(robot);
    const double dx = landmark[0] - sensor[0];
    const double dy = landmark[1] - sensor[1];
    const double d = z[0];
    const double d2 = d * d;
    if (J_z_x) {
      *J_z_x << -dx / d, -dy / d, 0.0,  //
          dy / d2, -dx / d2, -1.0;
      if (mounted())  // the sensor moves with theta
        (*J_z_x).col(2) += (*J_z_x).template leftCols<2>() * mountRate(robot[2]);
    }
    if (J_z_l) {
      *J_z_l << dx / d, dy / d,  //
          -dy / d2, dx / d2;
    }
    return z;
  }

  /// Innovation z - z_hat with the bearing difference wrapped to (-pi, pi].
  Vec<2> residual(const Vec<2>& z, const Vec<2>& z_hat) const {
    return Vec<2>(z[0] - z_hat[0], wrapAngle(z[1] - z_hat[1]));
  }

 private:
  Vec<2> mount_{0.0, 0.0};
};

/// Landmark initialization from one range-bearing measurement (eq. 2.33):
///   l = [x_r + r cos(theta_r + b), y_r + r sin(theta_r + b)]
/// with `J_l_x` (2x3, eq. 2.37) and `J_l_z` (2x2, eq. 2.38); from the sensor position when
/// a mount is given (see the file comment).
struct InverseRangeBearing {
  using Robot = Pose2D;  // serves Unicycle2D, Odometry2D, ...
  using Landmark = Point2;
  static constexpr int kMeasurementDim = 2;
  static constexpr const char* kName = "InverseRangeBearing";

  InverseRangeBearing() = default;
  /// A sensor at `sensor_in_robot` (robot frame), as for `RangeBearing`.
  explicit InverseRangeBearing(const Vec<2>& sensor_in_robot) : forward_(sensor_in_robot) {}
  const Vec<2>& mount() const { return forward_.mount(); }

  /// The landmark s + r [cos(theta_r + b), sin(theta_r + b)], generic in the scalar for
  /// automatic differentiation. No checks: operator() validates z and returns this.
  template <typename T>
  Vec<2, T> initialize(const Vec<3, T>& robot, const Vec<2, T>& z) const {
    using std::cos;
    using std::sin;
    const T a = robot[2] + z[1];
    const Vec<2, T> sensor = forward_.sensorPosition<T>(robot);
    return Vec<2, T>(sensor[0] + z[0] * cos(a), sensor[1] + z[0] * sin(a));
  }

  template <typename Tag = void>  // compiled only where called (core/deferred.hpp)
  Vec<2> operator()(const Vec<3>& robot,
                    const Vec<2>& z,
                    JacobianArg<2, 3, Tag> J_l_x = {},
                    JacobianArg<2, 2, Tag> J_l_z = {}) const {
    const double r = z[0];
    if (!std::isfinite(r) || !std::isfinite(z[1]))
      fail(ErrorCode::kNonFinite, "InverseRangeBearing: measurement is not finite");
    if (!(r > 0.0)) {
      std::ostringstream os;
      os << "InverseRangeBearing: range " << r << " m must be > 0";
      fail(ErrorCode::kDegenerateGeometry, os.str());
    }
    const double a = robot[2] + z[1];
    const double c = std::cos(a);
    const double s = std::sin(a);
    if (J_l_x) {
      *J_l_x << 1.0, 0.0, -r * s,  //
          0.0, 1.0, r * c;
      if (forward_.mounted()) (*J_l_x).col(2) += forward_.mountRate(robot[2]);
    }
    if (J_l_z) {
      *J_l_z << c, -r * s,  //
          s, r * c;
    }
    return initialize<double>(robot, z);
  }

 private:
  RangeBearing forward_;  ///< holds the mount and the sensor position
};

}  // namespace sylva
