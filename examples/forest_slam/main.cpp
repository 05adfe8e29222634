// forest_slam: monocular EKF-SLAM in a simulated forest, with and without the tree-width
// sensor, on the same measurements (tree-width thesis, Ch. 3-4), and a third pipeline beyond
// the thesis that uses the width from a tree's first sight (inverse depth plus radius, IDR).
//
// The world (sylva::sim, thesis Sec. 4.1.1): trees on a 3 m grid over 40 m x 40 m, each cell
// occupied with probability --density (about 85 trees by default), jittered by 0.6 m, radii ~ N(0.25 m, 0.07 m) on a
// gently rolling ground; a camera 1.5 m above the ground drives a closed Bezier loop of
// about 56 m through the forest --laps times (default 2) at 1 m/s, 10 frames per second,
// looking ahead and 15 degrees down. In every frame it measures, for each tree whose whole
// base ellipse is inside the 640 x 480 image (and, with occlusion on, that no nearer trunk
// overlaps in u), [u, v, w]: the centre of the base ellipse and its width in pixels, with
// Gaussian noise (--pixel-noise on u and v, --width-noise on w). Tree ids are the data
// association by default; with --association nn the filter ignores them (gated nearest
// neighbour on each tree's own model, sylva::slam::TrunkAssociation) and they only score it.
//
// Recorded detections: --write-recording PREFIX writes the simulated detections, the camera and
// its initial state as CSV (recording.hpp); --detections, --camera and --initial-state run the
// three pipelines on such files (a trunk detector's output) and write their estimates
// (--csv-prefix) and maps (--svg-prefix), with no truth to score them.
//
// The filter (sylva::slam::MonocularTreeSlam, include/sylva/slam/monocular_tree_slam.hpp): Ekf<ConstantVelocity3D,
// InverseDepth, Point3, TreeXYZR> starting at the true first camera state (the map frame),
// with the true initial velocity known to 0.1 m/s. Trees start as inverse-depth points
// (Civera et al. 2008), become XYZ when their linearity index drops below 0.1 and, in the
// run with the tree-width sensor, XYZ-R (radius from InverseTreeWidth) once their position
// sigma is below --xyzr-sigma (TreeSlamOptions::tree_position_sigma_m, default 0.3 m), after
// which TreeWidth updates use the width too. The run without the sensor keeps them XYZ and
// uses only (u, v). Observations whose NIS exceeds the
// chi-square gate of probability --gate (0.99999) are skipped. The third run
// ("width_first_sight") starts each tree as InverseDepthRadius, fuses [u, v, w] from the first
// frame and converts it straight to XYZ-R by the linearity rule.
//
// Evaluation (forest_run.hpp; sylva::eval, thesis Sec. 4.1.2): the estimated map is aligned to the true one
// by a similarity transform (Eigen::umeyama). landmark_error = e_l (eq. 4.2), the MEAN
// SQUARED distance (m^2) of the aligned landmarks at the end of lap 1 (trees mapped in
// Euclidean form, XYZ or XYZ-R; those still in inverse depth have no depth estimate yet and
// are counted apart); trajectory_error =
// e_t (eq. 4.12), the mean squared distance of the aligned camera positions over the last
// lap, aligned with the final map. converged: e_l < 10 and e_t < 3 (Sec. 4.2).
// radius_rmse_m: RMS error of the radii of the XYZ-R trees at the end, estimated radii
// multiplied by the alignment's scale (the map's unit is arbitrary in monocular SLAM);
// mean_true_radius_m: the mean true radius of the same trees.
//
// Output: a table (or --json), and one SVG per run (--svg-prefix) like the thesis' Fig. 4.9;
// --forest-svg draws the generated forest and path (Fig. 4.1). Everything is reproducible
// from the flags.

#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <sylva/eval.hpp>
#include <sylva/sim/forest_scenario.hpp>

#include "../common/report.hpp"
#include "forest_run.hpp"
#include "forest_svg.hpp"
#include "monocular_tree_slam.hpp"
#include "recording.hpp"

namespace {

using forest_slam::MonocularTreeSlam;
using forest_slam::TreeSlamOptions;
using sylva::Id;
using sylva::Mat;
using sylva::Vec;

using forest_slam::RunResult;
using forest_slam::WidthPipeline;

/// The three pipelines, in the order of the table's columns.
struct PipelineRun {
  WidthPipeline pipeline;
  const char* key;    ///< JSON key and SVG suffix
  const char* title;  ///< table column / SVG title
};
constexpr PipelineRun kPipelines[] = {
    {WidthPipeline::kAfterXyz, "with_width", "with width"},
    {WidthPipeline::kNone, "without_width", "without width"},
    {WidthPipeline::kFromFirstSight, "width_first_sight", "width 1st sight"},
};

RunResult runSlam(const sylva::sim::ForestScenario& scenario,
                  TreeSlamOptions options,
                  const PipelineRun& which,
                  int max_frames,
                  const std::string& svg_path,
                  const std::string& csv_prefix) {
  options.pipeline = which.pipeline;
  forest_slam::RunTrace trace;
  const RunResult result = forest_slam::runForestSlam(scenario, options, max_frames, 0, &trace);
  if (!csv_prefix.empty()) {
    forest_slam::Estimate e;
    e.path = trace.estimated_path;
    for (std::size_t k = 0; k < e.path.size(); ++k) e.t_s.push_back(scenario.frames[k].t_s);
    e.trees = trace.final_landmarks;
    forest_slam::writeEstimateCsv(csv_prefix + "_" + which.key, e);
  }
  if (!svg_path.empty()) {
    const auto& frames = scenario.frames;
    const int n_frames = static_cast<int>(trace.estimated_path.size());
    const sylva::eval::Similarity3& T = trace.final_alignment;
    forest_slam::ForestSvgData svg;
    const char* how = which.pipeline == WidthPipeline::kNone       ? "without the tree-width sensor"
                      : which.pipeline == WidthPipeline::kAfterXyz ? "with the tree-width sensor"
                                                                   : "with the tree-width sensor from the first sight (IDR)";
    svg.title = std::string("forest_slam, ") + how;
    char line[256];
    std::snprintf(line, sizeof line, "landmark error e_l %.3f m^2, trajectory error e_t %.3f m^2, %s; %d trees XYZ-R, %d XYZ, %d inverse depth",
                  result.landmark_error, result.trajectory_error, result.converged ? "converged" : "NOT converged",
                  result.by_type[2], result.by_type[1], result.by_type[0] + result.by_type[3]);
    svg.subtitle_lines.push_back(line);
    svg.subtitle_lines.push_back("estimates aligned to the truth by the similarity fitted to the final map (eq. 4.1-4.11)");
    for (const auto& t : scenario.trees) svg.true_trees.push_back({t.base.head<2>(), t.radius_m});
    for (int k = 0; k < n_frames; ++k) {
      svg.true_path.push_back(frames[k].state.head<2>());
      if (trace.aligned) svg.estimated_path.push_back(T(trace.estimated_path[k]).head<2>());
    }
    if (trace.aligned) {
      for (const auto& [p, radius] : trace.final_landmarks) {
        const Vec<3> q = T(p);
        if (std::isfinite(radius))
          svg.estimated_trees.push_back({q.head<2>(), radius * T.scale});
        else
          svg.estimated_points.push_back(q.head<2>());
      }
    }
    forest_slam::writeForestSvg(svg_path, svg);
  }
  return result;
}

nlohmann::json toJson(const RunResult& r) {
  auto number = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); };
  nlohmann::json j;
  j["landmark_error"] = number(r.landmark_error);
  j["trajectory_error"] = number(r.trajectory_error);
  j["converged"] = r.converged;
  j["radius_rmse_m"] = number(r.radius_rmse_m);
  j["mean_true_radius_m"] = number(r.mean_true_radius_m);
  j["runtime_s"] = r.runtime_s;
  j["trees_by_parametrization"] = {
      {"inverse_depth", r.by_type[0]}, {"xyz", r.by_type[1]}, {"xyzr", r.by_type[2]}, {"idr", r.by_type[3]}};
  j["rejected_observations"] = r.rejected;
  j["reanchored_frames"] = r.hypotheses;
  if (!r.failure.empty()) j["failure"] = r.failure;
  return j;
}

/// The association counts of a run without ids (scored with the simulator's ids).
nlohmann::json associationJson(const RunResult& r) {
  const sylva::AssociationScore& a = r.association;
  return {{"sightings", a.sightings},       {"paired_correct", a.paired_correct},
          {"paired_wrong", a.paired_wrong}, {"paired_before_own", a.paired_before_own},
          {"new_trees", a.new_trees},       {"duplicates", a.duplicates},
          {"ambiguous", a.ambiguous},       {"correct_fraction", a.correctFraction()}};
}

/// The three pipelines on a recording (recording.hpp): CSV of each estimate at csv_prefix,
/// an SVG of each (no truth to draw), and a summary on stdout.
int runOnRecording(const forest_slam::Recording& recording, const TreeSlamOptions& slam_options, int max_frames,
                   const std::string& csv_prefix, const std::string& svg_prefix, bool json) {
  nlohmann::json out;
  std::size_t detections = 0;
  for (const auto& f : recording.frames) detections += f.detections.size();
  out["frames"] = recording.frames.size();
  out["detections"] = detections;
  out["association"] = sylva::slam::associationName(slam_options.association);
  for (const PipelineRun& p : kPipelines) {
    TreeSlamOptions options = slam_options;
    options.pipeline = p.pipeline;
    forest_slam::FrameReport totals;
    const forest_slam::Estimate e = forest_slam::runRecording(recording, options, max_frames, totals);
    if (!csv_prefix.empty()) forest_slam::writeEstimateCsv(csv_prefix + "_" + p.key, e);
    if (!svg_prefix.empty()) {
      forest_slam::ForestSvgData svg;
      svg.title = std::string("forest_slam on recorded detections, ") + p.title;
      svg.subtitle_lines.push_back("the filter's map frame (the first camera pose), unaligned: no truth to align to");
      for (const Vec<3>& q : e.path) svg.estimated_path.push_back(q.head<2>());
      for (const auto& [q, radius] : e.trees) {
        if (std::isfinite(radius))
          svg.estimated_trees.push_back({q.head<2>(), radius});
        else
          svg.estimated_points.push_back(q.head<2>());
      }
      forest_slam::writeForestSvg(svg_prefix + "_" + p.key + ".svg", svg);
    }
    out[p.key] = {{"fused", totals.fused},        {"added", totals.added},
                  {"ambiguous", totals.ambiguous}, {"rejected", totals.rejected}, {"removed", totals.removed},
                  {"trees_in_euclidean_form", e.trees.size()}};
  }
  sylva_examples::writeResult(std::cout, json, "forest_slam on a recording: the three pipelines", out);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"forest_slam: monocular EKF-SLAM in a simulated forest, with and without the tree-width sensor"};
  app.option_defaults()->always_capture_default();  // every option shows its default in --help
  std::uint64_t seed = forest_slam::kDefaultForestSeed;
  sylva::sim::ForestScenarioOptions scenario_options;
  TreeSlamOptions slam_options;
  bool no_occlusion = false;
  // The filter assumes TreeSlamOptions' sigmas per pixel of simulated noise.
  double pixel_noise_scale = slam_options.pixel_sigma_px;
  double width_noise_scale = slam_options.width_sigma_px;
  double frame_rate_hz = 1.0 / scenario_options.trajectory.dt_s;
  bool json = false;
  int max_frames = 0;
  std::string svg_prefix = "forest_slam";
  std::string forest_svg;
  app.add_option("--seed", seed, "seed of the forest and of the measurement noise (default: the representative forest, see docs/forest-slam-results.md)");
  app.add_option("--pixel-noise", scenario_options.observer.sigma_px, "sigma of u and v (pixels) in the simulation (the filter assumes --pixel-noise-scale times it)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--width-noise", scenario_options.observer.sigma_width_px, "sigma of the width w (pixels) in the simulation (the filter assumes --width-noise-scale times it)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--density", scenario_options.forest.presence_probability, "probability that a grid cell (--grid) holds a tree")
      ->check(CLI::Range(0.0, 1.0));
  app.add_flag("--no-occlusion", no_occlusion, "also measure trees hidden behind nearer trunks");
  app.add_option("--laps", scenario_options.trajectory.laps, "laps of the loop (the thesis drives two)")->check(CLI::PositiveNumber);
  app.add_option("--frame-rate", frame_rate_hz, "camera frames per second")->check(CLI::PositiveNumber);
  app.add_option("--speed", scenario_options.trajectory.speed_mps, "camera speed along the loop (m/s)")
      ->check(CLI::PositiveNumber);
  app.add_option("--fx", scenario_options.camera.fx, "focal length u (pixels)");
  app.add_option("--fy", scenario_options.camera.fy, "focal length v (pixels)");
  app.add_option("--cx", scenario_options.camera.cx, "principal point u (pixels)");
  app.add_option("--cy", scenario_options.camera.cy, "principal point v (pixels)");
  app.add_option("--image-width", scenario_options.camera.width, "image width (pixels)");
  app.add_option("--image-height", scenario_options.camera.height, "image height (pixels)");
  app.add_option("--pixel-noise-scale", pixel_noise_scale,
                 "the filter assumes this multiple of the simulated sigma on u and v (the thesis' gain, Sec. 4.2)")
      ->check(CLI::PositiveNumber);
  app.add_option("--width-noise-scale", width_noise_scale, "the filter assumes this multiple of the simulated sigma on w")
      ->check(CLI::PositiveNumber);
  app.add_option("--accel-noise", slam_options.linear_accel_sigma, "filter's linear acceleration sigma (m/s^2)");
  const std::map<std::string, sylva::ConstantVelocity3D::VelocityFrame> velocity_frames{
      {"world", sylva::ConstantVelocity3D::VelocityFrame::kWorld},
      {"camera", sylva::ConstantVelocity3D::VelocityFrame::kCamera}};
  app.add_option("--velocity-frame", slam_options.velocity_frame,
                 "frame of the camera's linear velocity in the motion model: world (MonoSLAM's and the thesis's "
                 "model) or camera (constant along an arc; docs/consistency.md)")
      ->transform(CLI::CheckedTransformer(velocity_frames, CLI::ignore_case))
      ->default_str("world");
  const std::map<std::string, sylva::LinearizationPoint> linearizations{
      {"textbook", sylva::LinearizationPoint::kCurrentEstimate},
      {"first-estimates", sylva::LinearizationPoint::kFirstEstimates},
      {"iterated", sylva::LinearizationPoint::kIterated},
      {"observability-constrained", sylva::LinearizationPoint::kObservabilityConstrained}};
  app.add_option("--linearization", slam_options.linearization,
                 "where the filter linearizes: textbook, first-estimates, iterated or observability-constrained "
                 "(docs/filter.md)")
      ->transform(CLI::CheckedTransformer(linearizations, CLI::ignore_case))
      ->default_str("textbook");
  app.add_flag("--camera-on-manifold", slam_options.camera_on_manifold,
               "keep the camera's state on its manifold (OnManifold<ConstantVelocity3D>): its covariance on the "
               "12-dimensional tangent, each update composed through plus, instead of the quaternion's four entries");
  app.add_flag("--conversion-given-camera", slam_options.conversion_given_camera,
               "the life cycle judges each landmark's uncertainty given the camera's state (for a consistent "
               "filter, whose map keeps its position and scale uncertain)");
  app.add_option("--angular-accel-noise", slam_options.angular_accel_sigma, "filter's angular acceleration sigma (rad/s^2)");
  app.add_option("--linearity-threshold", slam_options.linearity_threshold, "inverse depth -> XYZ below this linearity index");
  app.add_option("--xyzr-sigma", slam_options.tree_position_sigma_m, "XYZ -> XYZ-R once the position sigma is below this (m)");
  app.add_option("--gate", slam_options.gate_probability, "chi-square gate probability on each observation's NIS (0: off)");
  app.add_option("--grid", scenario_options.forest.grid_spacing_m, "spacing of the forest's grid (m)");
  app.add_option("--frames", max_frames, "stop after this many frames (0: all)");
  app.add_flag("--json", json, "print the results as JSON");
  app.add_option("--svg-prefix", svg_prefix, "write PREFIX_with_width.svg, PREFIX_without_width.svg and PREFIX_width_first_sight.svg (empty: none)");
  app.add_option("--forest-svg", forest_svg, "also write the generated forest and path (top view) to this SVG");
  const std::map<std::string, sylva::Fusion> fusions{{"batched", sylva::Fusion::kBatched},
                                                     {"sequential", sylva::Fusion::kSequential}};
  app.add_option("--fusion", slam_options.fusion,
                 "batched: each model's observations of a frame in one update; sequential: one update per "
                 "observation, each linearized after the previous one (TreeSlamOptions::fusion)")
      ->transform(CLI::CheckedTransformer(fusions, CLI::ignore_case))
      ->default_str("batched");
  const std::map<std::string, sylva::slam::TrunkAssociation> associations{
      {"ids", sylva::slam::TrunkAssociation::kKnownIds}, {"nn", sylva::slam::TrunkAssociation::kNearestNeighbor}};
  app.add_option("--association", slam_options.association,
                 "ids: the detections' ids name the trees; nn: ids ignored, gated nearest neighbour on each tree's "
                 "own model (TrunkAssociation); with the simulator, the ids still score the result")
      ->transform(CLI::CheckedTransformer(associations, CLI::ignore_case))
      ->default_str("ids");
  app.add_option("--association-gate", slam_options.association_gate_probability,
                 "--association nn: chi-square probability of the gate of a pairing")
      ->check(CLI::Range(0.5, 0.9999999));
  app.add_option("--new-tree-gate", slam_options.new_tree_probability,
                 "--association nn: a sighting that pairs with nothing starts a tree only when its NIS to every tree "
                 "exceeds this chi-square quantile")
      ->check(CLI::Range(0.5, 0.9999999));
  bool no_width_appearance = false;
  app.add_flag("--no-width-appearance", no_width_appearance,
               "--association nn: compare landmarks that predict [u, v] only on [u, v] alone, not also on the width "
               "predicted from their last sighting");
  app.add_option("--width-appearance-tolerance", slam_options.width_appearance_tolerance,
                 "--association nn: relative standard deviation of a point landmark's predicted width beyond the "
                 "width noise")
      ->check(CLI::Range(0.0, 10.0));
  app.add_option("--continuity-cost", slam_options.continuity_cost,
                 "--association nn: the continuity test's largest cost, NIS + log det(S R^-1), of a pairing "
                 "with a tree not sighted in the previous frame or of a sighting near the image's left or right "
                 "edge ('inf': off)")
      ->capture_default_str();
  app.add_option("--continuity-edge-margin", slam_options.continuity_edge_margin_px,
                 "--association nn: the continuity test's margin (pixels) at the image's left and right edges "
                 "(< 0: none)")
      ->capture_default_str();
  app.add_option("--loop-pairings", slam_options.loop_pairings,
                 "--association nn: pairings with trees of at least --loop-sightings sightings that the continuity "
                 "test refuses are taken together when at least this many are jointly compatible (a loop closed; "
                 "0: off)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  app.add_option("--loop-sightings", slam_options.loop_sightings,
                 "--association nn: sightings a tree must have taken to count for --loop-pairings")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  app.add_option("--unconfirmed-after", slam_options.unconfirmed_after_frames,
                 "remove a landmark that took fewer than --confirm-sightings sightings once this many frames pass "
                 "without one (0: never)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  app.add_option("--confirm-sightings", slam_options.confirm_sightings,
                 "sightings that confirm a landmark (--unconfirmed-after)")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  std::string csv_prefix, write_recording, detections_file, camera_file, initial_state_file;
  app.add_option("--csv-prefix", csv_prefix,
                 "write each pipeline's estimate: PREFIX_<pipeline>_trajectory.csv and PREFIX_<pipeline>_map.csv");
  app.add_option("--write-recording", write_recording,
                 "write the simulated detections as a recording: PREFIX_detections.csv, PREFIX_camera.csv, "
                 "PREFIX_initial_state.csv (examples/forest_slam/recording.hpp)");
  app.add_option("--detections", detections_file,
                 "run on recorded detections instead of the simulator (CSV: time_s, u_px, v_px, w_px[, id]); needs "
                 "--camera and --initial-state");
  app.add_option("--camera", camera_file, "with --detections: the intrinsics (CSV: fx, fy, cx, cy, width, height)");
  app.add_option("--initial-state", initial_state_file,
                 "with --detections: the camera's state at the first frame (CSV, 13 values; it gives the map its "
                 "frame and scale)");
  CLI11_PARSE(app, argc, argv);
  slam_options.width_appearance = !no_width_appearance;
  scenario_options.observer.occlusion = !no_occlusion;
  scenario_options.trajectory.dt_s = 1.0 / frame_rate_hz;

  try {
    if (!detections_file.empty()) {
      if (camera_file.empty() || initial_state_file.empty())
        sylva::fail(sylva::ErrorCode::kInvalidArgument, "--detections needs --camera and --initial-state");
      slam_options.pixel_sigma_px = pixel_noise_scale * std::max(scenario_options.observer.sigma_px, 0.1);
      slam_options.width_sigma_px = width_noise_scale * std::max(scenario_options.observer.sigma_width_px, 0.1);
      return runOnRecording(forest_slam::readRecording(detections_file, camera_file, initial_state_file), slam_options,
                            max_frames, csv_prefix, svg_prefix, json);
    }
    slam_options.camera = scenario_options.camera;
    slam_options.pixel_sigma_px = pixel_noise_scale * std::max(scenario_options.observer.sigma_px, 0.1);
    slam_options.width_sigma_px = width_noise_scale * std::max(scenario_options.observer.sigma_width_px, 0.1);
    const sylva::sim::ForestScenario scenario = sylva::sim::makeForestScenario(scenario_options, seed);
    if (!write_recording.empty()) forest_slam::writeRecording(write_recording, scenario);
    if (!forest_svg.empty()) {
      forest_slam::ForestSvgData svg;
      svg.title = "forest_slam: the simulated forest and the camera's path (seed " + std::to_string(seed) + ")";
      svg.subtitle_lines.push_back(std::to_string(scenario.trees.size()) + " trees, " + std::to_string(scenario.frames.size()) +
                                   " frames; the dot marks the start");
      for (const auto& t : scenario.trees) svg.true_trees.push_back({t.base.head<2>(), t.radius_m});
      for (const auto& f : scenario.frames) svg.true_path.push_back(f.state.head<2>());
      forest_slam::writeForestSvg(forest_svg, svg);
    }
    const auto svg_for = [&](const char* which) { return svg_prefix.empty() ? std::string() : svg_prefix + "_" + which + ".svg"; };
    std::vector<RunResult> results;
    for (const PipelineRun& p : kPipelines)
      results.push_back(runSlam(scenario, slam_options, p, max_frames, svg_for(p.key), csv_prefix));

    std::size_t observations = 0;
    for (const auto& o : scenario.observations) observations += o.size();
    nlohmann::json out;
    out["seed"] = seed;
    out["trees"] = scenario.trees.size();
    out["frames"] = max_frames > 0 ? std::min<std::size_t>(max_frames, scenario.frames.size()) : scenario.frames.size();
    out["mean_trees_per_frame"] = static_cast<double>(observations) / scenario.frames.size();
    for (std::size_t i = 0; i < results.size(); ++i) {
      out[kPipelines[i].key] = toJson(results[i]);
      if (slam_options.association != sylva::slam::TrunkAssociation::kKnownIds)
        out[kPipelines[i].key]["association"] = associationJson(results[i]);
    }
    sylva_examples::writeResult(std::cout, json,
                                "forest_slam: monocular EKF-SLAM in a simulated forest, with and without the tree-width "
                                "sensor",
                                out);
  } catch (const sylva::Error& e) {
    std::cerr << "forest_slam: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
