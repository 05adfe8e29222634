#pragma once
// forest_slam on recorded detections: a recording is three CSV files (the formats of
// include/sylva/datasets/trunk_detections.hpp, plus the camera's initial state):
//
//   PREFIX_detections.csv     time_s, u_px, v_px, w_px[, id]   (a time alone: an empty frame)
//   PREFIX_camera.csv         fx_px, fy_px, cx_px, cy_px, width_px, height_px
//   PREFIX_initial_state.csv  the 13 entries of ConstantVelocity3D's state at the first frame:
//                             r_WC (3), q_WC (w, x, y, z), v_W (3), omega_C (3)
//
// The initial state gives the map its frame and, through the velocity, its scale: a single
// camera cannot measure either (the thesis starts the filter at the true first camera state,
// its velocity known to 0.1 m/s). `writeRecording` writes a simulated scenario this way, with
// the simulator's ids; `runRecording` runs the pipeline on a recording, and writes what it
// estimated as CSV (`writeEstimateCsv`), the same files a simulated run writes.

#include <cstdio>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include <sylva/datasets/numeric_table.hpp>
#include <sylva/datasets/trunk_detections.hpp>
#include <sylva/sim/forest_scenario.hpp>

#include "forest_run.hpp"
#include "monocular_tree_slam.hpp"

namespace forest_slam {

struct Recording {
  std::vector<sylva::datasets::TrunkDetectionFrame> frames;
  sylva::datasets::CameraIntrinsics camera;
  Vec<13> initial_state;
};

/// What a run estimated, for the CSV files: the camera position per frame, and the trees
/// mapped in Euclidean form at the end (radius NaN for XYZ points), unaligned.
struct Estimate {
  std::vector<double> t_s;
  std::vector<Vec<3>> path;
  std::vector<std::pair<Vec<3>, double>> trees;
};

inline std::string fullPrecision(double v) { return sylva::datasets::detail::fullPrecision(v); }

/// Writes `scenario` (every frame, with the simulator's ids) as a recording at `prefix`.
inline void writeRecording(const std::string& prefix, const sylva::sim::ForestScenario& scenario) {
  std::vector<sylva::datasets::TrunkDetectionFrame> frames;
  for (std::size_t k = 0; k < scenario.frames.size(); ++k) {
    sylva::datasets::TrunkDetectionFrame f{scenario.frames[k].t_s, {}};
    for (const auto& o : scenario.observations[k]) f.detections.push_back({o.z, o.id});
    frames.push_back(std::move(f));
  }
  sylva::datasets::writeTrunkDetections(prefix + "_detections.csv", frames);
  const auto& c = scenario.options.camera;
  sylva::datasets::writeCameraIntrinsics(prefix + "_camera.csv", {c.fx, c.fy, c.cx, c.cy, c.width, c.height});
  std::ofstream out(prefix + "_initial_state.csv");
  out << "# r_WC (3), q_WC (w, x, y, z), v_W (3), omega_C (3)\n";
  const Vec<13>& x0 = scenario.frames.front().state;
  for (int i = 0; i < 13; ++i) out << (i ? "," : "") << fullPrecision(x0[i]);
  out << "\n";
  if (!out) sylva::datasets::failMalformed(prefix + "_initial_state.csv", 0, "writing failed");
}

/// Reads the three files of a recording (kMalformedData names the file and line of anything
/// malformed).
inline Recording readRecording(const std::string& detections, const std::string& camera, const std::string& initial_state) {
  Recording r;
  r.frames = sylva::datasets::readTrunkDetections(detections);
  r.camera = sylva::datasets::readCameraIntrinsics(camera);
  sylva::datasets::readSingleCsvRow(initial_state, 13, "initial-state", [&](const sylva::datasets::NumericRow& row) {
    for (int i = 0; i < 13; ++i) r.initial_state[i] = row[i];
  });
  return r;
}

/// The pipeline of `options` over the first `max_frames` frames of `recording` (0: all).
/// With TrunkAssociation::kKnownIds every detection needs an id (kInvalidArgument otherwise).
template <typename Slam>
Estimate runRecordingWith(const Recording& recording, TreeSlamOptions options, int max_frames, FrameReport& totals) {
  const auto& c = recording.camera;
  options.camera = sylva::PinholeCamera{c.fx, c.fy, c.cx, c.cy, c.width, c.height};
  if (options.linearization == sylva::LinearizationPoint::kIdeal || options.unbiased_point_uv)
    sylva::fail(sylva::ErrorCode::kInvalidArgument, "forest_slam: a recording has no truth for the ideal diagnostics");
  Slam slam(options, recording.initial_state, initialCameraCovariance());
  const int n = max_frames > 0 ? std::min<int>(max_frames, static_cast<int>(recording.frames.size()))
                               : static_cast<int>(recording.frames.size());
  Estimate out;
  std::vector<TrunkSighting> sightings;
  for (int k = 0; k < n; ++k) {
    const auto& frame = recording.frames[static_cast<std::size_t>(k)];
    sightings.clear();
    for (const auto& d : frame.detections) {
      if (!d.id && options.association == sylva::slam::TrunkAssociation::kKnownIds)
        sylva::fail(sylva::ErrorCode::kInvalidArgument, "forest_slam: a detection at t = " + fullPrecision(frame.t_s) +
                                                            " s has no id; associate with --association nn");
      sightings.push_back(TrunkSighting{d.id ? *d.id : Id{-1}, d.z});
    }
    const double dt = k == 0 ? 0.0 : frame.t_s - recording.frames[static_cast<std::size_t>(k - 1)].t_s;
    const FrameReport report = slam.processFrame(dt, sightings);
    totals.fused += report.fused;
    totals.added += report.added;
    totals.rejected += report.rejected;
    totals.ambiguous += report.ambiguous;
    totals.removed += report.removed;
    out.t_s.push_back(frame.t_s);
    out.path.push_back(slam.filter().robotMean().template head<3>());
  }
  const auto& ekf = slam.filter();
  for (const auto& [id, p] : euclideanLandmarks(ekf))
    out.trees.emplace_back(p, ekf.template holds<sylva::TreeXYZR>(id) ? ekf.template landmarkMean<sylva::TreeXYZR>(id)[3]
                                                                     : std::numeric_limits<double>::quiet_NaN());
  return out;
}

inline Estimate runRecording(const Recording& recording, const TreeSlamOptions& options, int max_frames,
                             FrameReport& totals) {
  if (options.camera_on_manifold) return runRecordingWith<ManifoldTreeSlam>(recording, options, max_frames, totals);
  return runRecordingWith<MonocularTreeSlam>(recording, options, max_frames, totals);
}

/// Writes PREFIX_trajectory.csv (t_s, x, y, z of the camera) and PREFIX_map.csv (x, y, z,
/// radius_m of each tree in Euclidean form; radius "nan" for an XYZ point), unaligned, in the
/// filter's map frame, with 17 significant digits.
inline void writeEstimateCsv(const std::string& prefix, const Estimate& e) {
  std::ofstream path(prefix + "_trajectory.csv");
  path << "# t_s, x_m, y_m, z_m\n";
  for (std::size_t k = 0; k < e.path.size(); ++k)
    path << fullPrecision(e.t_s[k]) << "," << fullPrecision(e.path[k].x()) << "," << fullPrecision(e.path[k].y()) << ","
         << fullPrecision(e.path[k].z()) << "\n";
  std::ofstream map(prefix + "_map.csv");
  map << "# x_m, y_m, z_m, radius_m\n";
  for (const auto& [p, radius] : e.trees)
    map << fullPrecision(p.x()) << "," << fullPrecision(p.y()) << "," << fullPrecision(p.z()) << ","
        << (std::isfinite(radius) ? fullPrecision(radius) : std::string("nan")) << "\n";
  if (!path || !map) sylva::datasets::failMalformed(prefix, 0, "writing the estimate failed");
}

}  // namespace forest_slam
