#pragma once
// runForestSlam: one monocular tree-SLAM run over a simulated forest scenario and its
// evaluation (tree-width thesis, Sec. 4.1.2-4.2). Shared by examples/forest_slam (one run
// per pipeline, with pictures) and examples/tree_width_study (thousands of runs).
//
// Evaluation:
//   landmark_error   e_l (eq. 4.2): the mean squared distance (m^2) between the true trees
//                    and the estimated ones mapped in Euclidean form (XYZ or XYZ-R) at the
//                    end of lap 1, after the similarity alignment of eq. 4.1-4.11. Trees
//                    still in inverse depth (or IDR) have no depth estimate yet and are
//                    left out.
//   trajectory_error e_t (eq. 4.12): the mean squared distance of the camera positions over
//                    the last lap, aligned with the similarity fitted to the final map.
//   converged        e_l < 10 and e_t < 3 (Sec. 4.2).
//   radius_rmse_m    RMS error of the XYZ-R trees' radii at the end, estimated radii times
//                    the alignment's scale (a monocular map's unit is arbitrary).
//   pose_nees        the camera pose's NEES (position and orientation, 6 dof) every
//                    `nees_every` frames, in the filter's own frame: it starts at the true
//                    first pose, so no alignment is needed (or allowed) for consistency.

#include <array>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include <sylva/consistency/camera_pose_nees.hpp>
#include <sylva/eval/association_score.hpp>
#include <sylva/eval.hpp>
#include <sylva/sim/forest_scenario.hpp>

#include "monocular_tree_slam.hpp"

namespace forest_slam {

struct RunResult {
  double landmark_error = std::numeric_limits<double>::infinity();
  double trajectory_error = std::numeric_limits<double>::infinity();
  bool converged = false;
  double radius_rmse_m = std::numeric_limits<double>::quiet_NaN();
  double mean_true_radius_m = std::numeric_limits<double>::quiet_NaN();
  int xyzr_trees = 0;
  std::array<int, 4> by_type{0, 0, 0, 0};  ///< [inverse depth, XYZ, XYZ-R, IDR] at the end
  int rejected = 0;
  int hypotheses = 0;
  double runtime_s = 0.0;
  std::vector<double> pose_nees;  ///< every `nees_every` frames, from frame 0
  std::vector<double> position_nees;     ///< the same frames, camera position alone (3 dof)
  std::vector<double> orientation_nees;  ///< the same frames, camera orientation alone (3 dof)
  /// NIS at the predicted state by the landmark's parametrization [inverse depth, XYZ, XYZ-R,
  /// IDR] over the whole run (FrameReport::nis).
  std::array<sylva::NisTally, 4> nis = FrameReport::emptyNisTallies();
  std::string failure;            ///< why an error could not be computed, if so
  /// Association without ids, scored with the simulator's ids.
  sylva::AssociationScore association;
};

/// What a run leaves behind for drawing it.
struct RunTrace {
  std::vector<Vec<3>> estimated_path;  ///< the filter's camera position at every frame
  bool aligned = false;                ///< `final_alignment` is valid
  sylva::eval::Similarity3 final_alignment;
  /// The landmarks mapped in Euclidean form at the end (unaligned): position and radius
  /// (NaN for XYZ points).
  std::vector<std::pair<Vec<3>, double>> final_landmarks;
};

/// Position of every landmark mapped in Euclidean form (XYZ or XYZ-R): [id, position].
/// Trees still in inverse depth or IDR are left out: their depth is not yet observable (that
/// is why they have not been converted), so the point at 1 / rho is not an estimate of where
/// they are.
template <typename Filter>
std::vector<std::pair<Id, Vec<3>>> euclideanLandmarks(const Filter& ekf) {
  std::vector<std::pair<Id, Vec<3>>> out;
  for (const auto& s : ekf.slots()) {
    if (ekf.template holds<sylva::Point3>(s.id))
      out.emplace_back(s.id, ekf.template landmarkMean<sylva::Point3>(s.id));
    else if (ekf.template holds<sylva::TreeXYZR>(s.id))
      out.emplace_back(s.id, ekf.template landmarkMean<sylva::TreeXYZR>(s.id).template head<3>());
  }
  return out;
}

/// Aligns estimated landmark positions to the true trees; returns the transform and e_l.
std::pair<sylva::eval::Similarity3, double> alignMap(
    const std::vector<std::pair<Id, Vec<3>>>& estimated,
    const sylva::sim::ForestScenario& scenario);

/// The camera pose NEES (sylva::cameraPoseNees) and that of its position and orientation
/// alone, each infinity where the filter's covariance of it is not positive definite.
struct PoseNees {
  double pose, position, orientation;
};
/// P is the filter's camera covariance: of the 13 entries, or of the 12-dimensional tangent of
/// a camera on its manifold (then the error is truth (-) estimate).
template <int N>
PoseNees cameraPoseNees(const Vec<13>& estimate, const Mat<N, N>& P, const Vec<13>& truth);
extern template PoseNees cameraPoseNees<12>(const Vec<13>&, const Mat<12, 12>&, const Vec<13>&);
extern template PoseNees cameraPoseNees<13>(const Vec<13>&, const Mat<13, 13>&, const Vec<13>&);

/// One run of `options` over `scenario` (at most `max_frames` frames, 0: all).
RunResult runForestSlam(const sylva::sim::ForestScenario& scenario,
                        const TreeSlamOptions& options,
                        int max_frames = 0,
                        int nees_every = 10,
                        RunTrace* trace = nullptr);

}  // namespace forest_slam
