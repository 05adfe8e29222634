#pragma once
/// @file
/// `sim::forestTrajectory`: the camera's true motion for the forest simulator (tree-width
/// thesis, Sec. 4.1.1): it drives a `BezierLoop2D` `laps` times at constant speed, at a fixed
/// height above the ground, looking along the direction of travel and pitched down so that
/// trunk bases are in view. One frame every `dt_s` seconds.
///
/// Each frame carries the full `ConstantVelocity3D` state [r_WC, q_WC, v_W, omega_C]:
/// r_WC on the path at height `camera_height_m` above `ground(x, y)`; q_WC the rotation with
/// camera z (optical axis) = horizontal direction of travel tilted down by `pitch_rad`,
/// camera x to the right, camera y down (no roll; quaternion signs kept continuous);
/// v_W = (r_{k+1} - r_{k-1}) / (2 dt) and omega_C = log(R_k^T R_{k+1}) / dt (the rotation
/// the constant-velocity model applies in the camera frame), both from the neighbouring
/// poses, one-sided at the ends.

#include <cmath>
#include <functional>
#include <sstream>
#include <vector>

#include <Eigen/Geometry>

#include "sylva/core/angles.hpp"
#include "sylva/core/error.hpp"
#include "sylva/core/types.hpp"
#include "sylva/sim/bezier_loop_2d.hpp"

namespace sylva::sim {

struct TrajectoryOptions {
  double speed_mps = 1.0;
  double dt_s = 0.1;
  int laps = 2;
  double camera_height_m = 1.5;
  double pitch_rad = 15.0 * kRadPerDeg;

  void validate() const {
    std::ostringstream os;
    if (!(std::isfinite(speed_mps) && speed_mps > 0.0)) os << "speed_mps must be > 0, got " << speed_mps;
    else if (!(std::isfinite(dt_s) && dt_s > 0.0)) os << "dt_s must be > 0, got " << dt_s;
    else if (laps < 1) os << "laps must be >= 1, got " << laps;
    else if (!std::isfinite(camera_height_m)) os << "camera_height_m is not finite";
    else if (!(std::isfinite(pitch_rad) && std::abs(pitch_rad) < 1.5)) os << "pitch_rad must be in (-1.5, 1.5), got " << pitch_rad;
    else return;
    fail(ErrorCode::kInvalidArgument, "TrajectoryOptions: " + os.str());
  }
};

struct CameraFrame {
  double t_s;
  int lap;  ///< 0 for the first lap
  Vec<13> state;
};

/// Orientation (camera -> world) looking along the horizontal unit direction `forward`,
/// tilted down by `pitch_rad`.
inline Mat<3, 3> cameraOrientation(const Vec<2>& forward, double pitch_rad) {
  const Vec<3> z_C(std::cos(pitch_rad) * forward.x(), std::cos(pitch_rad) * forward.y(), -std::sin(pitch_rad));
  const Vec<3> x_C = z_C.cross(Vec<3>::UnitZ()).normalized();  // right of the direction of travel
  const Vec<3> y_C = z_C.cross(x_C);                            // down
  Mat<3, 3> R;
  R << x_C, y_C, z_C;
  return R;
}

inline std::vector<CameraFrame> forestTrajectory(const BezierLoop2D& path,
                                                 const TrajectoryOptions& options,
                                                 const std::function<double(double, double)>& ground) {
  options.validate();
  const double total = path.length() * options.laps;
  const int frames = static_cast<int>(std::floor(total / (options.speed_mps * options.dt_s) + 1e-9)) + 1;
  std::vector<Vec<3>> position(frames);
  std::vector<Eigen::Quaterniond> orientation(frames);
  for (int k = 0; k < frames; ++k) {
    const double s = options.speed_mps * options.dt_s * k;
    const Vec<2> p = path.position(s);
    position[k] = Vec<3>(p.x(), p.y(), ground(p.x(), p.y()) + options.camera_height_m);
    orientation[k] = Eigen::Quaterniond(cameraOrientation(path.tangent(s), options.pitch_rad));
    if (k > 0 && orientation[k].coeffs().dot(orientation[k - 1].coeffs()) < 0.0)
      orientation[k].coeffs() = -orientation[k].coeffs();
  }
  std::vector<CameraFrame> out(frames);
  for (int k = 0; k < frames; ++k) {
    const int a = k > 0 ? k - 1 : k;
    const int b = k + 1 < frames ? k + 1 : k;
    const Vec<3> v = (position[b] - position[a]) / (options.dt_s * (b - a));
    const int c = k + 1 < frames ? k : k - 1;  // rotation over [c, c + 1]
    const Eigen::AngleAxisd delta(orientation[c].conjugate() * orientation[c + 1]);
    const Vec<3> omega = delta.axis() * delta.angle() / options.dt_s;
    Vec<13> x;
    const Eigen::Quaterniond& q = orientation[k];
    x << position[k], q.w(), q.x(), q.y(), q.z(), v, omega;
    const double s = options.speed_mps * options.dt_s * k;
    out[k] = CameraFrame{options.dt_s * k, std::min(options.laps - 1, static_cast<int>(s / path.length() + 1e-12)), x};
  }
  return out;
}

}  // namespace sylva::sim
