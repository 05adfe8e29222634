// parking: the vision-based hybrid parking controller of Amarasinghe's thesis (2008), Ch. 5,
// on a simulated unicycle robot with a camera that sees a station of three features.
//
//   parking                 one parking attempt from the default start (near the axis, like
//                           Experiment I): FSM trace, cycles, time, final pose error, SVGs
//   parking --study         the repeatability study: --runs random starts with the station in
//                           view, with the adaptive virtual edge and with two fixed ones
//   --json                  one JSON object instead of text
//
// The controller (sylva::parking::HybridController, include/sylva/parking) sees only the
// measured feature positions; the simulator (station_camera.hpp, episode.hpp) and the study
// (study.hpp) are the example's own headers. See
// docs/examples/parking.md for the model, the parameters and where they come from, and the
// deviations from the printed algorithms. Same flags, same output, bit for bit.

#include <cmath>
#include <cstdint>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <sylva/parking/hybrid_controller.hpp>

#include "episode.hpp"
#include "figures.hpp"
#include "station_camera.hpp"
#include "study.hpp"
#include "../common/cli_checks.hpp"
#include "../common/report.hpp"


namespace {

using parking::kRadPerDeg;

struct Options {
  std::uint64_t seed = 1;
  double start_x_m = 0.03;
  double start_y_m = -1.0;
  double start_heading_deg = 90.0;
  double max_time_s = 300.0;
  bool json = false;
  std::string svg_prefix = "parking";
  std::string csv;
  bool study = false;
  parking::StudyOptions study_options;
  // Controller parameters in the units a user types (deg/s per px).
  double k1_degps_per_px = 0.25;
  double k2_degps_per_px = 0.10;
  double max_omega_degps = 1.0 / kRadPerDeg;
  bool no_adapt = false;
  bool raw_asymmetry = false;
  bool thesis_forward_exit = false;
};

std::string fixed(double v, int digits) {
  std::ostringstream os;
  os << std::fixed << std::setprecision(digits) << v;
  std::string s = os.str();
  if (s.size() > 1 && s[0] == '-' && s.find_first_not_of("-0.") == std::string::npos)
    s = s.substr(1);
  return s;
}

nlohmann::json poseJson(const parking::Pose& p) {
  return {{"x_m", p[0]}, {"y_m", p[1]}, {"heading_deg", p[2] / kRadPerDeg}};
}

nlohmann::json summaryJson(const parking::StudySummary& s) {
  return {{"runs", s.runs},
          {"parked", s.parked},
          {"station_lost", s.station_lost},
          {"timed_out", s.timed_out},
          {"collided", s.collided},
          {"success_rate", s.success_rate},
          {"x_spread_m", s.x_spread_m},
          {"y_spread_m", s.y_spread_m},
          {"heading_spread_deg", s.heading_spread_rad / kRadPerDeg},
          {"x_mean_m", s.x_mean_m},
          {"y_mean_m", s.y_mean_m},
          {"x_std_m", s.x_std_m},
          {"y_std_m", s.y_std_m},
          {"mean_cycles", s.mean_cycles},
          {"max_cycles", s.max_cycles},
          {"mean_time_s", s.mean_time_s},
          {"max_time_s", s.max_time_s},
          {"min_station_distance_m", s.min_station_distance_m}};
}

nlohmann::json controllerJson(const parking::ControllerParams& p) {
  return {{"reference_px", p.reference_px},
          {"image_width_px", p.image_width_px},
          {"k1_degps_per_px", p.k1_radps_per_px / kRadPerDeg},
          {"k2_degps_per_px", p.k2_radps_per_px / kRadPerDeg},
          {"c_min_px", p.c_min_px},
          {"c_max_px", p.c_max_px},
          {"adapt_c", p.adapt_c},
          {"c_gain", p.c_gain},
          {"c_static_px", p.c_static_px},
          {"scaled_asymmetry", p.scaled_asymmetry},
          {"exit_on_width", p.exit_on_width},
          {"start_exit_frames", p.start_exit_frames},
          {"parked_frames", p.parked_frames},
          {"v_forward_mps", p.v_forward_mps},
          {"v_reverse_mps", p.v_reverse_mps},
          {"v_reverse_slow_mps", p.v_reverse_slow_mps},
          {"delta_u_px", p.delta_u_px},
          {"delta_A_px", p.delta_A_px},
          {"A_min_px", p.A_min_px},
          {"max_omega_degps", p.max_omega_radps / kRadPerDeg}};
}

nlohmann::json cameraJson(const parking::CameraParams& c, const parking::RobotParams& r) {
  return {{"focal_px", c.focal_px},
          {"spacing_m", c.spacing_m},
          {"sigma_px", c.sigma_px},
          {"frame_rate_hz", c.frame_rate_hz},
          {"max_accel_mps2", r.max_accel_mps2},
          {"max_alpha_degps2", r.max_alpha_radps2 / kRadPerDeg},
          {"bump_distance_m", r.front_m}};
}

std::string noiseLine(const parking::CameraParams& c) {
  return "pixel noise " + fixed(c.sigma_px, 2) + " px, " + fixed(c.frame_rate_hz, 1) +
         " frames/s, f = " + fixed(c.focal_px, 0) + " px, feature spacing " +
         fixed(100 * c.spacing_m, 1) + " cm";
}

int runOne(const Options& o,
           const parking::StationCamera& camera,
           const parking::ControllerParams& cp,
           const parking::RobotParams& robot) {
  const parking::Pose start(o.start_x_m, o.start_y_m, o.start_heading_deg * kRadPerDeg);
  parking::EpisodeOptions eo;
  eo.max_time_s = o.max_time_s;
  eo.record = !o.svg_prefix.empty() || !o.csv.empty();
  const parking::EpisodeResult r = parking::runEpisode(camera, cp, robot, start, o.seed, eo);
  const bool parked = r.outcome == parking::Outcome::kParked;

  std::vector<std::string> written;
  if (!o.svg_prefix.empty()) {
    std::ostringstream l1, l2;
    l1 << "start (" << fixed(start[0], 2) << ", " << fixed(start[1], 2) << ") m, heading "
       << fixed(o.start_heading_deg, 1) << " deg; " << noiseLine(camera.params()) << "; seed "
       << o.seed;
    l2 << parking::toString(r.outcome) << " after " << fixed(r.time_s, 2) << " s, " << r.cycles
       << " forward-reverse cycle" << (r.cycles == 1 ? "" : "s");
    if (parked)
      l2 << "; final error x " << fixed(100 * r.error[0], 2) << " cm, y "
         << fixed(100 * r.error[1], 2) << " cm, heading " << fixed(r.error[2] / kRadPerDeg, 2)
         << " deg";
    const std::string path_svg = o.svg_prefix + "_path.svg";
    const std::string features_svg = o.svg_prefix + "_features.svg";
    parking::writePathSvg(
        path_svg, r, camera, "Hybrid parking controller: robot path", {l1.str(), l2.str()});
    parking::writeFeaturesSvg(features_svg,
                              r,
                              cp,
                              "Feature positions and velocities during parking",
                              {l1.str(), l2.str()});
    written = {path_svg, features_svg};
  }
  if (!o.csv.empty()) {
    std::ofstream csv(o.csv);
    if (!csv)
      sylva::fail(sylva::ErrorCode::kInvalidArgument, "cannot open CSV file '" + o.csv + "'");
    csv << "t_s,x_m,y_m,heading_deg,u1_px,u2_px,u3_px,v_cmd_mps,omega_cmd_degps,v_mps,"
           "omega_degps,state,c_px\n"
        << std::setprecision(9);
    for (const parking::Sample& s : r.samples)
      csv << s.t_s << "," << s.pose[0] << "," << s.pose[1] << "," << s.pose[2] / kRadPerDeg << ","
          << s.u_px[0] << "," << s.u_px[1] << "," << s.u_px[2] << "," << s.v_cmd << ","
          << s.omega_cmd / kRadPerDeg << "," << s.v << "," << s.omega / kRadPerDeg << ","
          << parking::toString(s.state) << "," << s.c_px << "\n";
    written.push_back(o.csv);
  }

  const double dt = 1.0 / camera.params().frame_rate_hz;
  nlohmann::json j;
  j["outcome"] = parking::toString(r.outcome);
  j["parked"] = parked;
  j["time_s"] = r.time_s;
  j["cycles"] = r.cycles;
  j["forward_moves"] = r.forward_moves;
  j["reverse_moves"] = r.reverse_moves;
  j["frames"] = r.frames;
  j["start"] = poseJson(r.start);
  j["goal"] = poseJson(r.goal);
  j["final_pose"] = poseJson(r.final_pose);
  j["final_error"] = {{"x_m", r.error[0]},
                      {"y_m", r.error[1]},
                      {"heading_deg", r.error[2] / kRadPerDeg},
                      {"position_m", std::hypot(r.error[0], r.error[1])}};
  j["min_station_distance_m"] = r.min_station_distance_m;
  nlohmann::json trace = nlohmann::json::array();
  for (std::size_t i = 0; i < r.transitions.size(); ++i) {
    const parking::Transition& t = r.transitions[i];
    trace.push_back({{"frame", t.frame},
                     {"t_s", static_cast<double>(t.frame) * dt},
                     {"from", parking::toString(t.from)},
                     {"to", parking::toString(t.to)},
                     {"event", parking::toString(t.event)},
                     {"c_px", t.c_px},
                     {"pose", poseJson(r.transition_poses[i])}});
  }
  j["trace"] = trace;
  j["seed"] = o.seed;
  j["controller"] = controllerJson(cp);
  j["camera_robot"] = cameraJson(camera.params(), robot);
  j["files"] = written;
  sylva_examples::writeResult(std::cout, o.json, "parking: one attempt of the hybrid parking controller (Amarasinghe 2008, Ch. 5)", j);
  return parked ? 0 : 3;
}

int runStudyMode(const Options& o,
                 const parking::StationCamera& camera,
                 const parking::ControllerParams& cp,
                 const parking::RobotParams& robot) {
  parking::StudyOptions so = o.study_options;
  so.seed = o.seed;
  so.max_time_s = o.max_time_s;
  parking::ControllerParams adaptive = cp;
  adaptive.adapt_c = true;
  parking::ControllerParams high = cp;  // Fig. 5.15(b): a high fixed c
  high.adapt_c = false;
  high.c_static_px = cp.c_max_px;
  parking::ControllerParams low = cp;  // Fig. 5.15(c): a low fixed c
  low.adapt_c = false;
  low.c_static_px = cp.c_min_px;
  const parking::StudyResult ra = parking::runStudy(camera, adaptive, robot, so);
  const parking::StudyResult rh = parking::runStudy(camera, high, robot, so);
  const parking::StudyResult rl = parking::runStudy(camera, low, robot, so);
  const parking::Pose goal = camera.goalPose(cp.reference_px);

  std::string svg_path;
  if (!o.svg_prefix.empty()) {
    svg_path = o.svg_prefix + "_study.svg";
    const auto& s = ra.summary;
    std::ostringstream l0, l1, l2, l3;
    l0 << so.runs << " random starts " << fixed(so.r_min_m, 2) << "-" << fixed(so.r_max_m, 2)
       << " m from P2, within +-" << fixed(so.max_angle_deg, 0) << " deg of the axis, heading "
       << "+-" << fixed(so.max_heading_offset_deg, 0) << " deg off P2, whole station in view";
    l1 << noiseLine(camera.params()) << "; seed " << o.seed;
    l2 << "adaptive c: " << s.parked << "/" << s.runs << " parked, spread +-"
       << fixed(100 * s.x_spread_m, 2) << " cm x, +-" << fixed(100 * s.y_spread_m, 2) << " cm y, "
       << fixed(s.mean_cycles, 2) << " cycles, " << fixed(s.mean_time_s, 1) << " s on average";
    const auto& h = rh.summary;
    l3 << "fixed c = " << fixed(cp.c_max_px, 0) << " px: " << h.parked << "/" << h.runs
       << " parked, spread +-" << fixed(100 * h.x_spread_m, 2) << " cm x, +-"
       << fixed(100 * h.y_spread_m, 2) << " cm y, " << fixed(h.mean_cycles, 2) << " cycles, "
       << fixed(h.mean_time_s, 1) << " s on average";
    parking::writeStudySvg(svg_path,
                           camera,
                           goal,
                           ra,
                           rh,
                           "fixed c = " + fixed(cp.c_max_px, 0) + " px (no adaptation)",
                           "Repeatability study: final parking positions",
                           {l0.str(), l1.str(), l2.str(), l3.str()});
  }

  nlohmann::json j = summaryJson(ra.summary);
  j["no_adaptation"] = summaryJson(rh.summary);
  j["no_adaptation"]["c_px"] = cp.c_max_px;
  j["static_c_min"] = summaryJson(rl.summary);
  j["static_c_min"]["c_px"] = cp.c_min_px;
  j["study"] = {{"runs", so.runs},
                {"seed", o.seed},
                {"r_min_m", so.r_min_m},
                {"r_max_m", so.r_max_m},
                {"max_angle_deg", so.max_angle_deg},
                {"max_heading_offset_deg", so.max_heading_offset_deg},
                {"margin_px", so.margin_px},
                {"max_time_s", so.max_time_s}};
  j["goal"] = poseJson(goal);
  j["controller"] = controllerJson(cp);
  j["camera_robot"] = cameraJson(camera.params(), robot);
  if (!svg_path.empty()) j["files"] = {svg_path};
  j["note"] = "spread: half of (max - min) of the final position error over the parked runs (the +- of Fig. 5.16)";
  sylva_examples::writeResult(std::cout, o.json,
                              "parking --study: random starts, the adaptive virtual edge c against two fixed ones", j);
  return 0;
}


}  // namespace

using sylva_examples::finite;

int main(int argc, char** argv) {
  Options o;
  parking::CameraParams camera_params;
  parking::ControllerParams cp;
  parking::RobotParams robot;
  CLI::App app{
      "Vision-based hybrid parking controller (Amarasinghe 2008, Ch. 5) on a simulated "
      "unicycle robot with a camera; prints the FSM trace, cycles, parking time and final "
      "pose error, and writes SVGs of the path and of the feature positions."};
  app.option_defaults()->always_capture_default();  // every option shows its default in --help
  app.footer(
      "World: station features at x = -d, 0, d on the line y = 0, seen from y < 0; the goal is\n"
      "the pose from which the camera sees the reference positions exactly. Defaults follow\n"
      "Table 5.2 (reference [478, 695, 910] px in a 1392 px image, gains 0.25/0.1 deg/s per px,\n"
      "c_min 255 px, v_c 140 mm/s, v_r 100 mm/s, delta 1.5 px) and Fig. 5.15 (c_max 470 px);\n"
      "the rest are this example's choices (docs/examples/parking.md). Exit status: 0 parked,\n"
      "3 not parked (station lost, timed out, bumped), 1 bad input. --study always exits 0.");
  const auto ok = finite(false);
  const auto pos = finite(true);
  const auto nonneg = finite(true, true);
  app.add_option("--seed", o.seed, "seed of the pixel noise (and of the study's starts)");
  app.add_option("--start-x", o.start_x_m, "start x (m), lateral")->check(ok);
  app.add_option("--start-y", o.start_y_m, "start y (m), < 0: in front of the station")->check(ok);
  app.add_option("--start-heading", o.start_heading_deg, "start heading (deg), 90: facing it")
      ->check(ok);
  app.add_option("--noise", camera_params.sigma_px, "pixel noise sigma (px)")->check(nonneg);
  app.add_option("--fps", camera_params.frame_rate_hz, "frame rate (frames/s)")->check(pos);
  app.add_option("--focal", camera_params.focal_px, "focal length lambda p (px)")->check(pos);
  app.add_option("--spacing", camera_params.spacing_m, "feature spacing d (m)")->check(pos);
  app.add_option("--k1", o.k1_degps_per_px, "Start/Reverse turn gain (deg/s per px)")->check(pos);
  app.add_option("--k2", o.k2_degps_per_px, "Forward turn gain (deg/s per px)")->check(pos);
  app.add_option("--c-min", cp.c_min_px, "smallest virtual edge c_min (px)")->check(ok);
  app.add_option("--c-max", cp.c_max_px, "largest virtual edge c_max (px)")->check(ok);
  app.add_option("--c-gain", cp.c_gain, "k_s k of eq. 5.9 (px of c per px of asymmetry)")
      ->check(ok);
  app.add_flag("--no-adapt",
               o.no_adapt,
               "fixed virtual edge --c-static instead of eq. 5.9 (one attempt; --study always "
               "runs adaptive, fixed c_max and fixed c_min)");
  app.add_option("--c-static", cp.c_static_px, "the fixed virtual edge with --no-adapt (px)")
      ->check(ok);
  app.add_flag("--raw-asymmetry",
               o.raw_asymmetry,
               "thesis as printed: side and c from the raw f1 - f2 (default: scaled to the "
               "reference size, relative to the reference)");
  app.add_flag(
      "--thesis-forward-exit",
      o.thesis_forward_exit,
      "end a forward move only on the uncontrolled feature (default: also when A >= W - 2c)");
  app.add_option("--start-exit-frames",
                 cp.start_exit_frames,
                 "frames Start averages f1, f2, E_A over once aligned (thesis: 1)");
  app.add_option(
         "--parked-frames", cp.parked_frames, "consecutive frames eq. 5.1 must hold (thesis: 1)");
  app.add_option("--A-min", cp.A_min_px, "reverse until the station is narrower (px)")->check(ok);
  app.add_option("--v-forward", cp.v_forward_mps, "forward speed v_c (m/s)")->check(ok);
  app.add_option("--v-reverse", cp.v_reverse_mps, "reverse speed v_r (m/s)")->check(ok);
  app.add_option("--v-slow", cp.v_reverse_slow_mps, "reverse speed near the goal (m/s)")->check(ok);
  app.add_option("--delta-u", cp.delta_u_px, "parking threshold on e1..e3 (px)")->check(ok);
  app.add_option("--delta-a", cp.delta_A_px, "parking threshold on E_A (px)")->check(ok);
  app.add_option("--max-omega", o.max_omega_degps, "turn-rate limit (deg/s)")->check(pos);
  double alpha_degps2 = robot.max_alpha_radps2 / kRadPerDeg;
  app.add_option("--accel", robot.max_accel_mps2, "robot acceleration limit (m/s^2, 0: none)")
      ->check(nonneg);
  app.add_option("--alpha", alpha_degps2, "robot turn acceleration limit (deg/s^2, 0: none)")
      ->check(nonneg);
  app.add_option("--bump",
                 robot.front_m,
                 "end as bumped when the robot centre comes this close to the station line "
                 "(m, 0: off)")
      ->check(nonneg);
  app.add_option("--max-time", o.max_time_s, "give up after this many seconds")->check(pos);
  app.add_flag("--json", o.json, "print one JSON object instead of text");
  app.add_option("--svg-prefix",
                 o.svg_prefix,
                 "write <prefix>_path.svg and <prefix>_features.svg (--study: <prefix>_study.svg); "
                 "\"\" for none");
  app.add_option("--csv", o.csv, "per-frame CSV of the run (pose, u, commands, state)");
  app.add_flag("--study", o.study, "run the repeatability study instead of one attempt");
  app.add_option("--runs", o.study_options.runs, "study: number of random starts");
  app.add_option("--study-r-min", o.study_options.r_min_m, "study: nearest start to P2 (m)")
      ->check(ok);
  app.add_option("--study-r-max", o.study_options.r_max_m, "study: farthest start from P2 (m)")
      ->check(ok);
  app.add_option("--study-angle",
                 o.study_options.max_angle_deg,
                 "study: largest polar angle of a start from the axis (deg)")
      ->check(ok);
  app.add_option("--study-heading",
                 o.study_options.max_heading_offset_deg,
                 "study: largest heading offset from P2 (deg)")
      ->check(ok);
  CLI11_PARSE(app, argc, argv);

  try {
    cp.k1_radps_per_px = o.k1_degps_per_px * kRadPerDeg;
    cp.k2_radps_per_px = o.k2_degps_per_px * kRadPerDeg;
    cp.max_omega_radps = o.max_omega_degps * kRadPerDeg;
    cp.adapt_c = !o.no_adapt;
    cp.scaled_asymmetry = !o.raw_asymmetry;
    cp.exit_on_width = !o.thesis_forward_exit;
    robot.max_alpha_radps2 = alpha_degps2 * kRadPerDeg;
    cp.image_width_px = camera_params.image_width_px;
    cp.validate();
    robot.validate();
    const parking::StationCamera camera(camera_params);
    if (o.study) return runStudyMode(o, camera, cp, robot);
    return runOne(o, camera, cp, robot);
  } catch (const sylva::Error& e) {
    std::cerr << "parking: " << e.what() << "\n";
    return 1;
  }
}
