// laser_camera_slam: 2D EKF-SLAM in a simulated office corridor with three kinds of point
// landmarks, compared on the same run (multisensor thesis, Amarasinghe 2008, Ch. 3):
//
//   laser_corners  corners extracted from the laser scan (sylva/laser/corner_features.hpp);
//   laser_camera   vertical lines seen by the camera, ranged by the laser
//                  (sylva::LaserCameraSensor, Sec. 3.3: calibration curve, eq. 3.4, eq. 3.5);
//   fused          both (a laser-camera point within 0.3 m of a corner of the same scan is
//                  dropped: it is the same vertical edge).
//
// World (indoor_world.hpp): a 3 m wide corridor around a 40 m loop, with flush door frames
// (camera only), posters above the laser plane (the sensor must reject them), pillars
// (laser corners and camera edges) and the walls' corners. The robot drives 1.75 laps at
// 0.5 m/s, one scan and one image every 0.4 s (20 cm, as the thesis logged its data).
// Sensors: laser 180 deg at 0.5 deg, 8 m, 1 cm (sim::LaserScanner2D); camera 60 deg, 1 px
// noise, with a systematic bearing error (0.5 deg yaw, 2 % scale, cubic lens term) that the
// program calibrates away from 40 simulated 'v'-target pairs (Sec. 3.3.2) unless
// --no-calibration. Odometry noise 5 cm/s and 1 deg/s.
//
// Filter: sylva::Ekf<Unicycle2D, Point2> with RangeBearing / InverseRangeBearing, stepped by
// sylva::slam::FrontEnd: JCBB
// association (gate 0.99 with Table 3.1's 5 cm / 1 deg), each feature fused with its own
// covariance; an unpaired feature becomes a landmark when its NIS to every candidate exceeds
// chi2(2, 0.999999).
//
// Output: landmark counts over time (as Fig. 3.12), final pose and map errors, pose NEES; an
// SVG map and an SVG of the pose error with its 3-sigma bounds (as Fig. 3.15-3.16). Same flags,
// same output, bit for bit. Run `laser_camera_slam --help` for the flags.

#include <cstdint>
#include <iostream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "../common/planar_map_svg.hpp"
#include "run.hpp"
#include "sigma_plot.hpp"
#include "../common/report.hpp"
#include "../common/text.hpp"

namespace {

using sylva_examples::fixed;

using namespace laser_camera_slam;

const Variant kVariants[] = {Variant::kLaserCorners, Variant::kLaserCamera, Variant::kFused};

nlohmann::json summary(const VariantResult& r) {
  return {{"landmarks", r.landmarks},
          {"spurious_landmarks", r.spurious},
          {"landmark_rmse_m", r.landmark_rmse_m},
          {"final_position_error_m", r.final_position_error_m},
          {"final_heading_error_deg", r.final_heading_error_rad / kRadPerDeg},
          {"nees_mean", r.nees_mean},
          {"nees_fraction_inside_95", r.nees_fraction_inside},
          {"paired", r.paired},
          {"wrongly_paired", r.wrong},
          {"ambiguous_dropped", r.ambiguous}};
}

void writePictures(const std::string& prefix, const Simulation& sim, const std::vector<VariantResult>& results) {
  const char* colours[] = {"#d62728", "#2ca02c", "#1f6fd1"};
  std::vector<SigmaSeries> series;
  for (const auto& r : results) {
    SigmaSeries s;
    s.name = variantName(r.variant);
    s.colour = colours[static_cast<int>(r.variant)];
    for (std::size_t k = 0; k < r.records.size(); ++k) {
      s.time_s.push_back(sim.dt_s * static_cast<double>(k + 1));
      for (int c = 0; c < 3; ++c) {
        const double unit = c == 2 ? 1.0 / kRadPerDeg : 1.0;
        s.error[c].push_back(unit * r.records[k].error[c]);
        s.sigma[c].push_back(unit * r.records[k].sigma[c]);
      }
    }
    series.push_back(std::move(s));
  }
  writeSigmaPlot(prefix + "sigma.svg", "Robot pose error and 3-sigma bounds", series);

  const VariantResult& fused = results[2];
  sylva_examples::SvgMapData map;
  map.title = "laser_camera_slam: fused landmarks (laser corners + laser-camera)";
  map.subtitle_lines = {"walls grey; true vertical edges that cross the laser plane as crosses, posters excluded; "
                        "estimated landmarks with 2-sigma ellipses",
                        "final pose error " + fixed(fused.final_position_error_m, 3) + " m, " +
                            std::to_string(fused.landmarks) + " landmarks, landmark RMS " +
                            fixed(fused.landmark_rmse_m, 3) + " m"};
  Vec<3> odo = Vec<3>::Zero();
  map.odometry_path.push_back(odo.head<2>());
  map.true_path.push_back(Vec<2>::Zero());
  const sylva::Unicycle2D unicycle;
  for (const auto& d : sim.steps) {
    odo = unicycle(odo, d.odometry, sim.dt_s);
    map.odometry_path.push_back(odo.head<2>());
    map.true_path.push_back(d.true_pose.head<2>());
  }
  map.estimated_path = fused.path;
  std::vector<bool> mapped;
  for (const auto& e : sim.world.edges) {
    if (e.z_bottom_m > 0.40 || e.z_top_m < 0.40) continue;
    map.true_landmarks.push_back(e.position);
    bool near = false;
    for (const auto& m : fused.map)
      if ((m.first - e.position).norm() < 0.25) near = true;
    mapped.push_back(near);
  }
  map.true_landmark_mapped = mapped;
  for (const auto& m : fused.map) map.estimated_landmarks.push_back({m.first, m.second});
  map.start_pose = Vec<3>::Zero();
  map.true_final_pose = sim.steps.back().true_pose;
  const Vec<3> e = fused.records.back().error;
  map.estimated_final_pose = map.true_final_pose - e;  // error = true - estimate
  map.final_position_covariance = Mat<2, 2>::Zero();
  map.final_position_covariance.diagonal() = fused.records.back().sigma.head<2>().cwiseAbs2();
  map.sensor_range_fov = Vec<2>(8.0, 30.0 * kRadPerDeg);
  for (const auto& s : sim.world.walls.segments()) map.walls.push_back({s.a, s.b});
  sylva_examples::writeSvgMap(prefix + "map.svg", map);
}

int run(const Options& o, int seeds, bool json, const std::string& svg_prefix) {
  nlohmann::json j;
  int met = 0;
  for (int s = 0; s < seeds; ++s) {
    Options os = o;
    os.seed = o.seed + static_cast<std::uint64_t>(s);
    const Simulation sim = simulate(os);
    std::vector<VariantResult> results;
    for (const Variant v : kVariants) results.push_back(runVariant(sim, os, v));
    const bool done = results[2].landmarks > results[0].landmarks &&
                      results[2].final_position_error_m < results[0].final_position_error_m;
    met += done ? 1 : 0;
    if (s == 0 && !svg_prefix.empty()) writePictures(svg_prefix, sim, results);

    nlohmann::json one;
    one["seed"] = os.seed;
    one["steps"] = sim.steps.size();
    for (const auto& r : results) one[variantName(r.variant)] = summary(r);
    one["fused_beats_corners"] = done;
    if (s == 0) {
      long long corners = 0, lc = 0, lines = 0;
      for (const auto& d : sim.steps) {
        corners += static_cast<long long>(d.corners.size());
        lc += static_cast<long long>(d.laser_camera.size());
        lines += d.lines_detected;
      }
      const double n = static_cast<double>(sim.steps.size());
      one["world"] = {{"vertical_edges", sim.world.edges.size()}, {"doors", sim.world.doors},
                      {"posters", sim.world.posters}, {"pillars", sim.world.pillars}};
      one["detections_per_step"] = {{"laser_corners", corners / n}, {"camera_lines", lines / n}, {"laser_camera", lc / n}};
      nlohmann::json status;
      for (int k = 0; k < 6; ++k)
        status[sylva::describe(static_cast<sylva::LaserCameraStatus>(k))] = sim.status_counts[static_cast<std::size_t>(k)];
      one["laser_camera_status"] = status;
      one["camera_bearing_bias_rms_deg"] = {{"uncalibrated", sim.uncalibrated_bearing_rms_rad / kRadPerDeg},
                                            {"calibrated", sim.calibrated_bearing_rms_rad / kRadPerDeg}};
      // As Fig. 3.12: the features observed in a step and the landmarks in each variant's map.
      nlohmann::json counts = nlohmann::json::array();
      for (std::size_t k = 0; k < sim.steps.size(); k += std::max<std::size_t>(1, sim.steps.size() / 20))
        counts.push_back({{"step", k + 1}, {"time_s", sim.dt_s * static_cast<double>(k + 1)},
                          {"seen_corners", sim.steps[k].corners.size()}, {"seen_lines", sim.steps[k].lines_detected},
                          {"seen_laser_camera", sim.steps[k].laser_camera.size()},
                          {"map_corners", results[0].records[k].map_size},
                          {"map_laser_camera", results[1].records[k].map_size},
                          {"map_fused", results[2].records[k].map_size}});
      one["landmarks_over_time"] = counts;
    }
    j["runs"].push_back(one);
  }
  j["seeds_where_fused_beats_corners"] = met;
  j["seeds"] = seeds;
  sylva_examples::writeResult(std::cout, json,
                              "laser_camera_slam: laser corners vs laser-camera landmarks vs both (multisensor thesis "
                              "Sec. 3.3-3.5)", j);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  int seeds = 1;
  bool json = false;
  bool no_calibration = false;
  bool reject_jumps = false;
  std::string svg_prefix = "laser_camera_";
  CLI::App app{"2D EKF-SLAM in a simulated corridor: laser corners vs laser-camera landmarks (multisensor thesis "
               "Sec. 3.3-3.5) vs both, on the same run."};
  app.option_defaults()->always_capture_default();  // every option shows its default in --help
  app.add_option("--seed", o.seed, "seed of the noise (the world is fixed)");
  app.add_option("--seeds", seeds, "run seeds seed .. seed + N - 1 and report each")
      ->check(CLI::Range(1, 10000));
  app.add_option("--laps", o.laps, "laps of the 40 m loop")->check(CLI::Range(0.05, 100.0));
  app.add_flag("--no-calibration", no_calibration, "use the camera bearings without the calibration curve");
  app.add_flag("--reject-jumps", reject_jumps,
               "reject lines at a range jump instead of ranging them on the nearer surface");
  app.add_flag("--json", json, "print one JSON object instead of text");
  app.add_option("--svg-prefix", svg_prefix, "write <prefix>map.svg and <prefix>sigma.svg (\"\": none)");
  CLI11_PARSE(app, argc, argv);
  o.calibrate = !no_calibration;
  o.near_side_at_jumps = !reject_jumps;
  try {
    return run(o, seeds, json, svg_prefix);
  } catch (const sylva::Error& e) {
    std::cerr << "laser_camera_slam: " << e.what() << "\n";
    return 1;
  }
}
