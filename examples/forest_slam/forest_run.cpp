// runForestSlam and its evaluation helpers (see forest_run.hpp), compiled once into the
// library forest_slam_pipeline.

#include "forest_run.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <unordered_map>
#include <unordered_set>

namespace forest_slam {

std::pair<sylva::eval::Similarity3, double> alignMap(
    const std::vector<std::pair<Id, Vec<3>>>& estimated,
    const sylva::sim::ForestScenario& scenario) {
  std::vector<Vec<3>> est, truth;
  for (const auto& [id, p] : estimated) {
    est.push_back(p);
    truth.push_back(scenario.tree(id).base);
  }
  const sylva::eval::Similarity3 T = sylva::eval::alignSimilarity(est, truth);
  return {T, sylva::eval::meanSquaredError(T, est, truth)};
}

template <int N>
PoseNees cameraPoseNees(const Vec<13>& estimate, const Mat<N, N>& P, const Vec<13>& truth) {
  const auto orInfinity = [](auto&& f) {
    try {
      return f();
    } catch (const sylva::Error&) {
      return std::numeric_limits<double>::infinity();
    }
  };
  const double inf = std::numeric_limits<double>::infinity();
  sylva::CameraPoseError err;
  try {
    if constexpr (N == 12) {
      err = sylva::cameraPoseErrorOnManifold(estimate, P, truth);
    } else {
      err = sylva::cameraPoseError(estimate, P, truth);
    }
  } catch (const sylva::Error&) {
    return {inf, inf, inf};
  }
  return {orInfinity([&] { return sylva::nees(err.e, err.S); }),
          orInfinity([&] { return sylva::nees(Vec<3>(err.e.head<3>()), Mat<3, 3>(err.S.topLeftCorner<3, 3>())); }),
          orInfinity([&] { return sylva::nees(Vec<3>(err.e.tail<3>()), Mat<3, 3>(err.S.bottomRightCorner<3, 3>())); })};
}

template PoseNees cameraPoseNees<12>(const Vec<13>&, const Mat<12, 12>&, const Vec<13>&);
template PoseNees cameraPoseNees<13>(const Vec<13>&, const Mat<13, 13>&, const Vec<13>&);

namespace {

template <typename Slam>
RunResult runWith(const sylva::sim::ForestScenario& scenario,
                  const TreeSlamOptions& options,
                  int max_frames,
                  int nees_every,
                  RunTrace* trace) {
  RunResult result;
  const auto& frames = scenario.frames;
  const int n_frames = std::min<int>(static_cast<int>(frames.size()),
                                     max_frames > 0 ? max_frames : static_cast<int>(frames.size()));
  Slam slam(options, frames.front().state, initialCameraCovariance());

  std::vector<Vec<3>> estimated_path;
  estimated_path.reserve(static_cast<std::size_t>(n_frames));
  std::unordered_map<Id, Id> tree_of;  // landmark -> the tree of the sighting that started it
  // The landmarks in Euclidean form, named by the tree they stand for (the evaluation's ids).
  const auto euclideanTrees = [&](const auto& filter) {
    std::vector<std::pair<Id, Vec<3>>> out = euclideanLandmarks(filter);
    for (auto& entry : out) entry.first = tree_of.at(entry.first);
    return out;
  };
  std::vector<std::pair<Id, Vec<3>>> end_of_lap1;
  const int last_lap = frames[n_frames - 1].lap;
  const auto start = std::chrono::steady_clock::now();
  const bool needs_truth = options.linearization == sylva::LinearizationPoint::kIdeal || options.unbiased_point_uv;
  const std::vector<Vec<4>> true_trees = treesOf(scenario.trees);
  std::vector<Vec<3>> noise_free;
  FrameTruth frame_truth;
  frame_truth.trees = &true_trees;
  frame_truth.noise_free = &noise_free;
  for (int k = 0; k < n_frames; ++k) {
    const double dt = k == 0 ? 0.0 : frames[k].t_s - frames[k - 1].t_s;
    frame_truth.camera_before = frames[k == 0 ? 0 : k - 1].state;
    frame_truth.camera = frames[k].state;
    if (options.unbiased_point_uv) noise_free = noiseFreeOf(scenario.observations[k]);
    const FrameReport report =
        slam.processFrame(dt, sightingsOf(scenario.observations[k]), needs_truth ? &frame_truth : nullptr);
    {
      std::vector<Id> trees;
      for (const auto& o : scenario.observations[k]) trees.push_back(o.id);
      result.association.addFrame(trees, report.landmark_of, tree_of);
    }
    result.rejected += report.rejected;
    result.hypotheses += report.hypotheses;
    for (std::size_t t = 0; t < 4; ++t) result.nis[t].merge(report.nis[t]);
    estimated_path.push_back(slam.filter().robotMean().template head<3>());
    if (nees_every > 0 && k % nees_every == 0) {
      const PoseNees n = cameraPoseNees(slam.filter().robotMean(), slam.filter().robotCovariance(), frames[k].state);
      result.pose_nees.push_back(n.pose);
      result.position_nees.push_back(n.position);
      result.orientation_nees.push_back(n.orientation);
    }
    const bool lap1_ends = frames[k].lap == 0 && (k + 1 == n_frames || frames[k + 1].lap > 0);
    if (lap1_ends) end_of_lap1 = euclideanTrees(slam.filter());
  }
  result.runtime_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const auto& ekf = slam.filter();
  result.by_type = slam.countByType();

  sylva::eval::Similarity3 final_alignment;
  bool aligned = false;
  try {
    result.landmark_error = alignMap(end_of_lap1, scenario).second;
    final_alignment = alignMap(euclideanTrees(ekf), scenario).first;
    aligned = true;
    std::vector<Vec<3>> est, truth;
    for (int k = 0; k < n_frames; ++k) {
      if (frames[k].lap != last_lap) continue;
      est.push_back(estimated_path[k]);
      truth.push_back(frames[k].state.head<3>());
    }
    result.trajectory_error = sylva::eval::meanSquaredError(final_alignment, est, truth);
  } catch (const sylva::Error& e) {
    result.failure = e.what();
  }
  result.converged =
      sylva::eval::ConvergenceCriteria{}.converged(result.landmark_error, result.trajectory_error);

  double sum_sq = 0.0, sum_true = 0.0;
  for (const auto& s : ekf.slots()) {
    if (!ekf.template holds<sylva::TreeXYZR>(s.id)) continue;
    const double r_est =
        ekf.template landmarkMean<sylva::TreeXYZR>(s.id)[3] * (aligned ? final_alignment.scale : 1.0);
    const double r_true = scenario.tree(tree_of.at(s.id)).radius_m;
    sum_sq += (r_est - r_true) * (r_est - r_true);
    sum_true += r_true;
    ++result.xyzr_trees;
  }
  if (result.xyzr_trees > 0) {
    result.radius_rmse_m = std::sqrt(sum_sq / result.xyzr_trees);
    result.mean_true_radius_m = sum_true / result.xyzr_trees;
  }
  if (trace != nullptr) {
    trace->estimated_path = std::move(estimated_path);
    trace->aligned = aligned;
    trace->final_alignment = final_alignment;
    trace->final_landmarks.clear();
    for (const auto& [id, p] : euclideanLandmarks(ekf))
      trace->final_landmarks.emplace_back(p,
                                          ekf.template holds<sylva::TreeXYZR>(id)
                                              ? ekf.template landmarkMean<sylva::TreeXYZR>(id)[3]
                                              : std::numeric_limits<double>::quiet_NaN());
  }
  return result;
}

}  // namespace

RunResult runForestSlam(const sylva::sim::ForestScenario& scenario,
                        const TreeSlamOptions& options,
                        int max_frames,
                        int nees_every,
                        RunTrace* trace) {
  if (options.camera_on_manifold) return runWith<ManifoldTreeSlam>(scenario, options, max_frames, nees_every, trace);
  return runWith<MonocularTreeSlam>(scenario, options, max_frames, nees_every, trace);
}

}  // namespace forest_slam
