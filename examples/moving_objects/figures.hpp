#pragma once
// The four pictures of the moving_objects program (see svg.hpp for the drawing helpers).

#include <algorithm>
#include <cmath>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <sylva/core/types.hpp>

#include "object_position.hpp"
#include "svg.hpp"

namespace moving_objects::svg {

/// Many points as one <path> of round dots, one per pixel at most.
inline void dots(Document& doc, const View& v, const std::vector<Vec<2>>& points, const std::string& colour, double size) {
  std::set<std::pair<long, long>> seen;
  std::ostringstream d;
  for (const Vec<2>& p : points) {
    const double x = v.px(p.x()), y = v.py(p.y());
    if (x < v.left || x > v.left + v.width() || y < v.top || y > v.top + v.height()) continue;
    if (!seen.insert({std::lround(x * 2.0), std::lround(y * 2.0)}).second) continue;
    d << "M" << num(x) << "," << num(y) << "h0";
  }
  if (seen.empty()) return;
  doc.body() << "<path d=\"" << d.str() << "\" stroke=\"" << colour << "\" stroke-width=\"" << num(size)
             << "\" stroke-linecap=\"round\" fill=\"none\"/>\n";
}

struct SceneFigure {
  std::string title;
  std::vector<std::string> subtitle;
  std::vector<std::vector<Vec<2>>> walls;
  std::vector<std::pair<Vec<2>, double>> pillars;
  std::vector<Vec<2>> scan_points;             ///< every reading of every scan (world)
  std::vector<Vec<2>> moving_points;           ///< readings reported moving
  std::vector<Box2> boxes;                     ///< every detected object
  std::vector<Vec<2>> torsos;                  ///< two-leg groups
  std::vector<std::vector<Vec<2>>> tracks;     ///< confirmed tracks
  std::vector<std::vector<Vec<2>>> true_paths; ///< people's true body paths
  std::vector<Vec<2>> robot_path;
  double x0, y0, x1, y1;
};

inline void writeSceneSvg(const std::string& path, const SceneFigure& f) {
  const double width = 1000, top = 70, left = 50, legend_w = 230;
  View v = fit(f.x0, f.y0, f.x1, f.y1, left, top, width - left - legend_w - 30, 700);
  Document doc(width, top + v.height() + 50);
  doc.text(left, 24, f.title, 16, " font-weight=\"bold\"");
  for (std::size_t i = 0; i < f.subtitle.size(); ++i) doc.text(left, 44 + 15 * i, f.subtitle[i], 12);
  doc.grid(v, 1.0);
  for (const auto& w : f.walls) doc.polyline(v, w, "stroke=\"#444\" stroke-width=\"2\"");
  for (const auto& [c, r] : f.pillars) doc.worldCircle(v, c, r, "fill=\"none\" stroke=\"#444\" stroke-width=\"1.5\"");
  for (const auto& p : f.true_paths) doc.polyline(v, p, "stroke=\"#f4a261\" stroke-width=\"1.5\" stroke-dasharray=\"5,4\"");
  dots(doc, v, f.scan_points, "#b5b5b5", 2.0);
  dots(doc, v, f.moving_points, "#d62828", 2.6);
  for (const Box2& b : f.boxes) doc.box(v, b, "fill=\"none\" stroke=\"#1d4ed8\" stroke-width=\"1\"");
  for (const auto& t : f.tracks) doc.polyline(v, t, "stroke=\"#2a9d8f\" stroke-width=\"1.5\"");
  for (const Vec<2>& s : f.torsos) doc.star(v, s, 6.0, "fill=\"black\"");
  doc.polyline(v, f.robot_path, "stroke=\"#16a34a\" stroke-width=\"3\"");
  if (!f.robot_path.empty()) doc.circle(v, f.robot_path.back(), 5, "fill=\"#16a34a\"");
  doc.legend(width - legend_w, top + 10,
             {{"<circle cx=\"10\" cy=\"6\" r=\"2\" fill=\"#b5b5b5\"/>", "laser readings, all scans"},
              {"<circle cx=\"10\" cy=\"6\" r=\"2.5\" fill=\"#d62828\"/>", "readings detected moving"},
              {"<rect x=\"3\" y=\"0\" width=\"14\" height=\"12\" fill=\"none\" stroke=\"#1d4ed8\"/>", "detected object (box)"},
              {"<polygon points=\"10,0 12,4.5 16.5,4.5 13,7.5 14.5,12 10,9 5.5,12 7,7.5 3.5,4.5 8,4.5\" fill=\"black\"/>",
               "torso: two legs detected"},
              {"<line x1=\"0\" y1=\"6\" x2=\"20\" y2=\"6\" stroke=\"#2a9d8f\" stroke-width=\"1.5\"/>", "track of torso/leg groups"},
              {"<line x1=\"0\" y1=\"6\" x2=\"20\" y2=\"6\" stroke=\"#f4a261\" stroke-width=\"1.5\" stroke-dasharray=\"5,4\"/>",
               "true walking routes"},
              {"<line x1=\"0\" y1=\"6\" x2=\"20\" y2=\"6\" stroke=\"#16a34a\" stroke-width=\"3\"/>", "robot path"},
              {"<line x1=\"0\" y1=\"6\" x2=\"20\" y2=\"6\" stroke=\"#444\" stroke-width=\"2\"/>", "walls, pillars (truth)"}});
  doc.write(path);
}

struct CasePanel {
  std::string title;
  std::string result;
  std::vector<Vec<2>> previous_points, current_points, detected_points;
  std::vector<Box2> boxes;
  double x0, y0, x1, y1;
};

inline void writeCasesSvg(const std::string& path, const std::string& title, const std::vector<CasePanel>& panels) {
  const double panel_w = 300, panel_h = 300, gap = 30, left = 40, top = 60;
  const double width = left + panels.size() * (panel_w + gap);
  Document doc(width, top + panel_h + 110);
  doc.text(left, 26, title, 16, " font-weight=\"bold\"");
  for (std::size_t i = 0; i < panels.size(); ++i) {
    const CasePanel& p = panels[i];
    View v = fit(p.x0, p.y0, p.x1, p.y1, left + i * (panel_w + gap), top + 20, panel_w, panel_h);
    doc.text(v.left, top + 8, p.title, 13, " font-weight=\"bold\"");
    doc.grid(v, 0.5);
    dots(doc, v, p.previous_points, "#9ca3af", 5.0);
    dots(doc, v, p.current_points, "#111", 2.5);
    dots(doc, v, p.detected_points, "#d62828", 4.0);
    for (const Box2& b : p.boxes) doc.box(v, b, "fill=\"none\" stroke=\"#1d4ed8\" stroke-width=\"1.5\"");
    doc.text(v.left, top + 20 + v.height() + 32, p.result, 12);
  }
  doc.legend(left, top + panel_h + 85,
             {{"<circle cx=\"10\" cy=\"6\" r=\"2.5\" fill=\"#9ca3af\"/>", "previous scan"}}, 16);
  doc.legend(left + 170, top + panel_h + 85, {{"<circle cx=\"10\" cy=\"6\" r=\"1.5\" fill=\"#111\"/>", "current scan"}}, 16);
  doc.legend(left + 330, top + panel_h + 85,
             {{"<circle cx=\"10\" cy=\"6\" r=\"2\" fill=\"#d62828\"/>", "readings of the detected object"}}, 16);
  doc.legend(left + 600, top + 85 + panel_h,
             {{"<rect x=\"3\" y=\"0\" width=\"14\" height=\"12\" fill=\"none\" stroke=\"#1d4ed8\"/>", "bounding box"}}, 16);
  doc.legend(left + 760, top + 85 + panel_h, {{"", "scanner at the origin looking along +x; grid 0.5 m"}}, 16);
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
  const double gap = 40, left = 40, top = 90;
  const double panel_w = f.panels.size() > 2 ? 460 : 620;
  std::vector<View> views;
  for (std::size_t i = 0; i < f.panels.size(); ++i)
    views.push_back(fit(f.x0, f.y0, f.x1, f.y1, left + i * (panel_w + gap), top + 20, panel_w, 600));
  const double height = top + 20 + views.front().height() + 80;
  Document doc(left + f.panels.size() * (panel_w + gap), height);
  doc.text(left, 24, f.title, 16, " font-weight=\"bold\"");
  for (std::size_t i = 0; i < f.subtitle.size(); ++i) doc.text(left, 44 + 15 * i, f.subtitle[i], 12);
  for (std::size_t i = 0; i < f.panels.size(); ++i) {
    const View& v = views[i];
    const SlamPanel& p = f.panels[i];
    doc.text(v.left, top + 10, p.title, 13, " font-weight=\"bold\"");
    doc.grid(v, 2.0);
    for (const auto& [a, b] : f.routes) doc.line(v, a, b, "stroke=\"#f4a261\" stroke-width=\"5\" stroke-opacity=\"0.35\"");
    doc.polyline(v, f.true_path, "stroke=\"#111\" stroke-width=\"1.2\"");
    doc.polyline(v, p.estimated_path, "stroke=\"#1d4ed8\" stroke-width=\"1.2\" stroke-dasharray=\"4,3\"");
    for (const Vec<2>& pole : f.poles) doc.circle(v, pole, 4.5, "fill=\"none\" stroke=\"#111\" stroke-width=\"1.3\"");
    for (const Vec<2>& l : p.pole_landmarks) doc.circle(v, l, 1.8, "fill=\"#1d4ed8\"");
    for (const Vec<2>& l : p.spurious_landmarks) {
      const double x = v.px(l.x()), y = v.py(l.y());
      doc.body() << "<path d=\"M" << num(x - 2.5) << "," << num(y - 2.5) << "l5,5m0,-5l-5,5\" stroke=\"#d62828\" stroke-width=\"1.2\"/>\n";
    }
  }
  const double ly = top + 20 + views.front().height() + 40;
  doc.legend(left, ly,
             {{"<circle cx=\"10\" cy=\"6\" r=\"4.5\" fill=\"none\" stroke=\"#111\" stroke-width=\"1.3\"/>", "true pole"},
              {"<circle cx=\"10\" cy=\"6\" r=\"1.8\" fill=\"#1d4ed8\"/>", "landmark from a pole (estimate)"}});
  doc.legend(left + 300, ly,
             {{"<path d=\"M7.5,3.5l5,5m0,-5l-5,5\" stroke=\"#d62828\" stroke-width=\"1.2\"/>", "spurious landmark (from a leg)"},
              {"<line x1=\"0\" y1=\"6\" x2=\"20\" y2=\"6\" stroke=\"#f4a261\" stroke-width=\"5\" stroke-opacity=\"0.35\"/>",
               "walking routes of the people"}});
  doc.legend(left + 640, ly,
             {{"<line x1=\"0\" y1=\"6\" x2=\"20\" y2=\"6\" stroke=\"#111\" stroke-width=\"1.2\"/>", "true path"},
              {"<line x1=\"0\" y1=\"6\" x2=\"20\" y2=\"6\" stroke=\"#1d4ed8\" stroke-width=\"1.2\" stroke-dasharray=\"4,3\"/>",
               "estimated path"}});
  doc.write(path);
}

/// Real data: a beams x scans image of ranges (grey, dark = near) with detections in red.
struct BeamTimeFigure {
  std::string title;
  std::vector<std::string> subtitle;
  std::vector<double> times;                  ///< per column (s from the first scan)
  std::vector<std::vector<double>> ranges;    ///< per column, per beam
  std::vector<std::vector<char>> detected;    ///< per column, per beam
  double range_max = 1.0;
  int beam_step = 1;                          ///< beams per pixel row (the nearest is drawn)
};

inline void writeBeamTimeSvg(const std::string& path, const BeamTimeFigure& f) {
  const std::size_t columns = f.ranges.size();
  const std::size_t beams = columns ? f.ranges.front().size() : 0;
  const std::size_t rows = (beams + static_cast<std::size_t>(f.beam_step) - 1) / static_cast<std::size_t>(f.beam_step);
  const double left = 70, top = 80, cell_w = 1.0, cell_h = 1.0;
  const double width = left + columns * cell_w + 40, height = top + rows * cell_h + 90;
  Document doc(width, height);
  doc.text(left, 24, f.title, 16, " font-weight=\"bold\"");
  for (std::size_t i = 0; i < f.subtitle.size(); ++i) doc.text(left, 44 + 15 * i, f.subtitle[i], 12);
  // Grey levels 0..4 (near dark .. far light), 5 no return (not drawn), 6 invalid (NaN).
  constexpr int kLevels = 5, kNoReturn = 5, kInvalid = 6;
  const auto level = [&](double r) -> int {
    if (std::isnan(r)) return kInvalid;
    if (!(r <= f.range_max)) return kNoReturn;
    return std::clamp(static_cast<int>(r / f.range_max * kLevels), 0, kLevels - 1);
  };
  const char* colours[] = {"#2b2b2b", "#555555", "#7f7f7f", "#a5a5a5", "#c8c8c8", "#ffffff", "#f2c94c"};
  // Row r shows beam (beams - 1 - r * step), the leftmost beam (largest angle) on top; a
  // row is detected when any beam it stands for is. Each colour is one <path> of
  // horizontal runs, one pixel high.
  const auto beamOf = [&](std::size_t r) {
    return beams - 1 - std::min(beams - 1, r * static_cast<std::size_t>(f.beam_step));
  };
  std::vector<std::ostringstream> runs(7);
  std::ostringstream detected_runs;
  for (std::size_t r = 0; r < rows; ++r) {
    const std::size_t beam = beamOf(r);
    const std::string y = num(top + r * cell_h + 0.5 * cell_h);
    std::size_t c = 0;
    while (c < columns) {
      const int l = level(f.ranges[c][beam]);
      std::size_t e = c + 1;
      while (e < columns && level(f.ranges[e][beam]) == l) ++e;
      if (l != kNoReturn) runs[static_cast<std::size_t>(l)] << "M" << num(left + c * cell_w) << "," << y << "h" << num((e - c) * cell_w);
      c = e;
    }
    const auto step = static_cast<std::size_t>(f.beam_step);
    const auto hit = [&](std::size_t column) {
      for (std::size_t k = 0; k < step && k <= beam; ++k)
        if (f.detected[column][beam - k]) return true;
      return false;
    };
    c = 0;
    while (c < columns) {
      if (!hit(c)) {
        ++c;
        continue;
      }
      std::size_t e = c + 1;
      while (e < columns && hit(e)) ++e;
      detected_runs << "M" << num(left + c * cell_w) << "," << y << "h" << num((e - c) * cell_w);
      c = e;
    }
  }
  auto& out = doc.body();
  out << "<g fill=\"none\" shape-rendering=\"crispEdges\">\n";
  for (int l = 0; l < 7; ++l)
    if (l != kNoReturn && !runs[static_cast<std::size_t>(l)].str().empty())
      out << "<path stroke=\"" << colours[l] << "\" stroke-width=\"" << num(cell_h) << "\" d=\""
          << runs[static_cast<std::size_t>(l)].str() << "\"/>\n";
  if (!detected_runs.str().empty())
    out << "<path stroke=\"#e11d48\" stroke-width=\"" << num(cell_h + 1.0) << "\" d=\"" << detected_runs.str() << "\"/>\n";
  out << "</g>\n";
  out << "<rect x=\"" << num(left) << "\" y=\"" << num(top) << "\" width=\"" << num(columns * cell_w) << "\" height=\""
      << num(rows * cell_h) << "\" fill=\"none\" stroke=\"#999\"/>\n";
  // Time axis every 10 s, beam axis every 64 beams.
  for (std::size_t c = 0; c < columns; ++c) {
    const double t = f.times[c];
    const double previous = c ? f.times[c - 1] : -1.0;
    if (std::floor(t / 10.0) != std::floor(previous / 10.0)) {
      const double x = left + c * cell_w;
      out << "<line x1=\"" << num(x) << "\" y1=\"" << num(top + rows * cell_h) << "\" x2=\"" << num(x) << "\" y2=\""
          << num(top + rows * cell_h + 5) << "\" stroke=\"#666\"/>\n";
      doc.text(x, top + rows * cell_h + 18, num(std::floor(t / 10.0) * 10.0, 0), 10, " text-anchor=\"middle\" fill=\"#666\"");
    }
  }
  doc.text(left + 0.5 * columns * cell_w, top + rows * cell_h + 34, "time (s)", 12, " text-anchor=\"middle\"");
  for (std::size_t beam = 0; beam < beams; beam += 64) {
    const double y = top + (beams - 1 - beam) / static_cast<double>(f.beam_step) * cell_h;
    doc.text(left - 6, y + 3, std::to_string(beam), 10, " text-anchor=\"end\" fill=\"#666\"");
  }
  doc.text(18, top + 0.5 * rows * cell_h, "beam", 12, " transform=\"rotate(-90 18 " + num(top + 0.5 * rows * cell_h) + ")\" text-anchor=\"middle\"");
  const double ly = top + rows * cell_h + 62;
  doc.legend(left, ly,
             {{"<rect x=\"0\" y=\"0\" width=\"20\" height=\"12\" fill=\"#2b2b2b\"/>", "near (dark) ... far (light grey)"}});
  doc.legend(left + 260, ly, {{"<rect x=\"0\" y=\"0\" width=\"20\" height=\"12\" fill=\"#ffffff\" stroke=\"#999\"/>", "no return"}});
  doc.legend(left + 400, ly, {{"<rect x=\"0\" y=\"0\" width=\"20\" height=\"12\" fill=\"#f2c94c\"/>", "invalid (NaN)"}});
  doc.legend(left + 560, ly, {{"<rect x=\"0\" y=\"0\" width=\"20\" height=\"12\" fill=\"#e11d48\"/>", "detected moving"}});
  doc.write(path);
}

}  // namespace moving_objects::svg
