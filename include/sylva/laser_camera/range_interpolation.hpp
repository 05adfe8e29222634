#pragma once
/// @file
/// `interpolateLaserRange`: the range along a bearing that falls between two laser beams,
/// from the two neighbouring readings (multisensor thesis, Amarasinghe 2008, Sec. 3.3.3,
/// Fig. 3.9, eq. 3.4), written for any angular resolution.
///
/// The two readings r_i, r_j at beam angles a_i, a_j (a_j != a_i) are the points
/// P_i = r_i [cos a_i, sin a_i] and P_j = r_j [cos a_j, sin a_j] of one surface. The surface
/// between them is taken as the straight line through P_i and P_j, and the range at bearing
/// phi is where the ray r [cos phi, sin phi] meets that line. With 2D cross products
/// (u x v = u_x v_y - u_y v_x) the line is {P : (P - P_i) x (P_j - P_i) = 0}, so
///
///   r(phi) = r_i r_j sin(a_j - a_i) / D,   D = r_i sin(phi - a_i) + r_j sin(a_j - phi)   (3.4')
///
/// which gives r_i at phi = a_i and r_j at phi = a_j, and is exact for a flat surface at any
/// resolution and any incidence. (The thesis prints eq. 3.4 for a 0.5 deg resolution with an
/// angle alpha of its Fig. 3.9; its printed form does not reduce to r_i at the beam angle, so
/// sylva uses the derivation above; see docs/models/laser-camera.md.)
///
/// Derivatives (for the covariance of the laser-camera sensor, eq. 3.5):
///
///   dr/dphi = -r^2 (r_i cos(phi - a_i) - r_j cos(a_j - phi)) / (r_i r_j sin(a_j - a_i))
///   dr/dr_i =  r_j^2 sin(a_j - a_i) sin(a_j - phi) / D^2
///   dr/dr_j =  r_i^2 sin(a_j - a_i) sin(phi - a_i) / D^2
///
/// The incidence angle is the angle between the ray and the surface normal,
/// cos(incidence) = |u(phi) x (P_j - P_i)| / |P_j - P_i| (0: head-on, pi/2: grazing).
///
/// phi may lie outside [a_i, a_j] (extrapolation along the surface); D must stay > 0.
///
/// Errors: non-finite input -> kNonFinite; a_i == a_j, r_i or r_j <= 0, or D <= 0 (the line
/// through the readings does not cross the ray in front of the sensor) -> kDegenerateGeometry.

#include <algorithm>
#include <cmath>
#include <sstream>

#include "sylva/core/error.hpp"
#include "sylva/core/types.hpp"

namespace sylva {

struct InterpolatedLaserRange {
  double range_m;
  Vec<3> J_r_input;  ///< d r / d [phi, r_i, r_j]
  double incidence_rad;
};

template <int = 0>  // compiled only where called (docs/build-time.md)
InterpolatedLaserRange interpolateLaserRange(double phi, double a_i, double r_i, double a_j, double r_j) {
  if (!std::isfinite(phi) || !std::isfinite(a_i) || !std::isfinite(r_i) || !std::isfinite(a_j) ||
      !std::isfinite(r_j))
    fail(ErrorCode::kNonFinite, "interpolateLaserRange: an angle or a reading is not finite");
  if (!(r_i > 0.0) || !(r_j > 0.0) || a_i == a_j) {
    std::ostringstream os;
    os << "interpolateLaserRange: need readings > 0 at distinct beam angles, got r_i = " << r_i
       << " m at " << a_i << " rad, r_j = " << r_j << " m at " << a_j << " rad";
    fail(ErrorCode::kDegenerateGeometry, os.str());
  }
  const double s = std::sin(a_j - a_i);
  const double si = std::sin(phi - a_i);
  const double sj = std::sin(a_j - phi);
  const double D = (r_i * si + r_j * sj) * (s > 0.0 ? 1.0 : -1.0);  // orientation-free
  const double N = r_i * r_j * std::abs(s);
  if (!(D > 1e-12 * (r_i + r_j)) || !(N > 0.0)) {
    std::ostringstream os;
    os << "interpolateLaserRange: the surface through the readings (" << r_i << " m, " << r_j
       << " m) does not cross the bearing " << phi << " rad in front of the sensor";
    fail(ErrorCode::kDegenerateGeometry, os.str());
  }
  const double sign = s > 0.0 ? 1.0 : -1.0;
  const double r = N / D;
  InterpolatedLaserRange out;
  out.range_m = r;
  const double D2 = D * D;
  out.J_r_input[0] = -N * sign * (r_i * std::cos(phi - a_i) - r_j * std::cos(a_j - phi)) / D2;
  out.J_r_input[1] = r_j * r_j * std::abs(s) * sj * sign / D2;
  out.J_r_input[2] = r_i * r_i * std::abs(s) * si * sign / D2;
  const Vec<2> Pi(r_i * std::cos(a_i), r_i * std::sin(a_i));
  const Vec<2> Pj(r_j * std::cos(a_j), r_j * std::sin(a_j));
  const Vec<2> d = Pj - Pi;
  const double length = d.norm();
  if (length > 0.0) {
    const double cross = std::cos(phi) * d.y() - std::sin(phi) * d.x();
    out.incidence_rad = std::acos(std::min(1.0, std::abs(cross) / length));
  } else {
    out.incidence_rad = 0.0;
  }
  return out;
}

}  // namespace sylva
