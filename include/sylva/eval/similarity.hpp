#pragma once
/// @file
/// `eval::alignSimilarity`: the similarity transform (scale, rotation, translation) that best
/// maps estimated points onto true ones in the least-squares sense, for evaluating monocular
/// SLAM, whose map has no absolute scale, position or orientation (tree-width thesis,
/// Sec. 4.1.2, eq. 4.1-4.11: Procrustes analysis with the Kabsch rotation).
///
/// The thesis writes the transform as T_v(p) = s R (p + p0) (4.3); here it is
/// T(p) = s R p + t (t = s R p0), computed by `Eigen::umeyama` (Umeyama 1991), which solves
/// the same least-squares problem as eq. 4.5-4.11 including the reflection correction of
/// eq. 4.10-4.11 (the rotation always has det +1).

#include <cmath>
#include <sstream>
#include <type_traits>
#include <vector>

#include <Eigen/Geometry>
#include <Eigen/SVD>

#include "sylva/core/error.hpp"
#include "sylva/core/types.hpp"

namespace sylva::eval {

/// p -> scale * rotation * p + translation.
struct Similarity3 {
  double scale = 1.0;
  Mat<3, 3> rotation = Mat<3, 3>::Identity();
  Vec<3> translation = Vec<3>::Zero();

  Vec<3> operator()(const Vec<3>& p) const { return scale * rotation * p + translation; }
};

/// The similarity minimizing sum |T(estimated_i) - truth_i|^2 (eq. 4.4). Throws
/// kInvalidArgument for different sizes or fewer than 3 pairs, kNonFinite for NaN/Inf, and
/// kDegenerateGeometry when the true points are (nearly) collinear, where the rotation about
/// their line is undetermined.
///
/// `Scalar` is double for every caller (it is deduced, or defaults to double for braced
/// lists); it is a template parameter only so that the body is a template: a translation
/// unit that includes this header without calling the function then does not instantiate
/// Eigen's SVD and `umeyama` (5 s of g++ 12 for a file that includes only this header).
template <typename Scalar = double>
Similarity3 alignSimilarity(const std::vector<Eigen::Matrix<Scalar, 3, 1>>& estimated,
                            const std::vector<Eigen::Matrix<Scalar, 3, 1>>& truth) {
  static_assert(std::is_same_v<Scalar, double>, "alignSimilarity works on Vec<3> (double) points");
  using Points = Eigen::Matrix<Scalar, 3, Eigen::Dynamic>;
  if (estimated.size() != truth.size()) {
    std::ostringstream os;
    os << "alignSimilarity: " << estimated.size() << " estimated points but " << truth.size() << " true points";
    fail(ErrorCode::kInvalidArgument, os.str());
  }
  const int n = static_cast<int>(truth.size());
  if (n < 3) fail(ErrorCode::kInvalidArgument, "alignSimilarity: need at least 3 point pairs, got " + std::to_string(n));
  Points src(3, n);
  Points dst(3, n);
  for (int i = 0; i < n; ++i) {
    if (!estimated[i].allFinite() || !truth[i].allFinite())
      fail(ErrorCode::kNonFinite, "alignSimilarity: point pair " + std::to_string(i) + " is not finite");
    src.col(i) = estimated[i];
    dst.col(i) = truth[i];
  }
  const auto singular = [](const Points& m) {
    const Points centred = m.colwise() - m.rowwise().mean();
    return Eigen::JacobiSVD<Points>(centred).singularValues();
  };
  const Vec<3> s_truth = singular(dst);
  const Vec<3> s_est = singular(src);
  if (!(s_truth[1] > 1e-9 * s_truth[0]) || !(s_est[1] > 1e-9 * s_est[0]))
    fail(ErrorCode::kDegenerateGeometry,
         "alignSimilarity: the points are (nearly) collinear or coincident; the alignment is undetermined");
  const Eigen::Matrix<Scalar, 4, 4> T = Eigen::umeyama(src, dst, true);
  Similarity3 out;
  const Mat<3, 3> sR = T.template topLeftCorner<3, 3>();
  out.scale = std::cbrt(sR.determinant());
  out.rotation = sR / out.scale;
  out.translation = T.template topRightCorner<3, 1>();
  return out;
}

}  // namespace sylva::eval
