#pragma once
// The simulated world of the parking example: a parking station of three equally spaced
// features and a camera fixed to a unicycle robot (thesis Sec. 5.2).
//
// World frame (sylva's): x right, y forward, z up. The station stands on the line y = 0 and
// faces -y; its features are P1 = (-d, 0), P2 = (0, 0), P3 = (d, 0). The robot approaches
// from y < 0; the thesis' "y-axis" (Fig. 5.7, 5.9) is the world y axis, and x is the lateral
// offset from it (P3's side positive).
//
// Camera (eq. 5.3, assumptions 1 and 3 of Sec. 5.2.4): a pinhole whose centre is on the
// robot's rotation axis and whose optical axis is the robot's heading; the features are at
// the height of the optical axis, so only the horizontal image position matters. A feature at
// (x_r, y_r) in the robot frame (x_r forward, y_r to the left) is seen at
//
//   u = W/2 + f * tan(gamma),   tan(gamma) = -y_r / x_r     (gamma clockwise, to the right)
//
// with f = lambda p the focal length in pixels. It is in the image when x_r > 0 and
// 0 <= u <= W, and only from the station's front (robot y < 0). A measured position is the
// true one plus N(0, sigma^2) pixel noise, clamped to the image (a blob centroid cannot lie
// outside it).

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include <Eigen/LU>

#include <sylva/core/angles.hpp>
#include <sylva/core/error.hpp>
#include <sylva/core/types.hpp>
#include <sylva/sim/random.hpp>

namespace parking {

using Pose = sylva::Vec<3>;  ///< [x, y, theta] (m, m, rad)

struct CameraParams {
  double image_width_px = 1392.0;  ///< W (Basler A102fc)
  double focal_px = 1240.0;        ///< f = lambda p: an 8 mm lens on 6.45 um pixels (assumed)
  double spacing_m = 0.106;        ///< d, feature spacing (Table 5.2: B/2 = 106 mm)
  double sigma_px = 0.5;           ///< pixel noise of a measured feature position
  double frame_rate_hz = 19.0;     ///< Sec. 5.5: about 19 frames per second

  void validate() const {
    const auto positive = [](const char* name, double v) {
      if (!std::isfinite(v)) {
        std::ostringstream os;
        os << "camera: " << name << " must be finite, got " << v;
        sylva::fail(sylva::ErrorCode::kNonFinite, os.str());
      }
      if (!(v > 0.0)) {
        std::ostringstream os;
        os << "camera: " << name << " must be > 0, got " << v;
        sylva::fail(sylva::ErrorCode::kInvalidArgument, os.str());
      }
    };
    positive("image_width_px", image_width_px);
    positive("focal_px", focal_px);
    positive("spacing_m", spacing_m);
    positive("frame_rate_hz", frame_rate_hz);
    if (!std::isfinite(sigma_px))
      sylva::fail(sylva::ErrorCode::kNonFinite, "camera: sigma_px must be finite");
    if (sigma_px < 0.0) {
      std::ostringstream os;
      os << "camera: sigma_px must be >= 0, got " << sigma_px;
      sylva::fail(sylva::ErrorCode::kInvalidArgument, os.str());
    }
  }
};

/// The true (noise-free) view of the station from one pose.
struct StationView {
  std::array<double, 3> u{};      ///< eq. 5.3, may lie outside [0, W]
  std::array<bool, 3> visible{};  ///< in front of the camera and inside the image
  bool allVisible() const { return visible[0] && visible[1] && visible[2]; }
};

class StationCamera {
 public:
  explicit StationCamera(const CameraParams& params = {}) : p_(params) { p_.validate(); }

  const CameraParams& params() const { return p_; }

  /// World position of feature i (0: P1, 1: P2, 2: P3).
  sylva::Vec<2> feature(int i) const { return sylva::Vec<2>((i - 1) * p_.spacing_m, 0.0); }

  /// Eq. 5.3: where each feature appears, without noise.
  StationView view(const Pose& pose) const {
    StationView out;
    const double c = std::cos(pose[2]);
    const double s = std::sin(pose[2]);
    for (int i = 0; i < 3; ++i) {
      const sylva::Vec<2> d = feature(i) - pose.head<2>();
      const double x_r = c * d.x() + s * d.y();   // forward
      const double y_r = -s * d.x() + c * d.y();  // left
      const auto k = static_cast<std::size_t>(i);
      out.u[k] = x_r > 0.0 ? 0.5 * p_.image_width_px - p_.focal_px * y_r / x_r
                           : std::numeric_limits<double>::quiet_NaN();
      out.visible[k] =
          pose[1] < 0.0 && x_r > 1e-6 && out.u[k] >= 0.0 && out.u[k] <= p_.image_width_px;
    }
    return out;
  }

  /// One frame: the measured positions of the visible features, left to right.
  std::vector<double> observe(const Pose& pose, sylva::sim::Rng& rng) const {
    const StationView v = view(pose);
    std::vector<double> out;
    out.reserve(3);
    for (std::size_t i = 0; i < 3; ++i) {
      if (!v.visible[i]) continue;
      const double u = v.u[i] + (p_.sigma_px > 0.0 ? p_.sigma_px * rng.normal() : 0.0);
      out.push_back(std::clamp(u, 0.0, p_.image_width_px));
    }
    return out;
  }

  /// The pose from which the station is seen exactly at `reference_px` (the goal of the
  /// parking task): Newton's method on the three equations of eq. 5.3, started on the axis
  /// at the distance where the station's width is A^r. Throws kDegenerateGeometry if the
  /// reference cannot be seen from any pose.
  Pose goalPose(const std::array<double, 3>& reference_px) const {
    const double A_r = reference_px[2] - reference_px[0];
    Pose x(0.0, -2.0 * p_.focal_px * p_.spacing_m / A_r, 0.5 * sylva::kPi);
    const auto residual = [&](const Pose& pose) {
      const StationView v = view(pose);
      sylva::Vec<3> r;
      for (int i = 0; i < 3; ++i)
        r[i] = v.u[static_cast<std::size_t>(i)] - reference_px[static_cast<std::size_t>(i)];
      return r;
    };
    for (int iter = 0; iter < 50; ++iter) {
      const sylva::Vec<3> r = residual(x);
      if (!r.allFinite()) break;
      if (r.norm() < 1e-9) return x;
      sylva::Mat<3, 3> J;
      for (int j = 0; j < 3; ++j) {
        Pose h = x;
        const double step = j < 2 ? 1e-7 : 1e-8;
        h[j] += step;
        J.col(j) = (residual(h) - r) / step;
      }
      const Eigen::FullPivLU<sylva::Mat<3, 3>> lu(J);
      if (!lu.isInvertible()) break;
      x -= lu.solve(r);
    }
    if (residual(x).norm() < 1e-6) return x;
    sylva::fail(sylva::ErrorCode::kDegenerateGeometry,
                "camera: no pose sees the station at the reference positions (check the focal "
                "length, the feature spacing and the reference)");
  }

 private:
  CameraParams p_;
};

}  // namespace parking
