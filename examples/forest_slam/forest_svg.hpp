#pragma once
// A top-view SVG of a forest run, like the tree-width thesis' Fig. 4.1 (forest and path) and
// Fig. 4.9 (true and estimated trees drawn as circles of their true and estimated radii, true
// and estimated trajectories). World x right, y up, drawn to scale with a metre grid, a scale
// bar and a legend. Fixed number formatting: the file depends only on the data.

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <string>
#include <vector>

#include <sylva/core/error.hpp>
#include <sylva/core/types.hpp>

namespace forest_slam {

struct ForestSvgData {
  std::string title;
  std::vector<std::string> subtitle_lines;
  struct Circle {
    sylva::Vec<2> centre;
    double radius_m;
  };
  std::vector<Circle> true_trees;
  std::vector<Circle> estimated_trees;          ///< XYZ-R estimates (radius estimated)
  std::vector<sylva::Vec<2>> estimated_points;  ///< trees without a radius estimate
  std::vector<sylva::Vec<2>> true_path;
  std::vector<sylva::Vec<2>> estimated_path;
  bool mark_start = true;
};

namespace svg_detail {

inline std::string num(double v) {
  std::ostringstream os;
  os << std::fixed << std::setprecision(2) << v;
  std::string s = os.str();
  return s == "-0.00" ? "0.00" : s;
}

inline std::string escape(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '<') out += "&lt;";
    else if (c == '>') out += "&gt;";
    else if (c == '&') out += "&amp;";
    else out += c;
  }
  return out;
}

}  // namespace svg_detail

/// Writes the picture to `path`; throws sylva::Error (kInvalidArgument) if it cannot.
inline void writeForestSvg(const std::string& path, const ForestSvgData& data) {
  using svg_detail::num;
  double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
  auto include = [&](const sylva::Vec<2>& p, double r) {
    x0 = std::min(x0, p.x() - r);
    y0 = std::min(y0, p.y() - r);
    x1 = std::max(x1, p.x() + r);
    y1 = std::max(y1, p.y() + r);
  };
  for (const auto& c : data.true_trees) include(c.centre, c.radius_m);
  for (const auto& p : data.true_path) include(p, 0.0);
  if (!(x1 > x0)) {
    x0 = y0 = -1.0;
    x1 = y1 = 1.0;
  }
  x0 -= 2.0, y0 -= 2.0, x1 += 2.0, y1 += 2.0;
  const double scale = 760.0 / std::max(x1 - x0, y1 - y0);  // pixels per metre
  const double left = 20.0, top = 30.0 + 18.0 * (1 + data.subtitle_lines.size());
  const double width = left * 2 + (x1 - x0) * scale;
  auto px = [&](double x) { return left + (x - x0) * scale; };
  auto py = [&](double y) { return top + (y1 - y) * scale; };
  auto polyline = [&](const std::vector<sylva::Vec<2>>& pts) {
    std::ostringstream os;
    for (std::size_t i = 0; i < pts.size(); ++i) os << (i ? " " : "") << num(px(pts[i].x())) << "," << num(py(pts[i].y()));
    return os.str();
  };

  std::ostringstream os;  // everything but the <svg> element, whose height depends on the legend
  os << "<text x=\"" << num(left) << "\" y=\"20\" font-size=\"16\" font-weight=\"bold\">" << svg_detail::escape(data.title)
     << "</text>\n";
  for (std::size_t i = 0; i < data.subtitle_lines.size(); ++i)
    os << "<text x=\"" << num(left) << "\" y=\"" << num(38.0 + 18.0 * i) << "\">" << svg_detail::escape(data.subtitle_lines[i])
       << "</text>\n";
  // Grid every 5 m.
  os << "<g stroke=\"#e4e4e4\" stroke-width=\"1\">\n";
  for (double g = std::ceil(x0 / 5.0) * 5.0; g <= x1; g += 5.0)
    os << "<line x1=\"" << num(px(g)) << "\" y1=\"" << num(py(y0)) << "\" x2=\"" << num(px(g)) << "\" y2=\"" << num(py(y1))
       << "\"/>\n";
  for (double g = std::ceil(y0 / 5.0) * 5.0; g <= y1; g += 5.0)
    os << "<line x1=\"" << num(px(x0)) << "\" y1=\"" << num(py(g)) << "\" x2=\"" << num(px(x1)) << "\" y2=\"" << num(py(g))
       << "\"/>\n";
  os << "</g>\n";
  os << "<rect x=\"" << num(px(x0)) << "\" y=\"" << num(py(y1)) << "\" width=\"" << num((x1 - x0) * scale) << "\" height=\""
     << num((y1 - y0) * scale) << "\" fill=\"none\" stroke=\"#999\"/>\n";
  // True trees to scale.
  os << "<g fill=\"#8c6d3f\" fill-opacity=\"0.55\" stroke=\"#5b4526\" stroke-width=\"1\">\n";
  for (const auto& c : data.true_trees)
    os << "<circle cx=\"" << num(px(c.centre.x())) << "\" cy=\"" << num(py(c.centre.y())) << "\" r=\""
       << num(std::max(1.0, c.radius_m * scale)) << "\"/>\n";
  os << "</g>\n";
  if (!data.true_path.empty())
    os << "<polyline points=\"" << polyline(data.true_path) << "\" fill=\"none\" stroke=\"#2a7f2a\" stroke-width=\"2\"/>\n";
  if (!data.estimated_path.empty())
    os << "<polyline points=\"" << polyline(data.estimated_path)
       << "\" fill=\"none\" stroke=\"#c0392b\" stroke-width=\"1.5\" stroke-dasharray=\"5,3\"/>\n";
  os << "<g fill=\"none\" stroke=\"#1f5fbf\" stroke-width=\"1.5\">\n";
  for (const auto& c : data.estimated_trees)
    os << "<circle cx=\"" << num(px(c.centre.x())) << "\" cy=\"" << num(py(c.centre.y())) << "\" r=\""
       << num(std::max(1.0, c.radius_m * scale)) << "\"/>\n";
  for (const auto& p : data.estimated_points) {
    const double x = px(p.x()), y = py(p.y());
    os << "<path d=\"M" << num(x - 4) << " " << num(y - 4) << "L" << num(x + 4) << " " << num(y + 4) << "M" << num(x - 4) << " "
       << num(y + 4) << "L" << num(x + 4) << " " << num(y - 4) << "\"/>\n";
  }
  os << "</g>\n";
  if (data.mark_start && !data.true_path.empty())
    os << "<circle cx=\"" << num(px(data.true_path.front().x())) << "\" cy=\"" << num(py(data.true_path.front().y()))
       << "\" r=\"5\" fill=\"#2a7f2a\"/>\n";

  // Legend and scale bar.
  double ly = top + (y1 - y0) * scale + 22.0;
  double lx = left;
  auto legend = [&](const std::string& swatch, const std::string& label) {
    const double item = 30.0 + 7.0 * label.size();
    if (lx > left && lx + item > width) {  // wrap to the next row
      lx = left;
      ly += 22.0;
    }
    os << "<g transform=\"translate(" << num(lx) << "," << num(ly) << ")\">" << swatch << "<text x=\"22\" y=\"4\">"
       << svg_detail::escape(label) << "</text></g>\n";
    lx += 30.0 + 7.0 * label.size();
  };
  legend("<circle r=\"6\" fill=\"#8c6d3f\" fill-opacity=\"0.55\" stroke=\"#5b4526\"/>", "true tree (true radius)");
  legend("<line x1=\"-8\" x2=\"10\" stroke=\"#2a7f2a\" stroke-width=\"2\"/>", "true trajectory");
  if (!data.estimated_trees.empty() || !data.estimated_points.empty() || !data.estimated_path.empty()) {
    legend("<circle r=\"6\" fill=\"none\" stroke=\"#1f5fbf\" stroke-width=\"1.5\"/>", "estimated tree (estimated radius)");
    legend("<path d=\"M-4 -4L4 4M-4 4L4 -4\" stroke=\"#1f5fbf\" stroke-width=\"1.5\"/>", "estimate without radius");
    legend("<line x1=\"-8\" x2=\"10\" stroke=\"#c0392b\" stroke-width=\"1.5\" stroke-dasharray=\"5,3\"/>", "estimated trajectory");
  }
  ly += 26.0;
  const double bar_m = 5.0;
  os << "<line x1=\"" << num(left) << "\" y1=\"" << num(ly) << "\" x2=\"" << num(left + bar_m * scale) << "\" y2=\"" << num(ly)
     << "\" stroke=\"black\" stroke-width=\"3\"/>\n";
  os << "<text x=\"" << num(left + bar_m * scale + 8) << "\" y=\"" << num(ly + 4)
     << "\">5 m (grid 5 m; trunks drawn to scale, x right, y up)</text>\n";
  const double height = ly + 20.0;

  std::ofstream file(path);
  if (!file) sylva::fail(sylva::ErrorCode::kInvalidArgument, "writeForestSvg: cannot write '" + path + "'");
  file << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << num(width) << "\" height=\"" << num(height)
       << "\" font-family=\"sans-serif\" font-size=\"13\">\n"
       << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
       << os.str() << "</svg>\n";
}

}  // namespace forest_slam
