#pragma once
// SVG plot of the robot pose error and its 3-sigma bounds over time (as Fig. 3.15-3.16 of
// the multisensor thesis): three panels (x, y, heading), one colour per variant, the error
// as a solid line and +-3 sigma as dashed lines. Drawn with examples/common/svg_plot.hpp.

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <sylva/core/types.hpp>

#include "../common/svg_plot.hpp"

namespace laser_camera_slam {

struct SigmaSeries {
  std::string name;
  std::string colour;
  std::vector<double> time_s;
  std::vector<double> error[3];  ///< x (m), y (m), heading (deg)
  std::vector<double> sigma[3];
};

inline void writeSigmaPlot(const std::string& file,
                           const std::string& title,
                           const std::vector<SigmaSeries>& series) {
  namespace svg = sylva_examples::svg;
  const char* labels[3] = {"x error [m]", "y error [m]", "heading error [deg]"};
  const double left = 90, width = 900, panel = 200, gap = 40;
  double t_max = 0.0;
  for (const auto& s : series)
    if (!s.time_s.empty()) t_max = std::max(t_max, s.time_s.back());
  if (!(t_max > 0.0)) t_max = 1.0;

  svg::Document doc(0, 0, 1);
  const double top =
      svg::header(doc,
                  left,
                  title,
                  {"solid: estimate - truth; dashed: +-3 sigma of the filter's pose covariance"}) +
      16;
  for (int c = 0; c < 3; ++c) {
    double a_max = 1e-9;
    for (const auto& s : series)
      for (std::size_t k = 0; k < s.sigma[c].size(); ++k)
        a_max = std::max({a_max, 3.0 * s.sigma[c][k], std::abs(s.error[c][k])});
    a_max *= 1.1;
    const svg::Frame f =
        svg::chartFrame({0.0, -a_max, t_max, a_max}, left, top + c * (panel + gap), width, panel);
    svg::Axes axes{c == 2 ? "time [s]" : "", labels[c]};
    axes.x_numbers = c == 2;
    svg::axes(doc, f, axes);
    doc.line(f.left, f.py(0.0), f.right(), f.py(0.0), "stroke=\"#aaa\"");
    for (const auto& s : series) {
      const auto curve = [&](double sign, bool bound) {
        std::vector<svg::Point> points;
        for (std::size_t k = 0; k < s.time_s.size(); ++k)
          points.emplace_back(s.time_s[k], bound ? sign * 3.0 * s.sigma[c][k] : s.error[c][k]);
        return points;
      };
      const std::string stroke = "stroke=\"" + s.colour + "\"";
      doc.polyline(f, curve(1.0, false), stroke + " stroke-width=\"1.3\"");
      for (const double sign : {1.0, -1.0})
        doc.polyline(f, curve(sign, true), stroke + " stroke-width=\"1\" stroke-dasharray=\"5 3\"");
    }
  }
  std::vector<svg::LegendEntry> legend;
  for (const auto& s : series)
    legend.push_back({svg::swatch::line("stroke=\"" + s.colour + "\" stroke-width=\"2\""), s.name});
  svg::legend(doc, left + width + 15, top + 10, legend);
  doc.resize(left + width + 230, top + 3 * panel + 2 * gap + 50);
  doc.write(file);
}

}  // namespace laser_camera_slam
