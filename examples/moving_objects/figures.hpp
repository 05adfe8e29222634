#pragma once
// The four pictures of the moving_objects program, drawn with examples/common/svg_plot.hpp:
//
//   writeSceneSvg  the default scene like the thesis' Fig. 4.9: every scan's readings in the
//                  world frame, detected objects as bounding boxes, the torso estimates
//                  (two legs detected together) as stars, the people tracks, the robot path;
//   writeCasesSvg  the five cases of Sec. 4.3.4, one panel each: previous and current scan,
//                  the readings of the detected object and its bounding box;
//   writeSlamSvg   the SLAM maps without and with moving-object removal side by side;
//   writeBeamTimeSvg  real data: range per beam (vertical) over time (horizontal), grey
//                  levels, with the detected moving readings in red.

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <sylva/core/angles.hpp>
#include <sylva/core/types.hpp>
#include <sylva/laser/object_position.hpp>

#include "../common/svg_plot.hpp"

namespace moving_objects::svg {

namespace plot = sylva_examples::svg;
using sylva::Vec;

namespace detail {

/// A world box as a rectangle, at least one pixel wide and high.
inline void box(plot::Document& doc,
                const plot::Frame& f,
                const Box2& b,
                const std::string& attrs) {
  doc.rect(f.px(b.min.x()),
           f.py(b.max.y()),
           std::max(1.0, (b.max.x() - b.min.x()) * f.xScale()),
           std::max(1.0, (b.max.y() - b.min.y()) * f.yScale()),
           attrs);
}

/// A five-pointed star around a world point, `r_px` from the centre to a tip.
inline void star(plot::Document& doc,
                 const plot::Frame& f,
                 const Vec<2>& c,
                 double r_px,
                 const std::string& attrs) {
  std::vector<plot::Point> corners;
  for (int k = 0; k < 10; ++k) {
    const double a = -sylva::kPi / 2 + k * sylva::kPi / 5;
    const double r = (k % 2 == 0) ? r_px : 0.45 * r_px;
    corners.emplace_back(f.px(c.x()) + r * std::cos(a), f.py(c.y()) + r * std::sin(a));
  }
  doc.polygon(corners, attrs);
}

constexpr const char* kStarSwatch =
    "<polygon points=\"12,0 14,4.5 18.5,4.5 15,7.5 16.5,12 12,9 7.5,12 9,7.5 5.5,4.5 10,4.5\" "
    "fill=\"black\"/>";

}  // namespace detail

struct SceneFigure {
  std::string title;
  std::vector<std::string> subtitle;
  std::vector<std::vector<Vec<2>>> walls;
  std::vector<std::pair<Vec<2>, double>> pillars;
  std::vector<Vec<2>> scan_points;              ///< every reading of every scan (world)
  std::vector<Vec<2>> moving_points;            ///< readings reported moving
  std::vector<Box2> boxes;                      ///< every detected object
  std::vector<Vec<2>> torsos;                   ///< two-leg groups
  std::vector<std::vector<Vec<2>>> tracks;      ///< confirmed tracks
  std::vector<std::vector<Vec<2>>> true_paths;  ///< people's true body paths
  std::vector<Vec<2>> robot_path;
  double x0, y0, x1, y1;
};

inline void writeSceneSvg(const std::string& path, const SceneFigure& f) {
  const double width = 1000, left = 50, legend_w = 230;
  plot::Document doc(width, 0, 1, 12);
  const double top = plot::header(doc, left, f.title, f.subtitle) + 12;
  const plot::Frame v =
      plot::fitMap({f.x0, f.y0, f.x1, f.y1}, left, top, width - left - legend_w - 30, 700);
  plot::axes(doc, v, {"", "", 1.0, 1.0});
  for (const auto& w : f.walls) doc.polyline(v, w, "stroke=\"#444\" stroke-width=\"2\"");
  for (const auto& [c, r] : f.pillars)
    doc.circle(v.px(c.x()),
               v.py(c.y()),
               r * v.xScale(),
               "fill=\"none\" stroke=\"#444\" stroke-width=\"1.5\"");
  for (const auto& p : f.true_paths)
    doc.polyline(v, p, "stroke=\"#f4a261\" stroke-width=\"1.5\" stroke-dasharray=\"5,4\"");
  doc.dots(v, f.scan_points, "#b5b5b5", 2.0);
  doc.dots(v, f.moving_points, "#d62828", 2.6);
  for (const Box2& b : f.boxes) detail::box(doc, v, b, "fill=\"none\" stroke=\"#1d4ed8\"");
  for (const auto& t : f.tracks) doc.polyline(v, t, "stroke=\"#2a9d8f\" stroke-width=\"1.5\"");
  for (const Vec<2>& s : f.torsos) detail::star(doc, v, s, 6.0, "fill=\"black\"");
  doc.polyline(v, f.robot_path, "stroke=\"#16a34a\" stroke-width=\"3\"");
  if (!f.robot_path.empty())
    doc.circle(v.px(f.robot_path.back().x()), v.py(f.robot_path.back().y()), 5, "fill=\"#16a34a\"");
  plot::legend(
      doc,
      width - legend_w,
      top + 4,
      {{plot::swatch::dot(2, "fill=\"#b5b5b5\""), "laser readings, all scans"},
       {plot::swatch::dot(2.5, "fill=\"#d62828\""), "readings detected moving"},
       {plot::swatch::box("fill=\"none\" stroke=\"#1d4ed8\""), "detected object (box)"},
       {detail::kStarSwatch, "torso: two legs detected"},
       {plot::swatch::line("stroke=\"#2a9d8f\" stroke-width=\"1.5\""), "track of torso/leg groups"},
       {plot::swatch::line("stroke=\"#f4a261\" stroke-width=\"1.5\" stroke-dasharray=\"5,4\""),
        "true walking routes"},
       {plot::swatch::line("stroke=\"#16a34a\" stroke-width=\"3\""), "robot path"},
       {plot::swatch::line("stroke=\"#444\" stroke-width=\"2\""), "walls, pillars (truth)"}});
  doc.resize(width, v.bottom() + 50);
  doc.write(path);
}

struct CasePanel {
  std::string title;
  std::string result;
  std::vector<Vec<2>> previous_points, current_points, detected_points;
  std::vector<Box2> boxes;
  double x0, y0, x1, y1;
};

inline void writeCasesSvg(const std::string& path,
                          const std::string& title,
                          const std::vector<CasePanel>& panels) {
  const double panel_w = 300, panel_h = 300, gap = 30, left = 40;
  const double width = left + static_cast<double>(panels.size()) * (panel_w + gap);
  plot::Document doc(width, 0, 1, 12);
  const double top = plot::header(doc, left, title, {}) + 24;
  double bottom = top;
  for (std::size_t i = 0; i < panels.size(); ++i) {
    const CasePanel& p = panels[i];
    const plot::Frame v =
        plot::fitMap({p.x0, p.y0, p.x1, p.y1}, left + i * (panel_w + gap), top, panel_w, panel_h);
    doc.text(v.left, top - 10, p.title, "font-size=\"13\" font-weight=\"bold\"");
    plot::axes(doc, v, {"", "", 0.5, 0.5});
    doc.dots(v, p.previous_points, "#9ca3af", 5.0);
    doc.dots(v, p.current_points, "#111", 2.5);
    doc.dots(v, p.detected_points, "#d62828", 4.0);
    for (const Box2& b : p.boxes)
      detail::box(doc, v, b, "fill=\"none\" stroke=\"#1d4ed8\" stroke-width=\"1.5\"");
    doc.text(v.left, v.bottom() + 32, p.result);
    bottom = std::max(bottom, v.bottom() + 32);
  }
  const double end =
      plot::legend(doc,
                   left,
                   bottom + 20,
                   {{plot::swatch::dot(2.5, "fill=\"#9ca3af\""), "previous scan"},
                    {plot::swatch::dot(1.5, "fill=\"#111\""), "current scan"},
                    {plot::swatch::dot(2, "fill=\"#d62828\""), "readings of the detected object"},
                    {plot::swatch::box("fill=\"none\" stroke=\"#1d4ed8\""), "bounding box"},
                    {"", "scanner at the origin looking along +x; grid 0.5 m"}},
                   width - left);
  doc.resize(width, end + 10);
  doc.write(path);
}

struct SlamPanel {
  std::string title;
  std::vector<Vec<2>> estimated_path;
  std::vector<Vec<2>> pole_landmarks;      ///< estimates born on poles
  std::vector<Vec<2>> spurious_landmarks;  ///< estimates born on legs
};

struct SlamFigure {
  std::string title;
  std::vector<std::string> subtitle;
  std::vector<std::vector<Vec<2>>> walls;
  std::vector<Vec<2>> poles;
  std::vector<Vec<2>> true_path;
  std::vector<std::pair<Vec<2>, Vec<2>>> routes;
  std::vector<SlamPanel> panels;
  double x0, y0, x1, y1;
};

inline void writeSlamSvg(const std::string& path, const SlamFigure& f) {
  const double gap = 40, left = 40;
  const double panel_w = f.panels.size() > 2 ? 460 : 620;
  const double width = left + static_cast<double>(f.panels.size()) * (panel_w + gap);
  plot::Document doc(width, 0, 1, 12);
  const double top = plot::header(doc, left, f.title, f.subtitle) + 30;
  double bottom = top;
  for (std::size_t i = 0; i < f.panels.size(); ++i) {
    const plot::Frame v =
        plot::fitMap({f.x0, f.y0, f.x1, f.y1}, left + i * (panel_w + gap), top, panel_w, 600);
    const SlamPanel& p = f.panels[i];
    doc.text(v.left, top - 10, p.title, "font-size=\"13\" font-weight=\"bold\"");
    plot::axes(doc, v, {"", "", 2.0, 2.0});
    for (const auto& [a, b] : f.routes)
      doc.segment(v, a, b, "stroke=\"#f4a261\" stroke-width=\"5\" stroke-opacity=\"0.35\"");
    doc.polyline(v, f.true_path, "stroke=\"#111\" stroke-width=\"1.2\"");
    doc.polyline(
        v, p.estimated_path, "stroke=\"#1d4ed8\" stroke-width=\"1.2\" stroke-dasharray=\"4,3\"");
    for (const Vec<2>& pole : f.poles)
      doc.circle(v.px(pole.x()),
                 v.py(pole.y()),
                 4.5,
                 "fill=\"none\" stroke=\"#111\" stroke-width=\"1.3\"");
    for (const Vec<2>& l : p.pole_landmarks)
      doc.circle(v.px(l.x()), v.py(l.y()), 1.8, "fill=\"#1d4ed8\"");
    for (const Vec<2>& l : p.spurious_landmarks)
      doc.cross(v.px(l.x()), v.py(l.y()), 2.5, "stroke=\"#d62828\" stroke-width=\"1.2\"");
    bottom = std::max(bottom, v.bottom());
  }
  const double end = plot::legend(
      doc,
      left,
      bottom + 36,
      {{plot::swatch::dot(4.5, "fill=\"none\" stroke=\"#111\" stroke-width=\"1.3\""), "true pole"},
       {plot::swatch::dot(1.8, "fill=\"#1d4ed8\""), "landmark from a pole (estimate)"},
       {plot::swatch::cross("stroke=\"#d62828\" stroke-width=\"1.2\""),
        "spurious landmark (from a leg)"},
       {plot::swatch::line("stroke=\"#f4a261\" stroke-width=\"5\" stroke-opacity=\"0.35\""),
        "walking routes of the people"},
       {plot::swatch::line("stroke=\"#111\" stroke-width=\"1.2\""), "true path"},
       {plot::swatch::line("stroke=\"#1d4ed8\" stroke-width=\"1.2\" stroke-dasharray=\"4,3\""),
        "estimated path"}},
      width - left);
  doc.resize(width, end + 10);
  doc.write(path);
}

/// Real data: a beams x scans image of ranges (grey, dark = near) with detections in red.
struct BeamTimeFigure {
  std::string title;
  std::vector<std::string> subtitle;
  std::vector<double> times;                ///< per column (s from the first scan)
  std::vector<std::vector<double>> ranges;  ///< per column, per beam
  std::vector<std::vector<char>> detected;  ///< per column, per beam
  double range_max = 1.0;
  int beam_step = 1;  ///< beams per pixel row (the nearest is drawn)
};

inline void writeBeamTimeSvg(const std::string& path, const BeamTimeFigure& f) {
  const std::size_t columns = f.ranges.size();
  const std::size_t beams = columns ? f.ranges.front().size() : 0;
  const auto step = static_cast<std::size_t>(f.beam_step);
  const std::size_t rows = (beams + step - 1) / step;
  const double left = 70;  // one pixel per column and per row
  plot::Document doc(left + static_cast<double>(columns) + 40, 0, 1, 12);
  const double top = plot::header(doc, left, f.title, f.subtitle) + 12;
  const double bottom = top + static_cast<double>(rows);
  // Grey levels 0..4 (near dark .. far light), 5 no return (not drawn), 6 invalid (NaN).
  constexpr int kLevels = 5, kNoReturn = 5, kInvalid = 6;
  const auto level = [&](double r) -> int {
    if (std::isnan(r)) return kInvalid;
    if (!(r <= f.range_max)) return kNoReturn;
    return std::clamp(static_cast<int>(r / f.range_max * kLevels), 0, kLevels - 1);
  };
  const char* colours[] = {
      "#2b2b2b", "#555555", "#7f7f7f", "#a5a5a5", "#c8c8c8", "#ffffff", "#f2c94c"};
  // Row r shows beam (beams - 1 - r * step), the leftmost beam (largest angle) on top; a row
  // is detected when any beam it stands for is. Each colour is one <path> of horizontal runs
  // one pixel high: `runs` adds the runs of columns for which `key` gives the same value.
  std::vector<std::string> level_runs(7);
  std::string detected_runs;
  const auto runs = [&](const std::string& y, auto key, auto&& add) {
    for (std::size_t c = 0; c < columns;) {
      std::size_t e = c + 1;
      while (e < columns && key(e) == key(c)) ++e;
      add(key(c),
          "M" + doc.n(left + static_cast<double>(c)) + "," + y + "h" +
              doc.n(static_cast<double>(e - c)));
      c = e;
    }
  };
  for (std::size_t r = 0; r < rows; ++r) {
    const std::size_t beam = beams - 1 - std::min(beams - 1, r * step);
    const std::string y = doc.n(top + static_cast<double>(r) + 0.5);
    runs(
        y,
        [&](std::size_t c) { return level(f.ranges[c][beam]); },
        [&](int l, const std::string& run) {
          if (l != kNoReturn) level_runs[static_cast<std::size_t>(l)] += run;
        });
    const auto hit = [&](std::size_t c) {
      for (std::size_t k = 0; k < step && k <= beam; ++k)
        if (f.detected[c][beam - k]) return true;
      return false;
    };
    runs(y, hit, [&](bool h, const std::string& run) {
      if (h) detected_runs += run;
    });
  }
  doc.group("fill=\"none\" shape-rendering=\"crispEdges\"");
  for (std::size_t l = 0; l < level_runs.size(); ++l)
    if (!level_runs[l].empty())
      doc.path(level_runs[l], std::string("stroke=\"") + colours[l] + "\" stroke-width=\"1\"");
  if (!detected_runs.empty()) doc.path(detected_runs, "stroke=\"#e11d48\" stroke-width=\"2\"");
  doc.endGroup();
  doc.rect(left,
           top,
           static_cast<double>(columns),
           static_cast<double>(rows),
           "fill=\"none\" stroke=\"#999\"");
  // Time ticks every 10 s (columns are scans, not evenly spaced in time), beam ticks every 64.
  const std::string tick = "font-size=\"11\" fill=\"#555\"";
  for (std::size_t c = 0; c < columns; ++c) {
    const double t = f.times[c], previous = c ? f.times[c - 1] : -1.0;
    if (std::floor(t / 10.0) == std::floor(previous / 10.0)) continue;
    const double x = left + static_cast<double>(c);
    doc.line(x, bottom, x, bottom + 5, "stroke=\"#666\"");
    doc.text(x,
             bottom + 17,
             plot::num(std::floor(t / 10.0) * 10.0, 0),
             tick + " text-anchor=\"middle\"");
  }
  doc.text(
      left + 0.5 * static_cast<double>(columns), bottom + 34, "time (s)", "text-anchor=\"middle\"");
  for (std::size_t beam = 0; beam < beams; beam += 64)
    doc.text(left - 6,
             top + static_cast<double>(beams - 1 - beam) / f.beam_step + 3,
             std::to_string(beam),
             tick + " text-anchor=\"end\"");
  const double mid = top + 0.5 * static_cast<double>(rows);
  doc.text(
      28, mid, "beam", "text-anchor=\"middle\" transform=\"rotate(-90 28 " + doc.n(mid) + ")\"");
  const double end =
      plot::legend(doc,
                   left,
                   bottom + 50,
                   {{plot::swatch::box("fill=\"#2b2b2b\""), "near (dark) ... far (light grey)"},
                    {plot::swatch::box("fill=\"#ffffff\" stroke=\"#999\""), "no return"},
                    {plot::swatch::box("fill=\"#f2c94c\""), "invalid (NaN)"},
                    {plot::swatch::box("fill=\"#e11d48\""), "detected moving"}},
                   doc.width() - left);
  doc.resize(doc.width(), end + 10);
  doc.write(path);
}

}  // namespace moving_objects::svg
