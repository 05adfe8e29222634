#pragma once
/// @file
/// `TreeLifeCycle`: the life cycle of a tree landmark in monocular SLAM (tree-width thesis,
/// Sec. 3.5, Fig. 3.3): first seen as an inverse-depth point, converted to XYZ once its depth
/// is known well enough, and to XYZ-R once its position is, with the radius from the inverse
/// tree-width model (Sec. 3.3) and this frame's width measurement.
///
///   InverseDepth --[ToXyz rule]--> Point3 --[ToTree rule + width z]--> TreeXYZR
///   InverseDepthRadius --[ToXyz rule]--> TreeXYZR      (trees with the width from the first
///                                                      sighting, beyond the thesis)
///
/// The switching rules are policies: any type with
/// `template <class Filter> bool operator()(const Filter& ekf, Id id) const`. The defaults
/// are `LinearityIndexBelow{0.1}` (Civera, Davison, Montiel 2007) and
/// `PositionSigmaBelow{0.1 m}`. Write your own to switch on anything the filter exposes
/// (number of frames, parallax, a relative uncertainty, ...).
///
/// Works with any `Ekf<ConstantVelocity3D, ...>` that holds InverseDepth, Point3 and
/// TreeXYZR (and InverseDepthRadius for `convertInverseDepthRadius`). To run without the
/// tree-width sensor, simply never call `convertToTree`.

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include "sylva/core/error.hpp"
#include "sylva/core/types.hpp"
#include "sylva/landmarks/inverse_depth.hpp"
#include "sylva/landmarks/inverse_depth_radius.hpp"
#include "sylva/landmarks/point3.hpp"
#include "sylva/landmarks/tree_xyzr.hpp"
#include "sylva/measurements/inverse_tree_width.hpp"
#include "sylva/measurements/pinhole_camera.hpp"
#include "sylva/motion/constant_velocity_3d.hpp"
#include "sylva/noise/gaussian.hpp"

namespace sylva {

/// The covariance of landmark `id` given the robot's state: P_ll - P_lx P_xx^+ P_xl (the
/// pseudo-inverse through an LDLT, since the camera's covariance is singular along its
/// quaternion). It leaves out what the landmark's uncertainty shares with the robot's,
/// above all where the whole map is and how large it is (the gauge of monocular SLAM, which a
/// consistent filter keeps uncertain and no measurement or conversion is sensitive to).
template <typename Landmark, typename Filter>
Mat<Landmark::kDim, Landmark::kDim> landmarkCovarianceGivenRobot(const Filter& ekf, Id id) {
  const auto P_xl = ekf.template robotLandmarkCovariance<Landmark>(id);
  const Eigen::LDLT<Mat<Filter::kRobotDim, Filter::kRobotDim>> ldlt(ekf.robotCovariance());
  return ekf.template landmarkCovariance<Landmark>(id) - P_xl.transpose() * ldlt.solve(P_xl);
}

/// Inverse depth -> XYZ (and IDR -> XYZ-R) when the linearity index of the point (the base
/// centre) seen from the current camera position is below `threshold` (0.1 is the usual
/// value). A point with rho <= 0 (at or beyond infinity) is not ready.
struct LinearityIndexBelow {
  double threshold = 0.1;
  /// Take sigma_rho from the landmark's covariance given the robot's state
  /// (landmarkCovarianceGivenRobot) rather than from its marginal.
  bool given_robot = false;

  template <typename Filter>
  bool operator()(const Filter& ekf, Id id) const {
    if constexpr (Filter::template kHolds<InverseDepthRadius>) {
      if (ekf.template holds<InverseDepthRadius>(id)) return ready<InverseDepthRadius>(ekf, id);
    }
    return ready<InverseDepth>(ekf, id);
  }

 private:
  // Landmark: InverseDepth, or InverseDepthRadius, whose first six entries are one.
  template <typename Landmark, typename Filter>
  bool ready(const Filter& ekf, Id id) const {
    const Vec<6> l = ekf.template landmarkMean<Landmark>(id).template head<6>();
    if (!(l[5] > 0.0)) return false;
    const double var_rho = given_robot ? landmarkCovarianceGivenRobot<Landmark>(ekf, id)(5, 5)
                                       : ekf.template landmarkCovariance<Landmark>(id)(5, 5);
    const double sigma_rho = std::sqrt(std::max(0.0, var_rho));
    return inverseDepthLinearityIndex(ekf.robotMean().template head<3>(), l, sigma_rho) < threshold;
  }
};

/// XYZ -> XYZ-R when the largest standard deviation of the position (the square root of the
/// largest eigenvalue of its 3x3 covariance) is below `max_sigma_m`.
struct PositionSigmaBelow {
  double max_sigma_m = 0.1;
  /// Judge the position's covariance given the robot's state (landmarkCovarianceGivenRobot)
  /// rather than its marginal.
  bool given_robot = false;

  template <typename Filter>
  bool operator()(const Filter& ekf, Id id) const {
    const Mat<3, 3> P = given_robot ? landmarkCovarianceGivenRobot<Point3>(ekf, id)
                                    : Mat<3, 3>(ekf.template landmarkCovariance<Point3>(id));
    const Eigen::SelfAdjointEigenSolver<Mat<3, 3>> eig(P, Eigen::EigenvaluesOnly);
    return eig.eigenvalues().maxCoeff() < max_sigma_m * max_sigma_m;
  }
};

template <typename ToXyz = LinearityIndexBelow, typename ToTree = PositionSigmaBelow>
class TreeLifeCycle {
 public:
  /// `camera`: the intrinsics of the tree-width sensor (for the inverse model).
  explicit TreeLifeCycle(const PinholeCamera& camera, ToXyz to_xyz = {}, ToTree to_tree = {})
      : inverse_(camera), to_xyz_(to_xyz), to_tree_(to_tree) {}

  const ToXyz& toXyzRule() const { return to_xyz_; }
  const ToTree& toTreeRule() const { return to_tree_; }

  /// Converts every inverse-depth landmark whose rule fires to XYZ (first arrow of Fig. 3.3,
  /// covariance through InverseDepthToPoint3's Jacobian). Returns the converted ids.
  template <typename Filter>
  std::vector<Id> convertInverseDepth(Filter& ekf) const {
    return convertWhereRuleFires<InverseDepth>(ekf, InverseDepthToPoint3<Pose3D>{});
  }

  /// Converts every InverseDepthRadius tree whose ToXyz rule fires straight to XYZ-R (its
  /// radius is already estimated; covariance through InverseDepthRadiusToTree's Jacobian).
  /// Returns the converted ids.
  template <typename Filter>
  std::vector<Id> convertInverseDepthRadius(Filter& ekf) const {
    return convertWhereRuleFires<InverseDepthRadius>(ekf, InverseDepthRadiusToTree<Pose3D>{});
  }

  /// Converts XYZ landmark `id`, observed in this frame with the tree-width measurement `z`
  /// ([u, v, w], noise `noise`), to XYZ-R if its rule fires (second arrow of Fig. 3.3).
  /// Returns true when it converted, false when the landmark is not (or no longer) XYZ or
  /// its rule does not fire. Throws like `Ekf::reparametrize` (the filter is then
  /// unchanged): unknown id, non-finite z, geometry in which the width gives no radius.
  template <typename Filter>
  bool convertToTree(Filter& ekf, Id id, const Vec<3>& z, const Gaussian<3>& noise) const {
    if (!ekf.contains(id))
      fail(ErrorCode::kUnknownId, "TreeLifeCycle: no landmark with id " + std::to_string(id));
    if (!ekf.template holds<Point3>(id) || !to_tree_(ekf, id)) return false;
    ekf.reparametrize(id, inverse_, z, noise);
    return true;
  }

 private:
  /// Reparametrizes, through `conversion`, every landmark of type `From` whose ToXyz rule
  /// fires; the rule is asked for every landmark before any is converted.
  template <typename From, typename Filter, typename Conversion>
  std::vector<Id> convertWhereRuleFires(Filter& ekf, const Conversion& conversion) const {
    std::vector<Id> ready;
    for (const auto& slot : ekf.slots()) {
      if (ekf.template holds<From>(slot.id) && to_xyz_(ekf, slot.id)) ready.push_back(slot.id);
    }
    for (Id id : ready) ekf.reparametrize(id, conversion);
    return ready;
  }

  InverseTreeWidth inverse_;
  ToXyz to_xyz_;
  ToTree to_tree_;
};

}  // namespace sylva
