#pragma once
// MonocularTreeSlam: one frame of monocular EKF-SLAM with tree landmarks, as in the
// tree-width thesis (Sec. 3.5 and 4.1.3): the camera of `ConstantVelocity3D`, trees first
// as inverse-depth points, then XYZ, then (with the tree-width sensor) XYZ-R.
//
// Three pipelines (`WidthPipeline`) share everything but the use of the width w:
//   kNone            no width: InverseDepth -> XYZ, (u, v) only;
//   kAfterXyz        the thesis: InverseDepth -> XYZ -> XYZ-R, w used once a tree is XYZ-R;
//   kFromFirstSight  beyond the thesis (its Ch. 5): trees start as InverseDepthRadius (IDR),
//                    fused with [u, v, w] from the first frame (InverseDepthTreeWidth), and
//                    become XYZ-R by the same linearity rule as inverse depth -> XYZ.
//
// Per frame:
//   1. predict the camera over dt (acceleration noise);
//   2. fuse the observations of mapped trees, one batched update per model:
//        InverseDepth  PinholePoint<InverseDepth>   z = [u, v]
//        Point3        PinholePoint<Point3>         z = [u, v]
//        TreeXYZR      TreeWidth                    z = [u, v, w]   (with the width sensor)
//        InverseDepthRadius  InverseDepthTreeWidth    z = [u, v, w]   (kFromFirstSight)
//      Each observation is gated on its NIS at the predicted state (chi-square gate of
//      probability `gate_probability`, 0.99999 by default; 0 turns it off). If fewer than half
//      pass, the prediction is the suspect (a turn the constant-velocity model did not expect):
//      the best few observations are tried alone on a copy of the filter and the one under
//      which most others pass is fused first (one-point hypotheses, after Civera et al. 2010).
//      Refused observations get a second chance against the updated estimate. A batch the
//      filter refuses as a whole is fused one observation at a time;
//   3. life cycle (`sylva::TreeLifeCycle`): inverse depth -> XYZ (and IDR -> XYZ-R) by the
//      linearity index;
//      with the width sensor, XYZ trees observed in this frame -> XYZ-R once their position
//      is certain enough, with the radius from this frame's width (`InverseTreeWidth`);
//   4. trees seen for the first time are added as inverse-depth points
//      (`InverseDepthInitialization`, Civera et al. 2008), or as IDR trees
//      (`InverseDepthRadiusInitialization`) with kFromFirstSight.
//
// The (u, v) used for points is the centre of the trunk base's image ellipse, as in the
// thesis (eq. 3.7); it differs slightly from the projection of the base centre, a small
// model error shared by the runs with and without the width sensor.
//
// Used by examples/forest_slam/main.cpp and bench/forest_slam.cpp.

#include <algorithm>
#include <array>
#include <limits>
#include <cstddef>
#include <cmath>
#include <cstdint>
#include <vector>

#include <sylva/core/error.hpp>
#include <sylva/consistency/chi_square.hpp>
#include <sylva/core/types.hpp>
#include <sylva/filter/ekf.hpp>
#include <sylva/filter/tree_life_cycle.hpp>
#include <sylva/landmarks/inverse_depth.hpp>
#include <sylva/landmarks/inverse_depth_radius.hpp>
#include <sylva/landmarks/point3.hpp>
#include <sylva/landmarks/tree_xyzr.hpp>
#include <sylva/measurements/inverse_depth_initialization.hpp>
#include <sylva/measurements/inverse_depth_tree_width.hpp>
#include <sylva/measurements/pinhole_camera.hpp>
#include <sylva/measurements/pinhole_point.hpp>
#include <sylva/measurements/tree_width.hpp>
#include <sylva/motion/constant_velocity_3d.hpp>
#include <sylva/noise/gaussian.hpp>

namespace forest_slam {

using sylva::Id;
using sylva::Mat;
using sylva::Vec;

/// The default forest. Seed 26 is the representative one of seeds 1..30 under the default
/// settings: the median of the trajectory error of the run WITHOUT the width sensor, so the
/// choice says nothing about the sensor (scripts/forest_slam_seeds.py finds it and
/// docs/forest-slam-results.md lists all 30 seeds).
constexpr std::uint64_t kDefaultForestSeed = 26;

/// The camera's prior: the first true camera state defines the map frame (pose known
/// exactly), its velocity is known to 0.1 m/s and its angular velocity to 0.05 rad/s.
inline Mat<13, 13> initialCameraCovariance() {
  Mat<13, 13> P0 = Mat<13, 13>::Zero();
  P0.diagonal().segment<7>(0).setConstant(1e-8);
  P0.diagonal().segment<3>(7).setConstant(0.1 * 0.1);
  P0.diagonal().segment<3>(10).setConstant(0.05 * 0.05);
  return P0;
}

/// How the tree-width measurement w is used (see the top of this file).
enum class WidthPipeline { kNone, kAfterXyz, kFromFirstSight };

/// "none", "after_xyz", "first_sight".
inline const char* pipelineName(WidthPipeline p) {
  switch (p) {
    case WidthPipeline::kNone: return "none";
    case WidthPipeline::kAfterXyz: return "after_xyz";
    case WidthPipeline::kFromFirstSight: return "first_sight";
  }
  return "?";
}

/// The filter's settings. The noise defaults are the "gains" (thesis Sec. 4.2) selected for
/// the default forest with 1 px simulated noise: see docs/forest-slam-results.md for how.
struct TreeSlamOptions {
  sylva::PinholeCamera camera{500.0, 500.0, 320.0, 240.0, 640, 480};
  WidthPipeline pipeline = WidthPipeline::kAfterXyz;  ///< how the width w is used
  double pixel_sigma_px = 1.5;      ///< filter's measurement noise on u, v
  double width_sigma_px = 1.0;      ///< filter's measurement noise on w
  double linear_accel_sigma = 0.3;  ///< m/s^2, ConstantVelocity3D's noise
  double angular_accel_sigma = 0.3; ///< rad/s^2
  double initial_inverse_depth = 0.1;  ///< 1/m, Civera et al. 2008
  double inverse_depth_sigma = 0.5;    ///< 1/m
  double linearity_threshold = 0.1;    ///< inverse depth -> XYZ, IDR -> XYZ-R (Civera et al. 2007)
  double tree_position_sigma_m = 0.3;  ///< XYZ -> XYZ-R once the position's largest sigma is below
  double gate_probability = 0.99999;   ///< chi-square gate on each observation's NIS (0: off)
};

/// What one frame did.
struct FrameReport {
  int fused = 0;      ///< observations fused
  int added = 0;      ///< new inverse-depth landmarks
  int to_xyz = 0;     ///< inverse depth -> XYZ conversions
  int to_tree = 0;    ///< XYZ -> XYZ-R or IDR -> XYZ-R conversions
  int rejected = 0;   ///< observations or conversions refused by the filter, a model or the gate
  int hypotheses = 0; ///< 1 when the frame was re-anchored on a one-point hypothesis
};

class MonocularTreeSlam {
 public:
  using Filter = sylva::Ekf<sylva::ConstantVelocity3D, sylva::InverseDepth, sylva::Point3, sylva::TreeXYZR,
                            sylva::InverseDepthRadius>;
  using IdPoint = sylva::PinholePoint<sylva::InverseDepth>;
  using XyzPoint = sylva::PinholePoint<sylva::Point3>;

  MonocularTreeSlam(const TreeSlamOptions& options, const Vec<13>& x0, const Mat<13, 13>& P0)
      : options_(options),
        ekf_(x0, P0),
        id_point_(options.camera),
        xyz_point_(options.camera),
        tree_width_(options.camera),
        idr_width_(options.camera),
        init_(options.camera, options.initial_inverse_depth, options.inverse_depth_sigma),
        idr_init_(options.camera, options.initial_inverse_depth, options.inverse_depth_sigma),
        life_(options.camera,
              sylva::LinearityIndexBelow{options.linearity_threshold},
              sylva::PositionSigmaBelow{options.tree_position_sigma_m}),
        accel_noise_(sylva::Gaussian<6>::sigmas(
            (Vec<6>() << Vec<3>::Constant(options.linear_accel_sigma), Vec<3>::Constant(options.angular_accel_sigma))
                .finished())),
        pixel_noise_(sylva::Gaussian<2>::sigmas(Vec<2>::Constant(options.pixel_sigma_px))),
        tree_noise_(sylva::Gaussian<3>::sigmas(Vec<3>(options.pixel_sigma_px, options.pixel_sigma_px, options.width_sigma_px))) {
    gate_.fill(std::numeric_limits<double>::infinity());
    if (options.gate_probability > 0.0)
      for (int dim = 1; dim <= 3; ++dim) gate_[dim] = sylva::chiSquareGate(dim, options.gate_probability);
  }

  const Filter& filter() const { return ekf_; }
  const TreeSlamOptions& options() const { return options_; }

  /// One frame: `observations` is a range of objects with `id` and `z` ([u, v, w] pixels).
  template <typename Observations>
  FrameReport processFrame(double dt, const Observations& observations) {
    FrameReport report;
    ekf_.predict(Vec<0>(), dt, accel_noise_);

    fresh_.clear();
    mapped_.clear();
    for (const auto& o : observations) {
      const Vec<3> z = o.z;
      (ekf_.contains(o.id) ? mapped_ : fresh_).push_back({o.id, z});
    }
    fuseMapped(report);

    report.to_xyz = static_cast<int>(life_.convertInverseDepth(ekf_).size());
    if (options_.pipeline == WidthPipeline::kFromFirstSight)
      report.to_tree += static_cast<int>(life_.convertInverseDepthRadius(ekf_).size());
    if (options_.pipeline == WidthPipeline::kAfterXyz) {
      for (const Seen& s : mapped_) {
        if (!ekf_.template holds<sylva::Point3>(s.id)) continue;
        try {
          if (life_.convertToTree(ekf_, s.id, s.z, tree_noise_)) ++report.to_tree;
        } catch (const sylva::Error&) {
          ++report.rejected;
        }
      }
    }

    for (const Seen& s : fresh_) {
      try {
        if (options_.pipeline == WidthPipeline::kFromFirstSight)
          ekf_.add(s.id, idr_init_, idr_init_.measurement(s.z), idr_init_.noise(tree_noise_));
        else
          ekf_.add(s.id, init_, init_.measurement(s.z.head<2>()), init_.noise(pixel_noise_));
        ++report.added;
      } catch (const sylva::Error&) {
        ++report.rejected;
      }
    }
    return report;
  }

  /// Number of landmarks per parametrization: [inverse depth, XYZ, XYZ-R, IDR].
  std::array<int, 4> countByType() const {
    std::array<int, 4> n{0, 0, 0, 0};
    for (const auto& s : ekf_.slots()) ++n[static_cast<std::size_t>(s.type_index)];
    return n;
  }

 private:
  struct Seen {
    Id id;
    Vec<3> z;
  };
  struct Candidate {
    Seen seen;
    double nis;
  };

  static constexpr double kUnpredictable = std::numeric_limits<double>::infinity();
  static constexpr int kMaxHypotheses = 5;

  /// NIS of observation `s` against `ekf`'s current estimate through the model of the
  /// landmark's parametrization (XYZ-R trees only with the width sensor); +inf when the model
  /// cannot predict it (e.g. behind the estimated camera).
  double nisOf(const Filter& ekf, const Seen& s) const {
    try {
      if (ekf.template holds<sylva::InverseDepth>(s.id))
        return ekf.innovation(id_point_, s.id, Vec<2>(s.z.head<2>()), pixel_noise_).nis();
      if (ekf.template holds<sylva::Point3>(s.id))
        return ekf.innovation(xyz_point_, s.id, Vec<2>(s.z.head<2>()), pixel_noise_).nis();
      if (ekf.template holds<sylva::InverseDepthRadius>(s.id))
        return ekf.innovation(idr_width_, s.id, s.z, tree_noise_).nis();
      return ekf.innovation(tree_width_, s.id, s.z, tree_noise_).nis();
    } catch (const sylva::Error&) {
      return kUnpredictable;
    }
  }

  /// True when the observation passes the chi-square gate (always, for a predictable one, with
  /// the gate off).
  bool passes(const Filter& ekf, const Seen& s) const { return withinGate(ekf, s.id, nisOf(ekf, s)); }

  bool withinGate(const Filter& ekf, Id id, double nis) const {
    if (!(nis < kUnpredictable)) return false;
    const bool with_width = ekf.template holds<sylva::TreeXYZR>(id) || ekf.template holds<sylva::InverseDepthRadius>(id);
    return nis < gate_[with_width ? 3 : 2];
  }

  /// Fuses observation `s` alone into `ekf` (throws like Ekf::update).
  void fuseOne(Filter& ekf, const Seen& s) const {
    if (ekf.template holds<sylva::InverseDepth>(s.id))
      ekf.update(id_point_, s.id, Vec<2>(s.z.head<2>()), pixel_noise_);
    else if (ekf.template holds<sylva::Point3>(s.id))
      ekf.update(xyz_point_, s.id, Vec<2>(s.z.head<2>()), pixel_noise_);
    else if (ekf.template holds<sylva::InverseDepthRadius>(s.id))
      ekf.update(idr_width_, s.id, s.z, tree_noise_);
    else
      ekf.update(tree_width_, s.id, s.z, tree_noise_);
  }

  /// Fuses the observations of mapped trees. Each is gated on its NIS at the predicted
  /// state. When fewer than half of the predictable ones pass, the prediction itself is
  /// suspect (a turn the motion model did not expect), not the measurements: one-point
  /// hypotheses as in Civera et al. 2010 ("1-point RANSAC for EKF filtering") try the best
  /// few observations alone on a copy of the filter and keep the one under which most of the
  /// others pass the gate, if it explains more of them than the prediction did. The passing
  /// observations are then fused in one batch per model; those refused get a second chance
  /// against the updated estimate.
  void fuseMapped(FrameReport& report) {
    candidates_.clear();
    for (const Seen& s : mapped_) {
      const double nis = nisOf(ekf_, s);
      if (nis < kUnpredictable) candidates_.push_back({s, nis});
      else ++report.rejected;
    }
    if (candidates_.empty()) return;
    accepted_.clear();
    refused_.clear();
    for (const Candidate& c : candidates_) (withinGate(ekf_, c.seen.id, c.nis) ? accepted_ : refused_).push_back(c.seen);

    const bool gated = options_.gate_probability > 0.0;
    if (gated && candidates_.size() >= 2 && 2 * accepted_.size() < candidates_.size()) {
      std::sort(candidates_.begin(), candidates_.end(),
                [](const Candidate& a, const Candidate& b) { return a.nis < b.nis; });
      int best = -1;
      std::size_t best_support = accepted_.size();
      const int tries = std::min<int>(kMaxHypotheses, static_cast<int>(candidates_.size()));
      for (int h = 0; h < tries; ++h) {
        Filter trial = ekf_;
        try {
          fuseOne(trial, candidates_[h].seen);
        } catch (const sylva::Error&) {
          continue;
        }
        std::size_t support = 0;
        for (int j = 0; j < static_cast<int>(candidates_.size()); ++j)
          if (j != h && passes(trial, candidates_[j].seen)) ++support;
        if (support > best_support) {
          best_support = support;
          best = h;
        }
      }
      if (best >= 0) {
        const Seen chosen = candidates_[best].seen;
        fuseOne(ekf_, chosen);  // succeeded on the copy, so it succeeds here
        ++report.fused;
        ++report.hypotheses;
        accepted_.clear();
        refused_.clear();
        for (const Candidate& c : candidates_) {
          if (c.seen.id == chosen.id) continue;
          (passes(ekf_, c.seen) ? accepted_ : refused_).push_back(c.seen);
        }
      }
    }

    fuseBatches(accepted_, report);
    if (refused_.empty()) return;
    second_chance_.clear();
    for (const Seen& s : refused_) {
      if (passes(ekf_, s)) second_chance_.push_back(s);
      else ++report.rejected;
    }
    fuseBatches(second_chance_, report);
  }

  /// Fuses `observations` in one batched update per model.
  void fuseBatches(const std::vector<Seen>& observations, FrameReport& report) {
    id_batch_.clear();
    xyz_batch_.clear();
    tree_batch_.clear();
    idr_batch_.clear();
    for (const Seen& s : observations) {
      if (ekf_.template holds<sylva::InverseDepth>(s.id))
        id_batch_.push_back({s.id, s.z.head<2>(), pixel_noise_});
      else if (ekf_.template holds<sylva::Point3>(s.id))
        xyz_batch_.push_back({s.id, s.z.head<2>(), pixel_noise_});
      else if (ekf_.template holds<sylva::InverseDepthRadius>(s.id))
        idr_batch_.push_back({s.id, s.z, tree_noise_});
      else
        tree_batch_.push_back({s.id, s.z, tree_noise_});
    }
    fuse(id_point_, id_batch_, report);
    fuse(xyz_point_, xyz_batch_, report);
    fuse(tree_width_, tree_batch_, report);
    fuse(idr_width_, idr_batch_, report);
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
  sylva::InverseDepthTreeWidth idr_width_;
  sylva::InverseDepthInitialization init_;
  sylva::InverseDepthRadiusInitialization idr_init_;
  sylva::TreeLifeCycle<> life_;
  sylva::Gaussian<6> accel_noise_;
  sylva::Gaussian<2> pixel_noise_;
  sylva::Gaussian<3> tree_noise_;
  std::vector<sylva::Observation<IdPoint>> id_batch_;
  std::vector<sylva::Observation<XyzPoint>> xyz_batch_;
  std::vector<sylva::Observation<sylva::TreeWidth>> tree_batch_;
  std::vector<sylva::Observation<sylva::InverseDepthTreeWidth>> idr_batch_;
  std::array<double, 4> gate_;  ///< chi-square gate by measurement dimension (2 and 3 used)
  std::vector<Seen> fresh_, mapped_, accepted_, refused_, second_chance_;
  std::vector<Candidate> candidates_;
};

}  // namespace forest_slam
