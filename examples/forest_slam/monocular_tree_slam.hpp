#pragma once
// MonocularTreeSlam: one frame of monocular EKF-SLAM with tree landmarks, as in the
// tree-width thesis (Sec. 3.5 and 4.1.3): the camera of `ConstantVelocity3D`, trees first
// as inverse-depth points, then XYZ, then (with the tree-width sensor) XYZ-R.
//
// Per frame:
//   1. predict the camera over dt (acceleration noise);
//   2. fuse the observations of mapped trees, one batched update per model:
//        InverseDepth  PinholePoint<InverseDepth>   z = [u, v]
//        Point3        PinholePoint<Point3>         z = [u, v]
//        TreeXYZR      TreeWidth                    z = [u, v, w]   (with the width sensor)
//      An observation whose prediction the model rejects (a point behind the estimated
//      camera, ...) or whose NIS exceeds the chi-square gate (`gate_probability`, 0.99999 by
//      default, 0 turns it off) is skipped and counted. If a batch is refused as a whole (its innovation
//      covariance not positive definite, a radius pushed <= 0) its observations are fused one
//      at a time and the refused ones are skipped and counted;
//   3. life cycle (`sylva::TreeLifeCycle`): inverse depth -> XYZ by the linearity index;
//      with the width sensor, XYZ trees observed in this frame -> XYZ-R once their position
//      is certain enough, with the radius from this frame's width (`InverseTreeWidth`);
//   4. trees seen for the first time are added as inverse-depth points
//      (`InverseDepthInitialization`, Civera et al. 2008).
//
// The (u, v) used for points is the centre of the trunk base's image ellipse, as in the
// thesis (eq. 3.7); it differs slightly from the projection of the base centre, a small
// model error shared by the runs with and without the width sensor.
//
// Used by examples/forest_slam/main.cpp and bench/forest_slam.cpp.

#include <array>
#include <cstddef>
#include <vector>

#include <sylva/core/error.hpp>
#include <sylva/consistency/chi_square.hpp>
#include <sylva/core/types.hpp>
#include <sylva/filter/ekf.hpp>
#include <sylva/filter/tree_life_cycle.hpp>
#include <sylva/landmarks/inverse_depth.hpp>
#include <sylva/landmarks/point3.hpp>
#include <sylva/landmarks/tree_xyzr.hpp>
#include <sylva/measurements/inverse_depth_initialization.hpp>
#include <sylva/measurements/pinhole_camera.hpp>
#include <sylva/measurements/pinhole_point.hpp>
#include <sylva/measurements/tree_width.hpp>
#include <sylva/motion/constant_velocity_3d.hpp>
#include <sylva/noise/gaussian.hpp>

namespace forest_slam {

using sylva::Id;
using sylva::Mat;
using sylva::Vec;

struct TreeSlamOptions {
  sylva::PinholeCamera camera{500.0, 500.0, 320.0, 240.0, 640, 480};
  bool use_width = true;            ///< the tree-width sensor (XYZ-R trees, TreeWidth updates)
  double pixel_sigma_px = 1.0;      ///< filter's measurement noise on u, v
  double width_sigma_px = 1.0;      ///< filter's measurement noise on w
  double linear_accel_sigma = 1.0;  ///< m/s^2, ConstantVelocity3D's noise
  double angular_accel_sigma = 1.0; ///< rad/s^2
  double initial_inverse_depth = 0.1;  ///< 1/m, Civera et al. 2008
  double inverse_depth_sigma = 0.5;    ///< 1/m
  double linearity_threshold = 0.1;    ///< inverse depth -> XYZ (Civera et al. 2007)
  double tree_position_sigma_m = 0.1;  ///< XYZ -> XYZ-R
  double gate_probability = 0.99999;   ///< chi-square gate on each observation's NIS (0: off)
};

/// What one frame did.
struct FrameReport {
  int fused = 0;      ///< observations fused
  int added = 0;      ///< new inverse-depth landmarks
  int to_xyz = 0;     ///< inverse depth -> XYZ conversions
  int to_tree = 0;    ///< XYZ -> XYZ-R conversions
  int rejected = 0;   ///< observations or conversions refused by the filter or a model
};

class MonocularTreeSlam {
 public:
  using Filter = sylva::Ekf<sylva::ConstantVelocity3D, sylva::InverseDepth, sylva::Point3, sylva::TreeXYZR>;
  using IdPoint = sylva::PinholePoint<sylva::InverseDepth>;
  using XyzPoint = sylva::PinholePoint<sylva::Point3>;

  MonocularTreeSlam(const TreeSlamOptions& options, const Vec<13>& x0, const Mat<13, 13>& P0)
      : options_(options),
        ekf_(x0, P0),
        id_point_(options.camera),
        xyz_point_(options.camera),
        tree_width_(options.camera),
        init_(options.camera, options.initial_inverse_depth, options.inverse_depth_sigma),
        life_(options.camera,
              sylva::LinearityIndexBelow{options.linearity_threshold},
              sylva::PositionSigmaBelow{options.tree_position_sigma_m}),
        accel_noise_(sylva::Gaussian<6>::sigmas(
            (Vec<6>() << Vec<3>::Constant(options.linear_accel_sigma), Vec<3>::Constant(options.angular_accel_sigma))
                .finished())),
        pixel_noise_(sylva::Gaussian<2>::sigmas(Vec<2>::Constant(options.pixel_sigma_px))),
        tree_noise_(sylva::Gaussian<3>::sigmas(Vec<3>(options.pixel_sigma_px, options.pixel_sigma_px, options.width_sigma_px))) {}

  const Filter& filter() const { return ekf_; }
  const TreeSlamOptions& options() const { return options_; }

  /// One frame: `observations` is a range of objects with `id` and `z` ([u, v, w] pixels).
  template <typename Observations>
  FrameReport processFrame(double dt, const Observations& observations) {
    FrameReport report;
    ekf_.predict(Vec<0>(), dt, accel_noise_);

    id_batch_.clear();
    xyz_batch_.clear();
    tree_batch_.clear();
    fresh_.clear();
    for (const auto& o : observations) {
      const Vec<3> z = o.z;
      if (!ekf_.contains(o.id)) {
        fresh_.push_back({o.id, z});
      } else if (ekf_.template holds<sylva::InverseDepth>(o.id)) {
        if (predictable(id_point_, o.id, Vec<2>(z.head<2>()), pixel_noise_)) id_batch_.push_back({o.id, z.head<2>(), pixel_noise_});
        else ++report.rejected;
      } else if (ekf_.template holds<sylva::Point3>(o.id)) {
        if (predictable(xyz_point_, o.id, Vec<2>(z.head<2>()), pixel_noise_)) xyz_batch_.push_back({o.id, z.head<2>(), pixel_noise_});
        else ++report.rejected;
        if (options_.use_width) seen_xyz_.push_back({o.id, z});
      } else {
        if (predictable(tree_width_, o.id, z, tree_noise_)) tree_batch_.push_back({o.id, z, tree_noise_});
        else ++report.rejected;
      }
    }
    fuse(id_point_, id_batch_, report);
    fuse(xyz_point_, xyz_batch_, report);
    fuse(tree_width_, tree_batch_, report);

    report.to_xyz = static_cast<int>(life_.convertInverseDepth(ekf_).size());
    for (const Seen& s : seen_xyz_) {
      try {
        if (life_.convertToTree(ekf_, s.id, s.z, tree_noise_)) ++report.to_tree;
      } catch (const sylva::Error&) {
        ++report.rejected;
      }
    }
    seen_xyz_.clear();

    for (const Seen& s : fresh_) {
      try {
        ekf_.add(s.id, init_, init_.measurement(s.z.head<2>()), init_.noise(pixel_noise_));
        ++report.added;
      } catch (const sylva::Error&) {
        ++report.rejected;
      }
    }
    return report;
  }

  /// Number of landmarks per parametrization: [inverse depth, XYZ, XYZ-R].
  std::array<int, 3> countByType() const {
    std::array<int, 3> n{0, 0, 0};
    for (const auto& s : ekf_.slots()) ++n[static_cast<std::size_t>(s.type_index)];
    return n;
  }

 private:
  struct Seen {
    Id id;
    Vec<3> z;
  };

  template <typename Model>
  bool predictable(const Model& model, Id id, const Vec<Model::kDim>& z, const sylva::Gaussian<Model::kDim>& noise) const {
    try {
      if (options_.gate_probability <= 0.0) {
        (void)ekf_.linearize(model, id);
        return true;
      }
      return ekf_.innovation(model, id, z, noise).nis() < sylva::chiSquareGate(Model::kDim, options_.gate_probability);
    } catch (const sylva::Error&) {
      return false;
    }
  }

  template <typename Model>
  void fuse(const Model& model, const std::vector<sylva::Observation<Model>>& batch, FrameReport& report) {
    if (batch.empty()) return;
    try {
      ekf_.update(model, batch);
      report.fused += static_cast<int>(batch.size());
      return;
    } catch (const sylva::Error&) {
      // The filter is unchanged; fall back to one observation at a time.
    }
    for (const auto& o : batch) {
      try {
        ekf_.update(model, o.id, o.z, o.noise);
        ++report.fused;
      } catch (const sylva::Error&) {
        ++report.rejected;
      }
    }
  }

  TreeSlamOptions options_;
  Filter ekf_;
  IdPoint id_point_;
  XyzPoint xyz_point_;
  sylva::TreeWidth tree_width_;
  sylva::InverseDepthInitialization init_;
  sylva::TreeLifeCycle<> life_;
  sylva::Gaussian<6> accel_noise_;
  sylva::Gaussian<2> pixel_noise_;
  sylva::Gaussian<3> tree_noise_;
  std::vector<sylva::Observation<IdPoint>> id_batch_;
  std::vector<sylva::Observation<XyzPoint>> xyz_batch_;
  std::vector<sylva::Observation<sylva::TreeWidth>> tree_batch_;
  std::vector<Seen> fresh_;
  std::vector<Seen> seen_xyz_;
};

}  // namespace forest_slam
