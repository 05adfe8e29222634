#pragma once
// Test helpers: a camera pose (Pose3D) or ConstantVelocity3D state placed by where it stands and
// what it looks at.
#include <cmath>

#include <Eigen/Geometry>

#include <sylva/core/types.hpp>

namespace sylva_test {

/// The camera state [r_WC, q_WC (w, x, y, z), v_W, omega_C] at `position`, looking at
/// `target` (world z up; camera x right, y down, z along the optical axis), rolled by
/// `roll_rad` about the optical axis. The stored quaternion is multiplied by `scale` (the
/// models normalize it). The velocities default to non-zero values, which must not enter a
/// measurement. Looking straight up or down, the camera's x axis is taken along world y x
/// the viewing direction instead.
inline sylva::Vec<13> lookAt(const sylva::Vec<3>& position,
                             const sylva::Vec<3>& target,
                             double roll_rad = 0.0,
                             double scale = 1.0,
                             const sylva::Vec<6>& velocities = (sylva::Vec<6>() << 0.3, -0.2, 0.1, 0.05, 0.1, -0.2).finished()) {
  using sylva::Vec;
  const Vec<3> z_C = (target - position).normalized();
  Vec<3> side = z_C.cross(Vec<3>::UnitZ());
  if (side.norm() < 1e-9) side = z_C.cross(Vec<3>::UnitX());
  const Vec<3> x_C0 = side.normalized();
  const Vec<3> y_C0 = z_C.cross(x_C0);
  const Vec<3> x_C = std::cos(roll_rad) * x_C0 + std::sin(roll_rad) * y_C0;
  const Vec<3> y_C = z_C.cross(x_C);
  sylva::Mat<3, 3> R;  // camera -> world: its columns are the camera axes in the world
  R << x_C, y_C, z_C;
  const Eigen::Quaterniond q(R);
  Vec<13> x;
  x << position, scale * Vec<4>(q.w(), q.x(), q.y(), q.z()), velocities;
  return x;
}

/// The pose [r_WC, q_WC] (Pose3D, what the camera models see) of lookAt's camera.
inline sylva::Vec<7> lookAtPose(const sylva::Vec<3>& position,
                                const sylva::Vec<3>& target,
                                double roll_rad = 0.0,
                                double scale = 1.0) {
  return lookAt(position, target, roll_rad, scale).head<7>();
}

}  // namespace sylva_test
