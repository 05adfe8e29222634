#pragma once
/// @file
/// `sim::TreeObserver`: which trees a camera sees and what it measures (tree-width thesis,
/// Sec. 4.1.1, Fig. 4.2). For each tree the true measurement [u, v, w] is `TreeWidth`'s
/// (centre of the base ellipse and its horizontal extent). A tree is visible when
///   - `TreeWidth` accepts the geometry (base in front of the camera, camera outside the trunk),
///   - its base centre is within `max_range_m` (horizontal distance) of the camera, and
///   - the whole base ellipse is inside the image: its horizontal extent u +- w / 2 and its
///     vertical extent (from the horizontal tangents of the dual conic D = K D_C K^T, the
///     roots of D_22 - 2 v D_23 + v^2 D_33 = 0; D_C as in tree_width.hpp) lie in
///     [0, width] x [0, height].
/// With occlusion on, a visible tree is dropped when a nearer one (smaller depth of the base
/// centre) overlaps it in u, [u - w/2, u + w/2] (the thesis' rule). Each kept tree's
/// measurement gets independent Gaussian noise (sigma_px on u and v, sigma_width_px on w),
/// drawn in order of tree id, so the same seed gives the same measurements bit for bit.

#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

#include "sylva/core/error.hpp"
#include "sylva/core/quaternion.hpp"
#include "sylva/core/types.hpp"
#include "sylva/motion/pose_3d.hpp"
#include "sylva/measurements/pinhole_camera.hpp"
#include "sylva/measurements/tree_width.hpp"
#include "sylva/sim/random.hpp"
#include "sylva/sim/tree_forest.hpp"

namespace sylva::sim {

struct TreeObservation {
  Id id;
  Vec<3> z;       ///< noisy [u, v, w] (pixels)
  Vec<3> z_true;  ///< noise-free [u, v, w]
  double depth_m; ///< depth of the base centre in the camera frame
};

struct ObserverOptions {
  double sigma_px = 1.0;        ///< noise on u and v
  double sigma_width_px = 1.0;  ///< noise on w
  bool occlusion = true;
  double max_range_m = 30.0;

  void validate() const {
    std::ostringstream os;
    if (!(std::isfinite(sigma_px) && sigma_px >= 0.0)) os << "sigma_px must be >= 0, got " << sigma_px;
    else if (!(std::isfinite(sigma_width_px) && sigma_width_px >= 0.0)) os << "sigma_width_px must be >= 0, got " << sigma_width_px;
    else if (!(max_range_m > 0.0)) os << "max_range_m must be > 0, got " << max_range_m;
    else return;
    fail(ErrorCode::kInvalidArgument, "ObserverOptions: " + os.str());
  }
};

class TreeObserver {
 public:
  TreeObserver(const PinholeCamera& camera, const ObserverOptions& options) : camera_(camera), model_(camera), options_(options) {
    options_.validate();
  }

  const PinholeCamera& camera() const { return camera_; }
  const ObserverOptions& options() const { return options_; }

  /// True [u, v, w] and whether the tree is visible (ignoring occlusion).
  bool visible(const Vec<13>& x, const Tree& tree, Vec<3>& z_true, double& depth) const {
    if ((tree.base.head<2>() - x.head<2>()).norm() > options_.max_range_m) return false;
    try {
      z_true = model_.predict<double>(Vec<7>(x.head<7>()), tree.xyzr());  // the pose [r_WC, q_WC]
    } catch (const Error&) {
      return false;
    }
    const Mat<3, 3> Rt = rotationMatrix<double>(Vec<4>(x.segment<4>(Pose3D::kQuaternion).normalized())).transpose();
    const Vec<3> n = Rt.col(2);
    const Vec<3> C = Rt * (tree.base - x.head<3>());
    depth = C.z();
    const double r2 = tree.radius_m * tree.radius_m;
    const Mat<3, 3> D_C = r2 * (Mat<3, 3>::Identity() - n * n.transpose()) - C * C.transpose();
    const Mat<3, 3> K = camera_.matrix();
    const Mat<3, 3> D = K * D_C * K.transpose();
    const double v_disc = D(1, 2) * D(1, 2) - D(1, 1) * D(2, 2);
    if (!(v_disc >= 0.0)) return false;
    const double v_half = std::sqrt(v_disc) / std::abs(D(2, 2));
    const double u_half = 0.5 * z_true[2];
    return z_true[0] - u_half >= 0.0 && z_true[0] + u_half <= camera_.width && z_true[1] - v_half >= 0.0 &&
           z_true[1] + v_half <= camera_.height;
  }

  /// The observations of `trees` from camera state `x`, sorted by id.
  std::vector<TreeObservation> observe(const Vec<13>& x, const std::vector<Tree>& trees, Rng& rng) const {
    std::vector<TreeObservation> seen;
    for (const Tree& tree : trees) {
      Vec<3> z_true;
      double depth = 0.0;
      if (visible(x, tree, z_true, depth)) seen.push_back(TreeObservation{tree.id, z_true, z_true, depth});
    }
    if (options_.occlusion) {
      std::vector<TreeObservation> kept;
      for (const TreeObservation& a : seen) {
        bool hidden = false;
        for (const TreeObservation& b : seen) {
          if (b.depth_m < a.depth_m && b.z_true[0] - 0.5 * b.z_true[2] < a.z_true[0] + 0.5 * a.z_true[2] &&
              a.z_true[0] - 0.5 * a.z_true[2] < b.z_true[0] + 0.5 * b.z_true[2]) {
            hidden = true;
            break;
          }
        }
        if (!hidden) kept.push_back(a);
      }
      seen.swap(kept);
    }
    for (TreeObservation& o : seen) {
      o.z[0] += rng.normal(0.0, options_.sigma_px);
      o.z[1] += rng.normal(0.0, options_.sigma_px);
      o.z[2] += rng.normal(0.0, options_.sigma_width_px);
    }
    return seen;
  }

 private:
  PinholeCamera camera_;
  TreeWidth model_;
  ObserverOptions options_;
};

}  // namespace sylva::sim
