#pragma once
// SVG plot of the robot pose error and its 3-sigma bounds over time (as Fig. 3.15-3.16 of
// the multisensor thesis): three panels (x, y, heading), one colour per variant, the error
// as a solid line and +-3 sigma as dashed lines. Fixed number formatting: the file depends
// only on the data.

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <string>
#include <vector>

#include <sylva/core/error.hpp>

namespace laser_camera_slam {

struct SigmaSeries {
  std::string name;
  std::string colour;
  std::vector<double> time_s;
  std::vector<double> error[3];  ///< x (m), y (m), heading (deg)
  std::vector<double> sigma[3];
};

inline std::string fmt(double v, int digits = 2) {
  std::ostringstream os;
  os << std::fixed << std::setprecision(digits) << v;
  std::string s = os.str();
  if (s == "-0.00" || s == "-0.0" || s == "-0") s = s.substr(1);
  return s;
}

inline void writeSigmaPlot(const std::string& file, const std::string& title, const std::vector<SigmaSeries>& series) {
  const double left = 80, width = 900, panel = 200, gap = 50, top = 70;
  const char* labels[3] = {"x error [m]", "y error [m]", "heading error [deg]"};
  double t_max = 0.0;
  for (const auto& s : series)
    if (!s.time_s.empty()) t_max = std::max(t_max, s.time_s.back());
  if (!(t_max > 0.0)) t_max = 1.0;
  std::ostringstream svg;
  const double height = top + 3 * panel + 2 * gap + 70;
  svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << fmt(left + width + 200, 0) << "\" height=\""
      << fmt(height, 0) << "\" font-family=\"DejaVu Sans, Helvetica, Arial, sans-serif\">\n";
  svg << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  svg << "<text x=\"" << fmt(left) << "\" y=\"30\" font-size=\"18\" font-weight=\"bold\">" << title << "</text>\n";
  svg << "<text x=\"" << fmt(left) << "\" y=\"52\" font-size=\"13\" fill=\"#333\">solid: estimate - truth; "
                                      "dashed: +-3 sigma of the filter's pose covariance</text>\n";
  for (int c = 0; c < 3; ++c) {
    const double y0 = top + c * (panel + gap);
    double a_max = 1e-9;
    for (const auto& s : series)
      for (std::size_t k = 0; k < s.sigma[c].size(); ++k)
        a_max = std::max({a_max, 3.0 * s.sigma[c][k], std::abs(s.error[c][k])});
    a_max *= 1.1;
    auto px = [&](double t) { return left + width * t / t_max; };
    auto py = [&](double v) { return y0 + panel * (0.5 - 0.5 * v / a_max); };
    svg << "<rect x=\"" << fmt(left) << "\" y=\"" << fmt(y0) << "\" width=\"" << fmt(width) << "\" height=\""
        << fmt(panel) << "\" fill=\"none\" stroke=\"#888\"/>\n";
    svg << "<line x1=\"" << fmt(left) << "\" y1=\"" << fmt(py(0)) << "\" x2=\"" << fmt(left + width) << "\" y2=\""
        << fmt(py(0)) << "\" stroke=\"#ccc\"/>\n";
    for (double v : {-a_max / 1.1, a_max / 1.1})
      svg << "<text x=\"" << fmt(left - 6) << "\" y=\"" << fmt(py(v) + 4) << "\" font-size=\"11\" text-anchor=\"end\">"
          << fmt(v, c == 2 ? 2 : 3) << "</text>\n";
    svg << "<text transform=\"rotate(-90 " << fmt(left - 55) << " " << fmt(y0 + panel / 2) << ")\" x=\""
        << fmt(left - 55) << "\" y=\"" << fmt(y0 + panel / 2) << "\" font-size=\"13\" text-anchor=\"middle\">"
        << labels[c] << "</text>\n";
    for (const auto& s : series) {
      auto line = [&](auto value, const std::string& style) {
        svg << "<polyline fill=\"none\" stroke=\"" << s.colour << "\" " << style << " points=\"";
        for (std::size_t k = 0; k < s.time_s.size(); ++k) svg << fmt(px(s.time_s[k]), 1) << "," << fmt(py(value(k)), 1) << " ";
        svg << "\"/>\n";
      };
      line([&](std::size_t k) { return s.error[c][k]; }, "stroke-width=\"1.3\"");
      line([&](std::size_t k) { return 3.0 * s.sigma[c][k]; }, "stroke-width=\"1\" stroke-dasharray=\"5 3\"");
      line([&](std::size_t k) { return -3.0 * s.sigma[c][k]; }, "stroke-width=\"1\" stroke-dasharray=\"5 3\"");
    }
  }
  const double yt = top + 3 * panel + 2 * gap;
  for (int i = 0; i <= 5; ++i) {
    const double t = t_max * i / 5.0;
    svg << "<text x=\"" << fmt(left + width * i / 5.0) << "\" y=\"" << fmt(yt + 18) << "\" font-size=\"11\" text-anchor=\"middle\">"
        << fmt(t, 0) << "</text>\n";
  }
  svg << "<text x=\"" << fmt(left + width / 2) << "\" y=\"" << fmt(yt + 40) << "\" font-size=\"13\" text-anchor=\"middle\">time [s]</text>\n";
  for (std::size_t i = 0; i < series.size(); ++i) {
    const double y = top + 20 + 22.0 * static_cast<double>(i);
    svg << "<line x1=\"" << fmt(left + width + 15) << "\" y1=\"" << fmt(y) << "\" x2=\"" << fmt(left + width + 45)
        << "\" y2=\"" << fmt(y) << "\" stroke=\"" << series[i].colour << "\" stroke-width=\"2\"/>\n";
    svg << "<text x=\"" << fmt(left + width + 50) << "\" y=\"" << fmt(y + 4) << "\" font-size=\"13\">" << series[i].name
        << "</text>\n";
  }
  svg << "</svg>\n";
  std::ofstream out(file);
  if (!out) sylva::fail(sylva::ErrorCode::kInvalidArgument, "cannot write '" + file + "'");
  out << svg.str();
}

}  // namespace laser_camera_slam
