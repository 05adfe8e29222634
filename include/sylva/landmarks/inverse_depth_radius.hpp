#pragma once
/// @file
/// `InverseDepthRadius` (IDR): a tree trunk as seen from the camera position that first
/// observed it, an `InverseDepth` point for the centre of the trunk's base circle extended
/// by the trunk's angular size, so that the radius is carried from the first image on:
///
///   l = [ x0, y0, z0, theta, phi, rho, kappa ]   (anchor (m), azimuth, elevation (rad),
///                                                 inverse depth (1/m), kappa (1))
///   c = anchor + m(theta, phi) / rho,   r = kappa / rho,
///   m = [cos(phi) cos(theta), cos(phi) sin(theta), sin(phi)]
///
/// with theta, phi, rho and m exactly as in `InverseDepth` (landmarks/inverse_depth.hpp:
/// world z up, theta the azimuth from world x, phi the elevation above the x-y plane) and
/// kappa = r rho the trunk radius divided by the depth 1/rho of the base centre from the
/// anchor. Seen from the anchor, the image of the base circle depends on the tree only
/// through m and kappa (scaling the scene about the camera changes no image), so a single
/// image fixes the ray and kappa but not the depth: as for inverse depth, rho starts from a
/// prior, while kappa starts from the measured width with a small variance (see
/// measurements/inverse_depth_tree_width.hpp). A trunk at infinity has rho = 0 and a finite
/// angular size kappa; the parametrization represents it, the conversion to XYZ-R cannot.
///
/// `normalize` wraps theta to (-pi, pi]. The domain is kappa > 0 (a trunk of positive
/// radius; `domainViolation`, as `TreeXYZR` does for r): the filter rejects an update that
/// would make kappa zero or negative (kOutOfDomain). rho < 0 is not outside the domain (a
/// far tree's estimate crosses zero while it settles, as for `InverseDepth`).
///
/// `InverseDepthRadiusToTree` is the conversion for `Ekf::reparametrize`, and
/// `inverseDepthRadiusLinearityIndex` the test of when to apply it: the linearity index of
/// the base centre (Civera, Davison, Montiel 2007), so a tree switches IDR -> XYZ-R by the
/// same rule as a point switches inverse depth -> XYZ.

#include <cmath>
#include <sstream>

#include "sylva/core/angles.hpp"
#include "sylva/core/error.hpp"
#include "sylva/core/jacobian_ref.hpp"
#include "sylva/core/types.hpp"
#include "sylva/landmarks/inverse_depth.hpp"
#include "sylva/landmarks/tree_xyzr.hpp"

namespace sylva {

struct InverseDepthRadius {
  static constexpr int kDim = 7;  ///< [x0_m, y0_m, z0_m, theta_rad, phi_rad, rho_per_m, kappa]
  static constexpr const char* kName = "InverseDepthRadius";
  using Mean = Vec<7>;

  /// Wraps the azimuth theta to (-pi, pi].
  static void normalize(Eigen::Ref<Vec<7>> l) { l[3] = wrapAngle(l[3]); }

  /// How moving, turning (about world z) and scaling the world move the tree
  /// (core/gauge.hpp): the base centre as an `InverseDepth` point; kappa = r rho is the
  /// trunk's angular size and does not change.
  static Mat<7, kGaugeDim> gaugeDirections(const Vec<7>& l) {
    Mat<7, kGaugeDim> N = Mat<7, kGaugeDim>::Zero();
    N.topRows<6>() = InverseDepth::gaugeDirections(l.head<6>());
    return N;
  }

  /// a - b with the azimuth difference wrapped to (-pi, pi].
  static Vec<7> difference(const Vec<7>& a, const Vec<7>& b) {
    Vec<7> d = a - b;
    d[3] = wrapAngle(d[3]);
    return d;
  }

  /// nullptr for kappa > 0, else the reason (see detail::HasDomain).
  static const char* domainViolation(const Vec<7>& l) {
    return l[6] > 0.0 ? nullptr
                      : "the trunk's angular size kappa = radius * inverse depth would become zero "
                        "or negative";
  }
};

/// InverseDepthRadius -> TreeXYZR (independent of the robot):
///
///   [c, r] = [anchor + m(theta, phi) / rho, kappa / rho],
///
/// J_to_x = 0; J_to_l (4x7): the base centre's rows are `InverseDepthToPoint3`'s (which
/// computes them) and 0 for kappa; the radius row is [0, 0, 0, 0, 0, -kappa / rho^2, 1 / rho].
template <typename Robot_>
struct InverseDepthRadiusToTree {
  using Robot = Robot_;
  using From = InverseDepthRadius;
  using To = TreeXYZR;
  static constexpr const char* kName = "InverseDepthRadiusToTree";

  /// The tree [anchor + m / rho, kappa / rho], generic in the scalar for automatic
  /// differentiation. No checks: operator() validates l and returns this.
  template <typename T>
  Vec<4, T> convert(const Vec<Robot_::kDim, T>& /*robot*/, const Vec<7, T>& l) const {
    Vec<4, T> tree;
    tree << InverseDepth::point<T>(Vec<6, T>(l.template head<6>())), l[6] / l[5];
    return tree;
  }

  template <typename Tag = void>  // compiled only where called (core/deferred.hpp)
  Vec<4> operator()(const Vec<Robot_::kDim>& /*robot*/,
                    const Vec<7>& l,
                    JacobianArg<4, Robot_::kDim, Tag> J_to_x = {},
                    JacobianArg<4, 7, Tag> J_to_l = {}) const {
    if (!l.allFinite())
      fail(ErrorCode::kNonFinite, "InverseDepthRadiusToTree: the landmark is not finite");
    const double rho = l[5];
    const double kappa = l[6];
    // rho <= 0 puts the tree at infinity or behind its anchor: an estimate that has not
    // settled, whose Euclidean form would be meaningless (and singular at rho = 0).
    if (!(rho > 1e-12)) {
      std::ostringstream os;
      os << "InverseDepthRadiusToTree: inverse depth " << rho
         << " 1/m is not usable for an XYZ-R tree (it must be > 0: in front of the anchor)";
      fail(ErrorCode::kDegenerateGeometry, os.str());
    }
    if (!(kappa > 0.0)) {
      std::ostringstream os;
      os << "InverseDepthRadiusToTree: kappa = radius * inverse depth " << kappa
         << " must be > 0 (a trunk of positive radius)";
      fail(ErrorCode::kDegenerateGeometry, os.str());
    }
    // The base centre is InverseDepthToPoint3 of the first six entries (valid: checked above).
    Mat<3, 6> J_c_l;
    const Vec<3> centre =
        InverseDepthToPoint3<Robot_>{}(Vec<Robot_::kDim>::Zero(), l.template head<6>(), {}, J_c_l);
    if (J_to_x) (*J_to_x).setZero();
    if (J_to_l) {
      auto J = *J_to_l;
      J.setZero();
      J.template topLeftCorner<3, 6>() = J_c_l;
      J(3, 5) = -kappa / (rho * rho);
      J(3, 6) = 1.0 / rho;
    }
    Vec<4> tree;
    tree << centre, kappa / rho;
    return tree;
  }
};

/// Linearity index of the base centre of an IDR tree seen from `camera_position`: exactly
/// `inverseDepthLinearityIndex` of its first six components (kappa does not enter), so a
/// tree is switched IDR -> XYZ-R by the same rule as a point inverse depth -> XYZ.
template <int = 0>  // compiled only where called (docs/build-time.md)
double inverseDepthRadiusLinearityIndex(const Vec<3>& camera_position,
                                               const Vec<7>& l,
                                               double sigma_rho) {
  return inverseDepthLinearityIndex(camera_position, Vec<6>(l.head<6>()), sigma_rho);
}

}  // namespace sylva
