#pragma once
/// @file
/// `slam::MonocularTreeSlam`: one frame of monocular EKF-SLAM with tree landmarks, as
/// in the tree-width thesis (Sec. 3.5 and 4.1.3): the camera of `ConstantVelocity3D`, trees
/// first as inverse-depth points, then XYZ, then (with the tree-width sensor) XYZ-R. Its input
/// is the trunks seen in a frame (`TrunkSighting`: the tree's id and [u, v, w] pixels).
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
//   3. life cycle (`TreeLifeCycle`): inverse depth -> XYZ (and IDR -> XYZ-R) by the
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
// The member functions are in monocular_tree_slam_impl.hpp. Instantiating this filter with
// its four models takes minutes, so a program compiles them once: one .cpp includes the
// implementation and instantiates the class (`template class
// slam::BasicMonocularTreeSlam<ConstantVelocity3D>;`), and the others include
// this header only, with an `extern template` declaration. examples/forest_slam does so
// (library forest_slam_pipeline, used by forest_slam, tree_width_study, consistency and
// bench/forest_slam.cpp).
#include <algorithm>
#include <array>
#include <string>
#include <limits>
#include <cstddef>
#include <cmath>
#include <cstdint>
#include <type_traits>
#include <unordered_map>
#include <unordered_set>
#include <utility>
#include <vector>

#include "sylva/consistency/monte_carlo.hpp"
#include "sylva/core/error.hpp"
#include "sylva/core/types.hpp"
#include "sylva/filter/ekf.hpp"
#include "sylva/landmarks/inverse_depth.hpp"
#include "sylva/landmarks/inverse_depth_radius.hpp"
#include "sylva/landmarks/point3.hpp"
#include "sylva/landmarks/tree_xyzr.hpp"
#include "sylva/measurements/inverse_depth_initialization.hpp"
#include "sylva/measurements/inverse_depth_tree_width.hpp"
#include "sylva/measurements/pinhole_camera.hpp"
#include "sylva/measurements/pinhole_point.hpp"
#include "sylva/measurements/tree_width.hpp"
#include "sylva/motion/constant_velocity_3d.hpp"
#include "sylva/motion/on_manifold.hpp"
#include "sylva/noise/gaussian.hpp"
#include "sylva/slam/tree_life_cycle.hpp"

namespace sylva::slam {

/// One trunk seen in a frame: the tree it belongs to, and [u, v, w] in pixels (the centre of
/// the trunk base's image ellipse and its width).
struct TrunkSighting {
  Id id;
  Vec<3> z;
};

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

/// How the sightings of a frame find their trees.
enum class TrunkAssociation {
  kKnownIds,  ///< TrunkSighting::id names the tree (a tracker's ids, or a simulator's)
  /// The ids are ignored: each sighting pairs with the mapped tree nearest to it in NIS,
  /// measured through that tree's own model ([u, v] for points, [u, v, w] for trees with a
  /// radius) at the predicted state, points also on the width predicted from their last
  /// sighting (`TreeSlamOptions::width_appearance`), within a chi-square gate; each tree
  /// takes at most one sighting (greedy by NIS over its gate). A sighting that pairs with no
  /// tree starts one only when its NIS to every tree exceeds chi2(dim, new_tree_probability),
  /// or when no tree within that gate explains it at the continuity test's cost
  /// (`TreeSlamOptions::continuity_cost`); otherwise it is ambiguous and dropped.
  kNearestNeighbor,
};
inline const char* associationName(TrunkAssociation a) {
  return a == TrunkAssociation::kKnownIds ? "ids" : "nn";
}

/// The filter's settings. The noise defaults are the "gains" (thesis Sec. 4.2) selected for
/// the default forest with 1 px simulated noise: see docs/forest-slam-results.md for how.
struct TreeSlamOptions {
  PinholeCamera camera{500.0, 500.0, 320.0, 240.0, 640, 480};
  WidthPipeline pipeline = WidthPipeline::kAfterXyz;  ///< how the width w is used
  double pixel_sigma_px = 1.5;      ///< filter's measurement noise on u, v
  double width_sigma_px = 1.0;      ///< filter's measurement noise on w
  double linear_accel_sigma = 0.3;  ///< m/s^2, ConstantVelocity3D's noise
  double angular_accel_sigma = 0.3; ///< rad/s^2
  /// The frame of ConstantVelocity3D's linear velocity.
  ConstantVelocity3D::VelocityFrame velocity_frame = ConstantVelocity3D::VelocityFrame::kWorld;
  double initial_inverse_depth = 0.1;  ///< 1/m, Civera et al. 2008
  double inverse_depth_sigma = 0.5;    ///< 1/m
  double linearity_threshold = 0.1;    ///< inverse depth -> XYZ, IDR -> XYZ-R (Civera et al. 2007)
  double tree_position_sigma_m = 0.3;  ///< XYZ -> XYZ-R once the position's largest sigma is below
  double gate_probability = 0.99999;   ///< chi-square gate on each observation's NIS (0: off)
  /// The life cycle's rules judge a landmark's uncertainty given the camera's state
  /// (landmarkCovarianceGivenRobot) instead of its marginal: a consistent filter keeps
  /// the map's position and scale uncertain, which the marginal includes.
  bool conversion_given_camera = false;
  /// The camera's state on its manifold (OnManifold<ConstantVelocity3D>: covariance on
  /// the 12-dimensional tangent, updates composed through plus) instead of its quaternion's
  /// four entries. runForestSlam picks ManifoldTreeSlam for it.
  bool camera_on_manifold = false;
  /// The left inverse of the observability-constrained update (GaugeInverse).
  GaugeInverse gauge_inverse = GaugeInverse::kRobot;
  /// Where the filter takes its Jacobians. kIdeal (a diagnostic) needs the truth of every frame
  /// (`FrameTruth`).
  LinearizationPoint linearization = LinearizationPoint::kCurrentEstimate;
  /// A diagnostic: the (u, v) fused by the point models is the projection of the true base
  /// centre plus the frame's noise, instead of the centre of the base ellipse (which the
  /// point models do not predict: their model error). Needs `FrameTruth`.
  bool unbiased_point_uv = false;
  TrunkAssociation association = TrunkAssociation::kKnownIds;
  double association_gate_probability = 0.999;  ///< kNearestNeighbor: gate of a pairing
  double new_tree_probability = 0.99999;        ///< kNearestNeighbor: the new-tree test
  /// kNearestNeighbor: a landmark whose model predicts [u, v] only (inverse depth, XYZ) is
  /// also compared on the width w. Its width is predicted from its last sighting's,
  /// w_last * d_last / d (the trunk's image width goes as one over its depth d, each depth
  /// that of the landmark's estimate at the time), and the pairing and new-tree tests take
  /// the squared difference over its variance as a third degree of freedom. Off: [u, v] only.
  bool width_appearance = true;
  /// Relative standard deviation of that predicted width beyond the width noise: the error of
  /// the depth ratio d_last / d.
  double width_appearance_tolerance = 0.05;
  /// kNearestNeighbor, the continuity test: where a track may have changed trees unseen, a
  /// pairing compared on [u, v, w] must also cost less than this. The cost is
  /// NIS + log det(S R^-1), -2 log of the sighting's likelihood under the tree's prediction
  /// N(z_hat, S) over its peak under the measurement noise R alone: a tree whose prediction is
  /// wide (a young landmark, its depth still open) explains a sighting poorly wherever it
  /// falls, and the sighting starts a tree of its own. The test applies to a tree not sighted
  /// in the previous frame (it was hidden, or out of view), and to a sighting within
  /// `continuity_edge_margin_px` of the image's left or right edge (where trees come into view,
  /// possibly in front of the one a young landmark stands for). A tree sighted in the previous
  /// frame, away from the edges, continues its track on the gate alone. Infinity: off.
  /// Chosen on development forests (docs/slam.md, "The continuity test").
  double continuity_cost = 10.5;
  /// The continuity test's margin (pixels) at the image's left and right edges (< 0: none).
  double continuity_edge_margin_px = 15.0;
  /// kNearestNeighbor, loops: pairings that the continuity test refuses one at a time, with
  /// trees that have taken at least `loop_sightings` sightings, are judged together. After a
  /// loop the map has drifted, and the trees of the first lap seen again are displaced
  /// together: one at a time each looks like a takeover, but together they are consistent.
  /// The set is grown greedily in order of NIS, keeping a pairing while the joint NIS of the
  /// set (their innovations stacked, S with the cross-covariances between the trees' models)
  /// stays within the pairing gate at its degrees of freedom, and is taken when it holds at
  /// least `loop_pairings` pairings. 0: off. Chosen on development forests (docs/slam.md).
  int loop_pairings = 3;
  int loop_sightings = 30;
  /// Map management: a landmark that has taken fewer than `confirm_sightings` sightings is
  /// removed once `unconfirmed_after_frames` frames pass without one (0: never). Such a
  /// landmark's depth is barely constrained, and where the life cycle has made it Euclidean it
  /// sits in the map far from its tree.
  int unconfirmed_after_frames = 0;
  int confirm_sightings = 3;
  /// How each model's observations of a frame are fused: in one batched update per model
  /// (one linearization point, one pass over P), or one update per observation, each
  /// linearized after the previous one (`Fusion`, filter/ekf.hpp).
  Fusion fusion = Fusion::kBatched;
};

/// What a simulator knows about one frame, for the diagnostics of `TreeSlamOptions`
/// (ideal linearization, bias-free point measurements). The filter never sees it otherwise.
struct FrameTruth {
  Vec<13> camera_before;  ///< true camera state at the previous frame
  Vec<13> camera;         ///< true camera state at this frame
  /// The forest: trees[id] = [x, y, z, r], the base centre and radius of the tree with that id.
  const std::vector<Vec<4>>* trees = nullptr;
  /// unbiased_point_uv: the noise-free [u, v, w] of each sighting of the frame, in its order.
  const std::vector<Vec<3>>* noise_free = nullptr;
};

/// What one frame did.
struct FrameReport {
  int fused = 0;      ///< observations fused
  int fused_rows = 0; ///< their measurement rows (2 for [u, v], 3 for [u, v, w])
  int added = 0;      ///< new inverse-depth landmarks
  int to_xyz = 0;     ///< inverse depth -> XYZ conversions
  int to_tree = 0;    ///< XYZ -> XYZ-R or IDR -> XYZ-R conversions
  int rejected = 0;   ///< observations or conversions refused by the filter, a model or the gate
  int hypotheses = 0; ///< 1 when the frame was re-anchored on a one-point hypothesis
  int ambiguous = 0;  ///< kNearestNeighbor: sightings dropped, neither paired nor clearly new
  int removed = 0;    ///< landmarks removed unconfirmed (TreeSlamOptions::unconfirmed_after_frames)
  /// Per sighting, in the order given: the landmark it was taken as (its own id with known
  /// ids; the paired or new tree's id without), or -1 when it was dropped as ambiguous.
  std::vector<Id> landmark_of;
  /// NIS of the observations of mapped trees at the predicted state (before any is fused), by
  /// the landmark's parametrization [inverse depth, XYZ, XYZ-R, IDR] (2 dof for the point
  /// models, 3 for the width models; unpredictable observations left out).
  std::array<NisTally, 4> nis = emptyNisTallies();

  static std::array<NisTally, 4> emptyNisTallies() {
    return {NisTally(2), NisTally(2), NisTally(3), NisTally(3)};
  }
};

/// Where the frames' time went, when profiling is on (`MonocularTreeSlam::setProfile`):
/// seconds per phase, summed over the frames processed since.
struct FrameProfile {
  double predict_s = 0.0;        ///< camera prediction
  double gating_s = 0.0;         ///< NIS of every observation and the one-point hypotheses
                                 ///< (with the filter copies they need)
  double point_updates_s = 0.0;  ///< PinholePoint updates of inverse-depth and XYZ trees
  double width_updates_s = 0.0;  ///< TreeWidth and InverseDepthTreeWidth updates
  double reparametrize_s = 0.0;  ///< life cycle: inverse depth -> XYZ, XYZ (or IDR) -> XYZ-R
  double add_s = 0.0;            ///< trees seen for the first time
  int frames = 0;
  double total_s() const {
    return predict_s + gating_s + point_updates_s + width_updates_s + reparametrize_s + add_s;
  }
};

/// `Camera` is the filter's robot: ConstantVelocity3D (its quaternion's 4 entries in the
/// covariance, renormalized after each update) or OnManifold<ConstantVelocity3D> (the
/// covariance on the 12-dimensional tangent, the update composed through plus). The examples
/// compile each instantiation once, in a unit of its own
/// (examples/forest_slam/monocular_tree_slam_*.cpp).
template <typename Camera>
class BasicMonocularTreeSlam {
 public:
  using Filter = Ekf<Camera, InverseDepth, Point3, TreeXYZR,
                            InverseDepthRadius>;
  using IdPoint = PinholePoint<InverseDepth>;
  using XyzPoint = PinholePoint<Point3>;

  /// Starts at the camera state `x0` (velocity in the world frame, as the simulator gives it)
  /// with covariance `P0` of its 13 entries (carried to the tangent for a camera on its
  /// manifold).
  BasicMonocularTreeSlam(const TreeSlamOptions& options, const Vec<13>& x0, const Mat<13, 13>& P0);

  const Filter& filter() const { return ekf_; }
  const TreeSlamOptions& options() const { return options_; }

  /// One frame: predict over `dt` seconds, then the trees seen ([u, v, w] pixels each).
  /// `truth` is needed by the diagnostic options only (kInvalidArgument without it).
  FrameReport processFrame(double dt, const std::vector<TrunkSighting>& observations, const FrameTruth* truth = nullptr);

  /// Number of landmarks per parametrization: [inverse depth, XYZ, XYZ-R, IDR].
  std::array<int, 4> countByType() const;

  /// Adds the time of every following frame's phases to `*profile` (nullptr: off, the
  /// default). The profile is the caller's; a copy of this object shares it.
  void setProfile(FrameProfile* profile) { profile_ = profile; }
  /// Fuses the following frames' observations as `fusion` says (TreeSlamOptions::fusion).
  void setFusion(Fusion fusion) { options_.fusion = fusion; }

 private:
  struct Seen {
    Id id;
    Vec<3> z;   ///< [u, v, w] for the width models
    Vec<2> uv;  ///< [u, v] for the point models (z's unless `unbiased_point_uv`)
  };
  struct Candidate {
    Seen seen;
    double nis;
  };

  static constexpr double kUnpredictable = std::numeric_limits<double>::infinity();

  /// P0 of the camera's 13 entries as the filter's: carried to the tangent at x0 on a manifold.
  static typename Filter::RobotCovariance priorCovariance(const Vec<13>& x0, const Mat<13, 13>& P0) {
    if constexpr (Filter::kRobotOnManifold) {
      const Mat<12, 13> M = Camera::minusJacobian(x0);
      return M * P0 * M.transpose();
    } else {
      (void)x0;
      return P0;
    }
  }
  static constexpr int kMaxHypotheses = 5;

  /// NIS of observation `s` against `ekf`'s current estimate through the model of the
  /// landmark's parametrization (XYZ-R trees only with the width sensor); +inf when the model
  /// cannot predict it (e.g. behind the estimated camera).
  double nisOf(const Filter& ekf, const Seen& s) const;
  /// True when the observation passes the chi-square gate (always, for a predictable one,
  /// with the gate off).
  bool passes(const Filter& ekf, const Seen& s) const;
  bool withinGate(const Filter& ekf, Id id, double nis) const;
  /// Fuses observation `s` alone into `ekf` (throws like Ekf::update).
  void fuseOne(Filter& ekf, const Seen& s) const;
  /// The model that observes each parametrization, and its batch buffer.
  const IdPoint& modelFor(LandmarkTag<InverseDepth>) const { return id_point_; }
  const XyzPoint& modelFor(LandmarkTag<Point3>) const { return xyz_point_; }
  const TreeWidth& modelFor(LandmarkTag<TreeXYZR>) const { return tree_width_; }
  const InverseDepthTreeWidth& modelFor(LandmarkTag<InverseDepthRadius>) const { return idr_width_; }
  std::vector<Observation<IdPoint>>& batchOf(const IdPoint&) { return id_batch_; }
  std::vector<Observation<XyzPoint>>& batchOf(const XyzPoint&) { return xyz_batch_; }
  std::vector<Observation<TreeWidth>>& batchOf(const TreeWidth&) { return tree_batch_; }
  std::vector<Observation<InverseDepthTreeWidth>>& batchOf(const InverseDepthTreeWidth&) {
    return idr_batch_;
  }
  /// Calls f(model, z, noise) with the model of the parametrization of the landmark `s` sees
  /// (Ekf::visit), its part of the sighting ([u, v] or [u, v, w]) and its noise.
  template <typename F>
  decltype(auto) withModelOf(const Filter& ekf, const Seen& s, F&& f) const {
    return ekf.visit(s.id, [&](auto type) -> decltype(auto) {
      const auto& model = modelFor(type);
      if constexpr (std::decay_t<decltype(model)>::kDim == 2) {
        return f(model, s.uv, pixel_noise_);
      } else {
        return f(model, s.z, tree_noise_);
      }
    });
  }
  /// Gates and fuses the observations of mapped trees (step 2 at the top of this file).
  void fuseMapped(FrameReport& report);
  /// Fuses `observations` in one batched update per model.
  void fuseBatches(const std::vector<Seen>& observations, FrameReport& report);
  /// One batched update through `model`; one observation at a time if the batch is refused.
  template <typename Model>
  void fuse(const Model& model, const std::vector<Observation<Model>>& batch, FrameReport& report);

  /// Hands the true state of every landmark, in its parametrization, to the filter
  /// (LinearizationPoint::kIdeal).
  void setIdealLandmarks(const FrameTruth& truth);
  /// One nearest-neighbour association of a frame's sightings against one filter state.
  struct NearestPairing {
    std::vector<Id> tree;     ///< per sighting: the paired tree, -1 if none
    std::vector<char> clear;  ///< per sighting: NIS to every tree beyond the new-tree gate
  };
  NearestPairing pairNearest(const Filter& ekf, const std::vector<Seen>& seen) const;
  /// The loop test (TreeSlamOptions::loop_pairings): a tree's Jacobians and S, and a pairing
  /// the continuity test refused, with its innovation.
  struct LoopTree {
    Eigen::MatrixXd J_x, J_l;  ///< H's two blocks: the camera's and the landmark's
    int landmark_offset = 0;
    Eigen::MatrixXd S;         ///< H P H^T + R in the model's dimensions
    int dof = 0;               ///< 3 for a point landmark also compared on its predicted width
    double width_hat = 0.0, width_variance = 0.0;
  };
  struct LoopPairing {
    double nis;
    std::size_t sighting;
    std::size_t tree;
    Eigen::VectorXd nu;
  };
  /// The largest set of the refused pairings, grown in order of NIS, whose joint NIS stays
  /// within the pairing gate; empty when it holds fewer than loop_pairings.
  std::vector<LoopPairing> loopSet(const Filter& ekf, const std::vector<Seen>& seen, const std::vector<LoopTree>& trees,
                                   std::vector<LoopPairing> refused) const;
  /// Depth (camera-frame z, metres) of landmark `id`'s estimate in `ekf`'s camera; +inf for an
  /// inverse-depth landmark at or beyond infinity.
  static double depthOf(const Filter& ekf, Id id);
  /// kNearestNeighbor with `width_appearance`: each point landmark's last sighting width and
  /// its depth then (recordAppearance, at the end of each frame).
  struct Appearance {
    double width_px;
    double depth_m;
  };
  void recordAppearance();
  /// kNearestNeighbor: sets the id of every sighting in `seen` (a mapped tree, a new tree, or
  /// -1 for an ambiguous one) from the predicted state (see TrunkAssociation).
  void associate(std::vector<Seen>& seen, FrameReport& report);

  TreeSlamOptions options_;
  /// The true camera position when each tree was first seen: the true anchor of its inverse
  /// depth (kIdeal only).
  std::unordered_map<Id, Vec<3>> true_anchor_;
  Filter ekf_;
  IdPoint id_point_;
  XyzPoint xyz_point_;
  TreeWidth tree_width_;
  InverseDepthTreeWidth idr_width_;
  InverseDepthInitialization init_;
  InverseDepthRadiusInitialization idr_init_;
  TreeLifeCycle<> life_;
  Gaussian<6> accel_noise_;
  Gaussian<2> pixel_noise_;
  Gaussian<3> tree_noise_;
  std::vector<Observation<IdPoint>> id_batch_;
  std::vector<Observation<XyzPoint>> xyz_batch_;
  std::vector<Observation<TreeWidth>> tree_batch_;
  std::vector<Observation<InverseDepthTreeWidth>> idr_batch_;
  std::array<double, 4> gate_;  ///< chi-square gate by measurement dimension (2 and 3 used)
  std::vector<Seen> fresh_, mapped_, accepted_, refused_, second_chance_;
  std::vector<Candidate> candidates_;
  std::vector<Seen> sightings_;
  Id next_tree_id_ = 0;  ///< kNearestNeighbor: the next new tree's id (mapped ids skipped)
  std::unordered_map<Id, Appearance> appearance_;
  /// kNearestNeighbor: the trees sighted in the previous frame (the continuity test).
  std::unordered_set<Id> sighted_last_frame_;
  /// kNearestNeighbor: sightings each landmark has taken (TreeSlamOptions::loop_sightings).
  std::unordered_map<Id, int> sightings_taken_;
  /// Per landmark: sightings taken, and the frame of the last (unconfirmed_after_frames).
  struct Sighted {
    int count = 0;
    int last_frame = 0;
  };
  std::unordered_map<Id, Sighted> sighted_;
  int frame_index_ = 0;
  /// Removes the landmarks that stay unconfirmed (TreeSlamOptions::unconfirmed_after_frames).
  void removeUnconfirmed(FrameReport& report);
  FrameProfile* profile_ = nullptr;
};

/// The pipeline with the camera's quaternion in the state (the thesis's filter).
using MonocularTreeSlam = BasicMonocularTreeSlam<ConstantVelocity3D>;
/// The pipeline with the camera on its manifold (TreeSlamOptions::camera_on_manifold).
using ManifoldTreeSlam = BasicMonocularTreeSlam<OnManifold<ConstantVelocity3D>>;

}  // namespace sylva::slam
