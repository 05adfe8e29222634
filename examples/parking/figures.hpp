#pragma once
// The parking example's pictures, after the thesis' figures:
//   writePathSvg      the robot's path in the x-y plane, coloured by FSM state (Fig. 5.12a)
//   writeFeaturesSvg  u1, u2, u3 over time with the reference and the virtual edge, and the
//                     commanded and actual v and omega (Fig. 5.12b, d, e)
//   writeStudySvg     the study's starts and final positions (Fig. 5.15, 5.16)

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "episode.hpp"
#include "study.hpp"
#include "svg.hpp"

namespace parking {

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

inline void titleLines(svg::Canvas& c,
                       const std::string& title,
                       const std::vector<std::string>& lines,
                       double x,
                       double y) {
  c.text(x, y, title, "font-size=\"15\" font-weight=\"bold\"");
  for (std::size_t i = 0; i < lines.size(); ++i)
    c.text(x, y + 18 + 15 * static_cast<double>(i), lines[i], "fill=\"#333\"");
}

/// The station (wall, features P1-P3) in a top-view frame.
inline void drawStation(svg::Canvas& c,
                        const svg::Frame& f,
                        const StationCamera& camera,
                        bool labels) {
  c.line(f.left, f.py(0.0), f.left + f.width, f.py(0.0), "stroke=\"#bbbbbb\" stroke-width=\"3\"");
  for (int i = 0; i < 3; ++i) {
    const auto p = camera.feature(i);
    c.rect(f.px(p.x()) - 4, f.py(p.y()) - 4, 8, 8, "fill=\"black\"");
    if (labels)
      c.text(f.px(p.x()),
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
  using figures_detail::styleOf;
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
  const double span = std::max(x1 - x0, y1 - y0);
  const double scale = 520.0 / span;  // px per metre, equal in x and y
  svg::Frame f;
  f.x0 = x0, f.x1 = x1, f.y0 = y0, f.y1 = y1;
  f.left = 70, f.top = 40 + 18 + 15.0 * static_cast<double>(lines.size()) + 10;
  f.width = (x1 - x0) * scale, f.height = (y1 - y0) * scale;
  // Inset: the final approach, +-6 cm around the goal.
  svg::Frame g;
  g.x0 = r.goal[0] - 0.06, g.x1 = r.goal[0] + 0.06;
  g.y0 = r.goal[1] - 0.03, g.y1 = r.goal[1] + 0.03;
  g.left = f.left + f.width + 90, g.top = f.top, g.width = 240, g.height = 120;
  const double page_w = std::max(g.left + 330, 760.0);  // room for the legend text
  const double page_h = std::max(f.top + f.height + 50, g.top + g.height + 260);
  svg::Canvas c(page_w, page_h);
  figures_detail::titleLines(c, title, lines, 20, 26);
  svg::axes(c, f, "x (m), lateral", "y (m), towards the station");
  figures_detail::drawStation(c, f, camera, true);
  c.line(f.px(0.0),
         f.top,
         f.px(0.0),
         f.top + f.height,
         "stroke=\"#999\" stroke-width=\"1\" stroke-dasharray=\"5,4\"");
  // Path, one polyline per state interval (each joined to the next interval's first point).
  for (std::size_t i = 0; i < r.samples.size();) {
    std::size_t j = i;
    svg::Points pts;
    while (j < r.samples.size() && r.samples[j].state == r.samples[i].state) {
      pts.emplace_back(r.samples[j].pose[0], r.samples[j].pose[1]);
      ++j;
    }
    if (j < r.samples.size())
      pts.emplace_back(r.samples[j].pose[0], r.samples[j].pose[1]);
    else
      pts.emplace_back(r.final_pose[0], r.final_pose[1]);
    c.polyline(
        f,
        pts,
        std::string("stroke=\"") + styleOf(r.samples[i].state).line + "\" stroke-width=\"2\"");
    i = j;
  }
  for (const Transition& t : r.transitions) {
    if (t.frame < 0 || static_cast<std::size_t>(t.frame) >= r.samples.size()) continue;
    const Pose& p = r.samples[static_cast<std::size_t>(t.frame)].pose;
    c.circle(f.px(p[0]), f.py(p[1]), 3, "fill=\"white\" stroke=\"#333\" stroke-width=\"1\"");
  }
  c.arrowhead(f,
              r.start[0],
              r.start[1],
              r.start[2],
              16,
              "fill=\"white\" stroke=\"black\" stroke-width=\"1.5\"");
  c.text(f.px(r.start[0]) + 12, f.py(r.start[1]) + 16, "start", "font-size=\"11\"");
  c.arrowhead(f,
              r.goal[0],
              r.goal[1],
              r.goal[2],
              16,
              "fill=\"#2ca02c\" fill-opacity=\"0.6\" stroke=\"#2ca02c\"");
  c.arrowhead(f, r.final_pose[0], r.final_pose[1], r.final_pose[2], 12, "fill=\"black\"");

  // Inset.
  svg::axes(c, g, "x (m)", "y (m)", 4, 3);
  c.text(g.left, g.top - 8, "final approach (goal +- 6 cm)", "font-size=\"11\"");
  {
    svg::Points pts;
    State last = State::kStart;
    for (const Sample& s : r.samples) {
      const bool inside =
          s.pose[0] > g.x0 && s.pose[0] < g.x1 && s.pose[1] > g.y0 && s.pose[1] < g.y1;
      if (s.state != last && !pts.empty()) {
        c.polyline(g, pts, std::string("stroke=\"") + styleOf(last).line + "\" stroke-width=\"2\"");
        pts.clear();
      }
      last = s.state;
      if (inside)
        pts.emplace_back(s.pose[0], s.pose[1]);
      else
        pts.emplace_back(std::numeric_limits<double>::quiet_NaN(), 0.0);
    }
    pts.emplace_back(r.final_pose[0], r.final_pose[1]);
    c.polyline(g, pts, std::string("stroke=\"") + styleOf(last).line + "\" stroke-width=\"2\"");
  }
  c.rect(g.px(r.goal[0] - 0.04),
         g.py(r.goal[1] + 0.005),
         g.px(0.04) - g.px(-0.04),
         g.py(-0.005) - g.py(0.005),
         "fill=\"none\" stroke=\"#2ca02c\" stroke-dasharray=\"4,3\"");
  c.circle(g.px(r.goal[0]), g.py(r.goal[1]), 4, "fill=\"#2ca02c\"");
  c.circle(g.px(r.final_pose[0]), g.py(r.final_pose[1]), 3.5, "fill=\"black\"");

  double ly = g.top + g.height + 60;
  const double lx = g.left;
  ly = svg::legendEntry(c, lx, ly, "stroke=\"#1f77b4\" stroke-width=\"2\"", "Forward");
  ly = svg::legendEntry(c, lx, ly, "stroke=\"#d62728\" stroke-width=\"2\"", "Reverse");
  ly = svg::legendEntry(
      c, lx, ly, "stroke=\"#7f7f7f\" stroke-width=\"2\"", "Start (turning on the spot)");
  ly = svg::legendEntry(c, lx, ly, "fill=\"white\" stroke=\"#333\"", "state change", true);
  ly = svg::legendEntry(c, lx, ly, "fill=\"#2ca02c\"", "goal (reference view)", true);
  ly = svg::legendEntry(c, lx, ly, "fill=\"black\"", "final pose", true);
  svg::legendEntry(c,
                   lx,
                   ly,
                   "stroke=\"#2ca02c\" stroke-dasharray=\"4,3\"",
                   "thesis repeatability +-4 cm x, +-0.5 cm y");
  c.write(path);
}

/// Feature positions and velocities over time (needs recorded samples).
inline void writeFeaturesSvg(const std::string& path,
                             const EpisodeResult& r,
                             const ControllerParams& params,
                             const std::string& title,
                             const std::vector<std::string>& lines) {
  using figures_detail::styleOf;
  const double T = r.samples.empty() ? 1.0 : std::max(r.samples.back().t_s, 1e-3);
  const double W = params.image_width_px;
  const double top = 40 + 18 + 15.0 * static_cast<double>(lines.size()) + 10;
  svg::Frame fu{0, T, 0, W, 80, top, 640, 280};
  double v_max = 0.05, w_max = 5.0;
  for (const Sample& s : r.samples) {
    v_max = std::max({v_max, std::abs(s.v_cmd), std::abs(s.v)});
    w_max = std::max({w_max, std::abs(s.omega_cmd) / kRadPerDeg, std::abs(s.omega) / kRadPerDeg});
  }
  v_max *= 1.1, w_max *= 1.1;
  svg::Frame fv{0, T, -v_max, v_max, 80, fu.top + fu.height + 30, 640, 120};
  svg::Frame fw{0, T, -w_max, w_max, 80, fv.top + fv.height + 30, 640, 120};
  svg::Canvas c(960, fw.top + fw.height + 60);
  figures_detail::titleLines(c, title, lines, 20, 26);

  // State bands behind all three panels.
  for (std::size_t i = 0; i < r.samples.size();) {
    std::size_t j = i;
    while (j < r.samples.size() && r.samples[j].state == r.samples[i].state) ++j;
    const double t_a = r.samples[i].t_s;
    const double t_b = j < r.samples.size() ? r.samples[j].t_s : T;
    for (const svg::Frame* f : {&fu, &fv, &fw})
      c.rect(f->px(t_a),
             f->top,
             std::max(f->px(t_b) - f->px(t_a), 0.5),
             f->height,
             std::string("fill=\"") + styleOf(r.samples[i].state).band + "\"");
    i = j;
  }
  svg::axes(c, fu, "", "u (px)", 10, 7, false);
  svg::axes(c, fv, "", "v (m/s)", 10, 4, false);
  svg::axes(c, fw, "time (s)", "omega (deg/s)", 10, 4, true);

  const char* colours[3] = {"#1b9e77", "#d95f02", "#7570b3"};
  for (std::size_t k = 0; k < 3; ++k) {
    const double u_ref = params.reference_px[k];
    c.line(
        fu.px(0),
        fu.py(u_ref),
        fu.px(T),
        fu.py(u_ref),
        std::string("stroke=\"") + colours[k] + "\" stroke-dasharray=\"6,4\" stroke-width=\"1\"");
    svg::Points pts;
    for (const Sample& s : r.samples) pts.emplace_back(s.t_s, s.u_px[k]);
    c.polyline(fu, pts, std::string("stroke=\"") + colours[k] + "\" stroke-width=\"1.6\"");
  }
  {  // the virtual edge the forward move holds its feature on
    svg::Points pts;
    for (const Sample& s : r.samples) {
      if (s.state != State::kForward) {
        pts.emplace_back(std::numeric_limits<double>::quiet_NaN(), 0.0);
        continue;
      }
      pts.emplace_back(s.t_s, s.holds_right ? W - s.c_px : s.c_px);
    }
    c.polyline(fu, pts, "stroke=\"black\" stroke-width=\"1.2\" stroke-dasharray=\"2,2\"");
  }
  svg::Points v_cmd, v_act, w_cmd, w_act;
  for (const Sample& s : r.samples) {
    v_cmd.emplace_back(s.t_s, s.v_cmd);
    v_act.emplace_back(s.t_s, s.v);
    w_cmd.emplace_back(s.t_s, s.omega_cmd / kRadPerDeg);
    w_act.emplace_back(s.t_s, s.omega / kRadPerDeg);
  }
  c.polyline(fv, v_cmd, "stroke=\"#444\" stroke-width=\"1.2\" stroke-dasharray=\"4,3\"");
  c.polyline(fv, v_act, "stroke=\"#000\" stroke-width=\"1.6\"");
  c.polyline(fw, w_cmd, "stroke=\"#444\" stroke-width=\"1.2\" stroke-dasharray=\"4,3\"");
  c.polyline(fw, w_act, "stroke=\"#000\" stroke-width=\"1.6\"");

  const double lx = fu.left + fu.width + 20;
  double ly = fu.top + 10;
  for (std::size_t k = 0; k < 3; ++k)
    ly = svg::legendEntry(c,
                          lx,
                          ly,
                          std::string("stroke=\"") + colours[k] + "\" stroke-width=\"2\"",
                          "u" + std::to_string(k + 1));
  ly = svg::legendEntry(c, lx, ly, "stroke=\"#555\" stroke-dasharray=\"6,4\"", "reference u_i^r");
  ly = svg::legendEntry(
      c, lx, ly, "stroke=\"black\" stroke-dasharray=\"2,2\"", "virtual edge (c or W - c)");
  ly += 8;
  for (State s : {State::kStart, State::kForward, State::kReverse}) {
    c.rect(lx, ly - 11, 22, 11, std::string("fill=\"") + styleOf(s).band + "\" stroke=\"#bbb\"");
    c.text(lx + 28, ly, toString(s));
    ly += 17;
  }
  ly = fv.top + 10;
  ly = svg::legendEntry(c, lx, ly, "stroke=\"#444\" stroke-dasharray=\"4,3\"", "commanded");
  svg::legendEntry(c, lx, ly, "stroke=\"#000\" stroke-width=\"1.6\"", "actual");
  c.write(path);
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
  const double top = 40 + 18 + 15.0 * static_cast<double>(lines.size()) + 20;
  // Left: the starts in the x-y plane.
  double x0 = -0.2, x1 = 0.2, y0 = goal[1], y1 = 0.0;
  for (const StudyRun& r : adaptive.runs) {
    x0 = std::min(x0, r.start[0]), x1 = std::max(x1, r.start[0]);
    y0 = std::min(y0, r.start[1]);
  }
  x0 -= 0.1, x1 += 0.1, y0 -= 0.1, y1 += 0.05;
  const double scale = 360.0 / std::max(x1 - x0, y1 - y0);
  svg::Frame fs{x0, x1, y0, y1, 70, top, (x1 - x0) * scale, (y1 - y0) * scale};
  // Right: the final position errors in cm.
  double ex = 4.5, ey = 0.6;
  for (const StudyResult* s : {&adaptive, &fixed_c})
    for (const StudyRun& r : s->runs)
      if (r.outcome == Outcome::kParked) {
        ex = std::max(ex, 100.0 * std::abs(r.error[0]) * 1.1);
        ey = std::max(ey, 100.0 * std::abs(r.error[1]) * 1.1);
      }
  svg::Frame fe{-ex, ex, -ey, ey, fs.left + fs.width + 110, top, 380, 300};
  svg::Canvas c(fe.left + fe.width + 40, std::max(fs.top + fs.height, fe.top + fe.height) + 115);
  figures_detail::titleLines(c, title, lines, 20, 26);

  svg::axes(c, fs, "x (m)", "y (m)", 6, 6);
  c.text(fs.left, fs.top - 8, "starts (one arrow per run)", "font-size=\"11\"");
  figures_detail::drawStation(c, fs, camera, false);
  for (const StudyRun& r : adaptive.runs)
    c.arrowhead(fs,
                r.start[0],
                r.start[1],
                r.start[2],
                7,
                r.outcome == Outcome::kParked ? "fill=\"#1f77b4\" fill-opacity=\"0.7\""
                                              : "fill=\"#d62728\"");
  c.circle(fs.px(goal[0]), fs.py(goal[1]), 4, "fill=\"#2ca02c\"");

  svg::axes(c, fe, "final x error (cm), lateral", "final y error (cm), along the axis", 8, 6);
  c.text(fe.left, fe.top - 8, "final positions relative to the goal", "font-size=\"11\"");
  c.rect(fe.px(-4),
         fe.py(0.5),
         fe.px(4) - fe.px(-4),
         fe.py(-0.5) - fe.py(0.5),
         "fill=\"none\" stroke=\"#2ca02c\" stroke-width=\"1.5\" stroke-dasharray=\"5,3\"");
  for (const StudyRun& r : fixed_c.runs)
    if (r.outcome == Outcome::kParked)
      c.circle(fe.px(100 * r.error[0]),
               fe.py(100 * r.error[1]),
               2.6,
               "fill=\"none\" stroke=\"#ff7f0e\" stroke-width=\"1\"");
  for (const StudyRun& r : adaptive.runs)
    if (r.outcome == Outcome::kParked)
      c.circle(fe.px(100 * r.error[0]),
               fe.py(100 * r.error[1]),
               2.2,
               "fill=\"#1f77b4\" fill-opacity=\"0.75\"");
  double ly = fe.top + fe.height + 55;
  ly = svg::legendEntry(c, fe.left, ly, "fill=\"#1f77b4\"", "adaptive c (eq. 5.9)", true);
  ly = svg::legendEntry(c, fe.left, ly, "fill=\"none\" stroke=\"#ff7f0e\"", fixed_label, true);
  svg::legendEntry(c,
                   fe.left,
                   ly,
                   "stroke=\"#2ca02c\" stroke-dasharray=\"5,3\"",
                   "thesis repeatability, +-4 cm x, +-0.5 cm y (Sec. 5.6)");
  double ls = fs.top + fs.height + 55;
  ls = svg::legendEntry(c, fs.left, ls, "fill=\"#1f77b4\"", "start, parked (adaptive c)", true);
  ls = svg::legendEntry(c, fs.left, ls, "fill=\"#d62728\"", "start, not parked", true);
  svg::legendEntry(c, fs.left, ls, "fill=\"#2ca02c\"", "goal", true);
  c.write(path);
}

}  // namespace parking
