#pragma once
/// @file
/// `alignRigid2`: the rigid 2D transform (rotation and translation, no scale) that best maps
/// estimated points onto their reference in the least-squares sense,
///
///   argmin over (R, t) of sum_i |R estimated_i + t - truth_i|^2,
///
/// computed by `Eigen::umeyama` without scaling (Umeyama 1991). A 2D SLAM map is defined
/// only up to such a transform, so "aligned" errors (against ground truth landmarks, or a
/// trajectory against GPS fixes in another frame) are measured after applying it.
///
/// Errors: fewer than 2 pairs, lists of different lengths, or a non-finite point ->
/// kInvalidArgument / kNonFinite.

#include <cmath>
#include <string>
#include <type_traits>
#include <vector>

#include <Eigen/Geometry>

#include "sylva/core/angles.hpp"
#include "sylva/core/error.hpp"
#include "sylva/core/types.hpp"

namespace sylva::eval {

struct Rigid2 {
  Mat<2, 2> rotation = Mat<2, 2>::Identity();
  Vec<2> translation = Vec<2>::Zero();

  Vec<2> operator()(const Vec<2>& p) const { return rotation * p + translation; }
  double angle() const { return std::atan2(rotation(1, 0), rotation(0, 0)); }
  /// A pose [x, y, theta] moved by the transform.
  Vec<3> pose(const Vec<3>& x) const {
    Vec<3> out;
    out << (*this)(x.head<2>()), wrapAngle(x[2] + angle());
    return out;
  }
};

/// `Scalar` is double for every caller (deduced, or the default for braced lists); it makes
/// the body a template so that a translation unit that includes this header without calling
/// the function does not instantiate `Eigen::umeyama` (3.5 s of g++ 12 for a file that
/// includes only this header).
template <typename Scalar = double>
Rigid2 alignRigid2(const std::vector<Eigen::Matrix<Scalar, 2, 1>>& estimated,
                   const std::vector<Eigen::Matrix<Scalar, 2, 1>>& truth) {
  static_assert(std::is_same_v<Scalar, double>, "alignRigid2 works on Vec<2> (double) points");
  using Points = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
  if (estimated.size() != truth.size() || estimated.size() < 2)
    fail(ErrorCode::kInvalidArgument, "alignRigid2: need the same number (>= 2) of estimated and true points, got " +
                                          std::to_string(estimated.size()) + " and " + std::to_string(truth.size()));
  const auto n = static_cast<Eigen::Index>(truth.size());
  // Dynamic-size matrices: with Matrix2Xd, g++ 12 warns (-Wstringop-overread, a false
  // positive) inside Eigen::umeyama's fixed-size 2-vector code.
  Points src(2, n), dst(2, n);
  for (Eigen::Index i = 0; i < n; ++i) {
    src.col(i) = estimated[static_cast<std::size_t>(i)];
    dst.col(i) = truth[static_cast<std::size_t>(i)];
  }
  if (!src.allFinite() || !dst.allFinite()) fail(ErrorCode::kNonFinite, "alignRigid2: a point is not finite");
  const Points T = Eigen::umeyama(src, dst, false);  // 3 x 3 homogeneous
  Rigid2 out;
  out.rotation = T.topLeftCorner(2, 2);
  out.translation = T.topRightCorner(2, 1);
  return out;
}

}  // namespace sylva::eval
