#pragma once
/// @file
/// `InverseDepth`: a point as seen from the camera position that first observed it
/// (Civera, Davison, Montiel 2008, "Inverse depth parametrization for monocular SLAM"):
///
///   l = [ x0, y0, z0, theta, phi, rho ]      (anchor (m), azimuth, elevation (rad), 1/m)
///   p = anchor + m(theta, phi) / rho,  m = [cos(phi) cos(theta), cos(phi) sin(theta), sin(phi)]
///
/// Angles are in the world frame (z up): theta is the azimuth about world z measured from
/// world x, phi the elevation above the world x-y plane. (Civera et al. write m for a world
/// frame whose y axis points down; the geometry is the same, the formula follows our axes.)
/// `normalize` wraps theta to (-pi, pi]. rho > 0 in front of the anchor; a point at infinity
/// has rho = 0, which the parametrization represents but the conversion to XYZ cannot.
///
/// `InverseDepthToPoint3` is the conversion for `Ekf::reparametrize`, and
/// `inverseDepthLinearityIndex` the test of when to apply it (Civera, Davison, Montiel 2007,
/// "Inverse depth to depth conversion for monocular SLAM", eq. 11-13: L = 4 sigma_d |cos a| / d,
/// sigma_d = sigma_rho / rho^2; convert when L falls below a threshold, 0.1 in the paper).

#include <cmath>
#include <sstream>

#include "sylva/core/angles.hpp"
#include "sylva/core/error.hpp"
#include "sylva/core/gauge.hpp"
#include "sylva/core/jacobian_ref.hpp"
#include "sylva/core/types.hpp"
#include "sylva/landmarks/point3.hpp"

namespace sylva {

struct InverseDepth {
  static constexpr int kDim = 6;
  static constexpr const char* kName = "InverseDepth";
  using Mean = Vec<6>;

  /// Unit direction m(theta, phi) in the world frame.
  template <typename T>
  static Vec<3, T> direction(const T& theta, const T& phi) {
    using std::cos;
    using std::sin;
    Vec<3, T> m;
    m << cos(phi) * cos(theta), cos(phi) * sin(theta), sin(phi);
    return m;
  }

  /// [dm/dtheta, dm/dphi] (3 x 2) of the unit direction m(theta, phi): the one place the
  /// inverse-depth models and conversions take it from.
  template <int = 0>  // compiled only where called (docs/build-time.md)
  static Mat<3, 2> directionJacobian(double theta, double phi) {
    const double ct = std::cos(theta), st = std::sin(theta);
    const double cp = std::cos(phi), sp = std::sin(phi);
    Mat<3, 2> J;
    J << -cp * st, -sp * ct,  //
        cp * ct, -sp * st,    //
        0.0, cp;
    return J;
  }

  /// Euclidean point anchor + m / rho (requires rho != 0).
  template <typename T>
  static Vec<3, T> point(const Vec<6, T>& l) {
    return l.template head<3>() + direction<T>(l[3], l[4]) / l[5];
  }

  static void normalize(Eigen::Ref<Vec<6>> l) { l[3] = wrapAngle(l[3]); }

  /// How moving, turning (about world z) and scaling the world move the landmark
  /// (core/gauge.hpp): the anchor like a point, the azimuth with the turn, and the inverse
  /// depth against the scale (the point's distance from the anchor grows with it).
  static Mat<6, kGaugeDim> gaugeDirections(const Vec<6>& l) {
    Mat<6, kGaugeDim> N = Mat<6, kGaugeDim>::Zero();
    N.topLeftCorner<3, 3>().setIdentity();
    N.block<3, 1>(0, 3) << -l.y(), l.x(), 0.0;  // e_z x anchor
    N(3, 3) = 1.0;                               // theta
    N.block<3, 1>(0, 4) = l.head<3>();
    N(5, 4) = -l[5];  // rho / (1 + s)
    return N;
  }

  /// a - b with the azimuth difference wrapped to (-pi, pi].
  static Vec<6> difference(const Vec<6>& a, const Vec<6>& b) {
    Vec<6> d = a - b;
    d[3] = wrapAngle(d[3]);
    return d;
  }
};

/// InverseDepth -> Point3 (independent of the robot): p = anchor + m(theta, phi) / rho.
template <typename Robot_>
struct InverseDepthToPoint3 {
  using Robot = Robot_;
  using From = InverseDepth;
  using To = Point3;
  static constexpr const char* kName = "InverseDepthToPoint3";

  /// The point anchor + m / rho, generic in the scalar for automatic differentiation. No
  /// checks: operator() validates l and returns this.
  template <typename T>
  Vec<3, T> convert(const Vec<Robot_::kDim, T>& /*robot*/, const Vec<6, T>& l) const {
    return InverseDepth::point<T>(l);
  }

  template <typename Tag = void>  // compiled only where called (core/deferred.hpp)
  Vec<3> operator()(const Vec<Robot_::kDim>& /*robot*/,
                    const Vec<6>& l,
                    JacobianArg<3, Robot_::kDim, Tag> J_to_x = {},
                    JacobianArg<3, 6, Tag> J_to_l = {}) const {
    if (!l.allFinite()) fail(ErrorCode::kNonFinite, "InverseDepthToPoint3: the landmark is not finite");
    const double rho = l[5];
    // rho <= 0 puts the point at infinity or behind its anchor: an estimate that has not
    // settled, whose Euclidean form would be meaningless (and singular at rho = 0).
    if (!(rho > 1e-12)) {
      std::ostringstream os;
      os << "InverseDepthToPoint3: inverse depth " << rho
         << " 1/m is not usable for a Euclidean point (it must be > 0: in front of the anchor)";
      fail(ErrorCode::kDegenerateGeometry, os.str());
    }
    if (J_to_x) (*J_to_x).setZero();
    if (J_to_l) {
      (*J_to_l).template leftCols<3>().setIdentity();
      (*J_to_l).template middleCols<2>(3) = InverseDepth::directionJacobian(l[3], l[4]) / rho;  // d m / d (theta, phi)
      (*J_to_l).col(5) = -InverseDepth::direction<double>(l[3], l[4]) / (rho * rho);
    }
    return InverseDepth::point<double>(l);
  }
};

/// Linearity index of an inverse-depth point seen from `camera_position`
/// (Civera, Davison, Montiel 2007): L = 4 sigma_d |cos a| / d with d the distance from the
/// camera to the point, a the angle between the rays from the anchor and from the camera,
/// sigma_d = sigma_rho / rho^2. Small L: the Euclidean parametrization is linear enough.
template <int = 0>  // compiled only where called (docs/build-time.md)
double inverseDepthLinearityIndex(const Vec<3>& camera_position, const Vec<6>& l, double sigma_rho) {
  if (!camera_position.allFinite() || !l.allFinite() || !std::isfinite(sigma_rho) || sigma_rho < 0.0)
    fail(ErrorCode::kNonFinite, "inverseDepthLinearityIndex: inputs must be finite, sigma_rho >= 0");
  if (!(l[5] > 0.0))
    fail(ErrorCode::kDegenerateGeometry, "inverseDepthLinearityIndex: inverse depth must be > 0");
  const Vec<3> m = InverseDepth::direction<double>(l[3], l[4]);
  const Vec<3> p = l.head<3>() + m / l[5];
  const Vec<3> h = p - camera_position;
  const double d = h.norm();
  if (!(d > 0.0)) fail(ErrorCode::kDegenerateGeometry, "inverseDepthLinearityIndex: camera at the point");
  const double cos_a = m.dot(h) / d;
  const double sigma_d = sigma_rho / (l[5] * l[5]);
  return 4.0 * sigma_d * std::abs(cos_a) / d;
}

}  // namespace sylva
