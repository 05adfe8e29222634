#pragma once
// The parking example's pictures, after the thesis' figures:
//   writePathSvg      the robot's path in the x-y plane, coloured by FSM state (Fig. 5.12a)
//   writeFeaturesSvg  u1, u2, u3 over time with the reference and the virtual edge, and the
//                     commanded and actual v and omega (Fig. 5.12b, d, e)
//   writeStudySvg     the study's starts and final positions (Fig. 5.15, 5.16)
// Drawn with examples/common/svg_plot.hpp.

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "../common/svg_plot.hpp"
#include "episode.hpp"
#include "study.hpp"

namespace parking {

namespace svg = sylva_examples::svg;

namespace figures_detail {

struct StateStyle {
  const char* line;
  const char* band;
};

inline StateStyle styleOf(State s) {
  switch (s) {
    case State::kStart:
      return {"#7f7f7f", "#ededed"};
    case State::kForward:
      return {"#1f77b4", "#e2edf7"};
    case State::kReverse:
      return {"#d62728", "#f9e3e3"};
    case State::kStop:
      return {"#000000", "#ffffff"};
    case State::kLost:
      return {"#9467bd", "#ffffff"};
  }
  return {"#000000", "#ffffff"};
}

/// Page y below the title and its lines.
inline double titled(svg::Document& doc,
                     const std::string& title,
                     const std::vector<std::string>& lines) {
  return svg::header(doc, 20, title, lines) + 16;
}

/// Axes whose ticks are about `x_ticks` and `y_ticks` round steps apart.
inline svg::Axes axesWith(const svg::Frame& f,
                          std::string x_label,
                          std::string y_label,
                          double x_ticks,
                          double y_ticks,
                          bool x_numbers = true) {
  svg::Axes a{std::move(x_label),
              std::move(y_label),
              svg::niceStep(f.world.width(), x_ticks),
              svg::niceStep(f.world.height(), y_ticks)};
  a.x_numbers = x_numbers;
  return a;
}

/// (x, y) of a pose, in a frame's world coordinates.
inline svg::Point at(const Pose& p) { return svg::Point(p[0], p[1]); }

/// A legend row's swatch: a line of `style`.
inline std::string lineOf(const std::string& style) { return svg::swatch::line(style); }
/// A legend row's swatch: a marker (circle) of `style`.
inline std::string markerOf(const std::string& style) { return svg::swatch::dot(3.5, style); }

/// The station (wall, features P1-P3) in a top-view frame.
inline void drawStation(svg::Document& doc,
                        const svg::Frame& f,
                        const StationCamera& camera,
                        bool labels) {
  doc.line(f.left, f.py(0.0), f.right(), f.py(0.0), "stroke=\"#bbbbbb\" stroke-width=\"3\"");
  for (int i = 0; i < 3; ++i) {
    const auto p = camera.feature(i);
    doc.rect(f.px(p.x()) - 4, f.py(p.y()) - 4, 8, 8, "fill=\"black\"");
    if (labels)
      doc.text(f.px(p.x()),
               f.py(p.y()) - 9,
               "P" + std::to_string(i + 1),
               "text-anchor=\"middle\" font-size=\"11\"");
  }
}

}  // namespace figures_detail

/// Top view of one episode (needs recorded samples).
inline void writePathSvg(const std::string& path,
                         const EpisodeResult& r,
                         const StationCamera& camera,
                         const std::string& title,
                         const std::vector<std::string>& lines) {
  using namespace figures_detail;
  double x0 = -camera.params().spacing_m, x1 = camera.params().spacing_m;
  double y0 = std::min(r.goal[1], r.final_pose[1]), y1 = 0.0;
  for (const Sample& s : r.samples) {
    x0 = std::min(x0, s.pose[0]), x1 = std::max(x1, s.pose[0]);
    y0 = std::min(y0, s.pose[1]), y1 = std::max(y1, s.pose[1]);
  }
  const double pad = 0.08;
  x0 -= pad, x1 += pad, y0 -= pad, y1 += 0.06;
  // A mostly straight path would give a sliver: keep the width at least 0.7 of the height.
  const double min_width = 0.7 * (y1 - y0);
  if (x1 - x0 < min_width) {
    const double mid = 0.5 * (x0 + x1);
    x0 = mid - 0.5 * min_width, x1 = mid + 0.5 * min_width;
  }
  svg::Document doc(0, 0, 2, 12);
  const svg::Box world{x0, y0, x1, y1};
  const svg::Frame f =
      svg::mapFrame(world, 70, titled(doc, title, lines), 520.0 / std::max(x1 - x0, y1 - y0));
  // Inset: the final approach, +-6 cm around the goal.
  const svg::Box near_goal{r.goal[0] - 0.06, r.goal[1] - 0.03, r.goal[0] + 0.06, r.goal[1] + 0.03};
  const svg::Frame g = svg::chartFrame(near_goal, f.right() + 90, f.top, 240, 120);

  svg::axes(doc, f, axesWith(f, "x (m), lateral", "y (m), towards the station", 8, 6));
  drawStation(doc, f, camera, true);
  doc.line(f.px(0.0), f.top, f.px(0.0), f.bottom(), "stroke=\"#999\" stroke-dasharray=\"5,4\"");
  const auto stateLine = [](State s) {
    return std::string("stroke=\"") + styleOf(s).line + "\" stroke-width=\"2\"";
  };
  // Path, one polyline per state interval (each joined to the next interval's first point).
  for (std::size_t i = 0; i < r.samples.size();) {
    std::size_t j = i;
    std::vector<svg::Point> points;
    for (; j < r.samples.size() && r.samples[j].state == r.samples[i].state; ++j)
      points.push_back(at(r.samples[j].pose));
    points.push_back(j < r.samples.size() ? at(r.samples[j].pose) : at(r.final_pose));
    doc.polyline(f, points, stateLine(r.samples[i].state));
    i = j;
  }
  for (const Transition& t : r.transitions) {
    if (t.frame < 0 || static_cast<std::size_t>(t.frame) >= r.samples.size()) continue;
    const Pose& p = r.samples[static_cast<std::size_t>(t.frame)].pose;
    doc.circle(f.px(p[0]), f.py(p[1]), 3, "fill=\"white\" stroke=\"#333\"");
  }
  doc.arrow(f.px(r.start[0]),
            f.py(r.start[1]),
            r.start[2],
            16,
            "fill=\"white\" stroke=\"black\" stroke-width=\"1.5\"");
  doc.text(f.px(r.start[0]) + 12, f.py(r.start[1]) + 16, "start", "font-size=\"11\"");
  doc.arrow(f.px(r.goal[0]),
            f.py(r.goal[1]),
            r.goal[2],
            16,
            "fill=\"#2ca02c\" fill-opacity=\"0.6\" stroke=\"#2ca02c\"");
  doc.arrow(f.px(r.final_pose[0]), f.py(r.final_pose[1]), r.final_pose[2], 12, "fill=\"black\"");

  // Inset: the samples inside it, a break (NaN) where the path leaves it.
  svg::axes(doc, g, axesWith(g, "x (m)", "y (m)", 4, 3));
  doc.text(g.left, g.top - 8, "final approach (goal +- 6 cm)", "font-size=\"11\"");
  {
    std::vector<svg::Point> points;
    State last = State::kStart;
    for (const Sample& s : r.samples) {
      const bool inside = s.pose[0] > near_goal.x0 && s.pose[0] < near_goal.x1 &&
                          s.pose[1] > near_goal.y0 && s.pose[1] < near_goal.y1;
      if (s.state != last && !points.empty()) {
        doc.polyline(g, points, stateLine(last));
        points.clear();
      }
      last = s.state;
      points.push_back(inside ? at(s.pose)
                              : svg::Point(std::numeric_limits<double>::quiet_NaN(), 0.0));
    }
    points.push_back(at(r.final_pose));
    doc.polyline(g, points, stateLine(last));
  }
  doc.rect(g.px(r.goal[0] - 0.04),
           g.py(r.goal[1] + 0.005),
           0.08 * g.xScale(),
           0.01 * g.yScale(),
           "fill=\"none\" stroke=\"#2ca02c\" stroke-dasharray=\"4,3\"");
  doc.circle(g.px(r.goal[0]), g.py(r.goal[1]), 4, "fill=\"#2ca02c\"");
  doc.circle(g.px(r.final_pose[0]), g.py(r.final_pose[1]), 3.5, "fill=\"black\"");

  const double end = svg::legend(doc,
                                 g.left,
                                 g.bottom() + 50,
                                 {{lineOf(stateLine(State::kForward)), "Forward"},
                                  {lineOf(stateLine(State::kReverse)), "Reverse"},
                                  {lineOf(stateLine(State::kStart)), "Start (turning on the spot)"},
                                  {markerOf("fill=\"white\" stroke=\"#333\""), "state change"},
                                  {markerOf("fill=\"#2ca02c\""), "goal (reference view)"},
                                  {markerOf("fill=\"black\""), "final pose"},
                                  {lineOf("stroke=\"#2ca02c\" stroke-dasharray=\"4,3\""),
                                   "thesis repeatability +-4 cm x, +-0.5 cm y"}});
  doc.resize(std::max(g.left + 330, 760.0), std::max(f.bottom() + 50, end + 10));
  doc.write(path);
}

/// Feature positions and velocities over time (needs recorded samples).
inline void writeFeaturesSvg(const std::string& path,
                             const EpisodeResult& r,
                             const ControllerParams& params,
                             const std::string& title,
                             const std::vector<std::string>& lines) {
  using namespace figures_detail;
  const double T = r.samples.empty() ? 1.0 : std::max(r.samples.back().t_s, 1e-3);
  const double W = params.image_width_px;
  double v_max = 0.05, w_max = 5.0;
  for (const Sample& s : r.samples) {
    v_max = std::max({v_max, std::abs(s.v_cmd), std::abs(s.v)});
    w_max = std::max({w_max, std::abs(s.omega_cmd) / kRadPerDeg, std::abs(s.omega) / kRadPerDeg});
  }
  v_max *= 1.1, w_max *= 1.1;
  svg::Document doc(0, 0, 2, 12);
  const svg::Frame fu = svg::chartFrame({0, 0, T, W}, 80, titled(doc, title, lines), 640, 280);
  const svg::Frame fv = svg::chartFrame({0, -v_max, T, v_max}, 80, fu.bottom() + 30, 640, 120);
  const svg::Frame fw = svg::chartFrame({0, -w_max, T, w_max}, 80, fv.bottom() + 30, 640, 120);

  // State bands behind all three panels.
  for (std::size_t i = 0; i < r.samples.size();) {
    std::size_t j = i;
    while (j < r.samples.size() && r.samples[j].state == r.samples[i].state) ++j;
    const double t_a = r.samples[i].t_s;
    const double t_b = j < r.samples.size() ? r.samples[j].t_s : T;
    for (const svg::Frame* f : {&fu, &fv, &fw})
      doc.rect(f->px(t_a),
               f->top,
               std::max(f->px(t_b) - f->px(t_a), 0.5),
               f->height,
               std::string("fill=\"") + styleOf(r.samples[i].state).band + "\"");
    i = j;
  }
  svg::axes(doc, fu, axesWith(fu, "", "u (px)", 10, 7, false));
  svg::axes(doc, fv, axesWith(fv, "", "v (m/s)", 10, 4, false));
  svg::axes(doc, fw, axesWith(fw, "time (s)", "omega (deg/s)", 10, 4));

  const char* colours[3] = {"#1b9e77", "#d95f02", "#7570b3"};
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (std::size_t k = 0; k < 3; ++k) {
    const double u_ref = params.reference_px[k];
    doc.line(fu.px(0),
             fu.py(u_ref),
             fu.px(T),
             fu.py(u_ref),
             std::string("stroke=\"") + colours[k] + "\" stroke-dasharray=\"6,4\"");
    std::vector<svg::Point> points;
    for (const Sample& s : r.samples) points.emplace_back(s.t_s, s.u_px[k]);
    doc.polyline(fu, points, std::string("stroke=\"") + colours[k] + "\" stroke-width=\"1.6\"");
  }
  {  // the virtual edge the forward move holds its feature on
    std::vector<svg::Point> points;
    for (const Sample& s : r.samples)
      points.emplace_back(s.state == State::kForward ? s.t_s : nan,
                          s.holds_right ? W - s.c_px : s.c_px);
    doc.polyline(fu, points, "stroke=\"black\" stroke-width=\"1.2\" stroke-dasharray=\"2,2\"");
  }
  std::vector<svg::Point> v_cmd, v_act, w_cmd, w_act;
  for (const Sample& s : r.samples) {
    v_cmd.emplace_back(s.t_s, s.v_cmd);
    v_act.emplace_back(s.t_s, s.v);
    w_cmd.emplace_back(s.t_s, s.omega_cmd / kRadPerDeg);
    w_act.emplace_back(s.t_s, s.omega / kRadPerDeg);
  }
  const std::string commanded = "stroke=\"#444\" stroke-width=\"1.2\" stroke-dasharray=\"4,3\"";
  const std::string actual = "stroke=\"#000\" stroke-width=\"1.6\"";
  doc.polyline(fv, v_cmd, commanded);
  doc.polyline(fv, v_act, actual);
  doc.polyline(fw, w_cmd, commanded);
  doc.polyline(fw, w_act, actual);

  std::vector<svg::LegendEntry> features;
  for (std::size_t k = 0; k < 3; ++k)
    features.push_back({lineOf(std::string("stroke=\"") + colours[k] + "\" stroke-width=\"2\""),
                        "u" + std::to_string(k + 1)});
  features.push_back({lineOf("stroke=\"#555\" stroke-dasharray=\"6,4\""), "reference u_i^r"});
  features.push_back(
      {lineOf("stroke=\"black\" stroke-dasharray=\"2,2\""), "virtual edge (c or W - c)"});
  for (State s : {State::kStart, State::kForward, State::kReverse})
    features.push_back(
        {svg::swatch::box(std::string("fill=\"") + styleOf(s).band + "\" stroke=\"#bbb\""),
         toString(s)});
  svg::legend(doc, fu.right() + 20, fu.top + 4, features);
  svg::legend(doc,
              fv.right() + 20,
              fv.top + 4,
              {{lineOf(commanded), "commanded"}, {lineOf(actual), "actual"}});
  doc.resize(960, fw.bottom() + 60);
  doc.write(path);
}

/// Starts and final positions of a study, for two controller variants (Fig. 5.15/5.16).
inline void writeStudySvg(const std::string& path,
                          const StationCamera& camera,
                          const Pose& goal,
                          const StudyResult& adaptive,
                          const StudyResult& fixed_c,
                          const std::string& fixed_label,
                          const std::string& title,
                          const std::vector<std::string>& lines) {
  using namespace figures_detail;
  svg::Document doc(0, 0, 2, 12);
  const double top = titled(doc, title, lines) + 10;
  // Left: the starts in the x-y plane.
  double x0 = -0.2, x1 = 0.2, y0 = goal[1], y1 = 0.0;
  for (const StudyRun& r : adaptive.runs) {
    x0 = std::min(x0, r.start[0]), x1 = std::max(x1, r.start[0]);
    y0 = std::min(y0, r.start[1]);
  }
  x0 -= 0.1, x1 += 0.1, y0 -= 0.1, y1 += 0.05;
  const svg::Frame fs =
      svg::mapFrame({x0, y0, x1, y1}, 70, top, 360.0 / std::max(x1 - x0, y1 - y0));
  // Right: the final position errors in cm.
  double ex = 4.5, ey = 0.6;
  for (const StudyResult* s : {&adaptive, &fixed_c})
    for (const StudyRun& r : s->runs)
      if (r.outcome == Outcome::kParked) {
        ex = std::max(ex, 100.0 * std::abs(r.error[0]) * 1.1);
        ey = std::max(ey, 100.0 * std::abs(r.error[1]) * 1.1);
      }
  const svg::Frame fe = svg::chartFrame({-ex, -ey, ex, ey}, fs.right() + 110, top, 380, 300);

  svg::axes(doc, fs, axesWith(fs, "x (m)", "y (m)", 6, 6));
  doc.text(fs.left, fs.top - 8, "starts (one arrow per run)", "font-size=\"11\"");
  drawStation(doc, fs, camera, false);
  for (const StudyRun& r : adaptive.runs)
    doc.arrow(fs.px(r.start[0]),
              fs.py(r.start[1]),
              r.start[2],
              7,
              r.outcome == Outcome::kParked ? "fill=\"#1f77b4\" fill-opacity=\"0.7\""
                                            : "fill=\"#d62728\"");
  doc.circle(fs.px(goal[0]), fs.py(goal[1]), 4, "fill=\"#2ca02c\"");

  svg::axes(
      doc,
      fe,
      axesWith(fe, "final x error (cm), lateral", "final y error (cm), along the axis", 8, 6));
  doc.text(fe.left, fe.top - 8, "final positions relative to the goal", "font-size=\"11\"");
  doc.rect(fe.px(-4),
           fe.py(0.5),
           8 * fe.xScale(),
           1 * fe.yScale(),
           "fill=\"none\" stroke=\"#2ca02c\" stroke-width=\"1.5\" stroke-dasharray=\"5,3\"");
  for (const StudyRun& r : fixed_c.runs)
    if (r.outcome == Outcome::kParked)
      doc.circle(fe.px(100 * r.error[0]),
                 fe.py(100 * r.error[1]),
                 2.6,
                 "fill=\"none\" stroke=\"#ff7f0e\"");
  for (const StudyRun& r : adaptive.runs)
    if (r.outcome == Outcome::kParked)
      doc.circle(fe.px(100 * r.error[0]),
                 fe.py(100 * r.error[1]),
                 2.2,
                 "fill=\"#1f77b4\" fill-opacity=\"0.75\"");
  const double end_e = svg::legend(doc,
                                   fe.left,
                                   fe.bottom() + 45,
                                   {{markerOf("fill=\"#1f77b4\""), "adaptive c (eq. 5.9)"},
                                    {markerOf("fill=\"none\" stroke=\"#ff7f0e\""), fixed_label},
                                    {lineOf("stroke=\"#2ca02c\" stroke-dasharray=\"5,3\""),
                                     "thesis repeatability, +-4 cm x, +-0.5 cm y (Sec. 5.6)"}});
  const double end_s = svg::legend(doc,
                                   fs.left,
                                   fs.bottom() + 45,
                                   {{markerOf("fill=\"#1f77b4\""), "start, parked (adaptive c)"},
                                    {markerOf("fill=\"#d62728\""), "start, not parked"},
                                    {markerOf("fill=\"#2ca02c\""), "goal"}});
  doc.resize(fe.right() + 40, std::max(end_e, end_s) + 10);
  doc.write(path);
}

}  // namespace parking
