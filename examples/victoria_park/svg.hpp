#pragma once
// SVG of one Victoria Park run: the GPS fixes (valid and excluded), the estimated laser path
// and the map (trunk circles to scale for the tree variant, dots for points), in the GPS
// frame after the rigid alignment. Fixed number formatting: same run, same file.

#include <fstream>
#include <iomanip>
#include <sstream>
#include <string>
#include <vector>

#include <sylva/core/error.hpp>
#include <sylva/datasets/victoria_park.hpp>

#include "slam_run.hpp"

namespace victoria_park {

inline void writeSvg(const std::string& file,
                     const RunResult& r,
                     const std::vector<sylva::datasets::VictoriaParkGps>& gps,
                     const std::vector<char>& valid,
                     const std::string& title) {
  double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
  const auto include = [&](const Vec<2>& p) {
    x0 = std::min(x0, p.x());
    y0 = std::min(y0, p.y());
    x1 = std::max(x1, p.x());
    y1 = std::max(y1, p.y());
  };
  for (const auto& p : r.laser_path) include(p.p);
  for (const auto& l : r.map) include(l.p);
  x0 -= 10.0; y0 -= 10.0; x1 += 10.0; y1 += 10.0;
  const double scale = 900.0 / std::max(x1 - x0, y1 - y0);
  const double left = 50.0, top = 70.0;
  const double width = left + (x1 - x0) * scale + 20.0, height = top + (y1 - y0) * scale + 50.0;
  const auto num = [](double v) {
    std::ostringstream os;
    os << std::fixed << std::setprecision(1) << v;
    return os.str();
  };
  const auto px = [&](double x) { return num(left + (x - x0) * scale); };
  const auto py = [&](double y) { return num(top + (y1 - y) * scale); };
  std::ostringstream s;
  s << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << num(width) << "\" height=\"" << num(height)
    << "\" font-family=\"DejaVu Sans, Helvetica, Arial, sans-serif\">\n"
    << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
    << "<text x=\"" << left << "\" y=\"26\" font-size=\"18\" font-weight=\"bold\">" << title << "</text>\n"
    << "<text x=\"" << left << "\" y=\"48\" font-size=\"13\" fill=\"#333\">GPS RMS " << std::setprecision(3)
    << r.gps.rmse_valid_m << " m (valid fixes), median " << r.gps.median_valid_m << " m, all fixes "
    << r.gps.rmse_all_m << " m; " << r.landmarks << " landmarks. Grey: valid GPS, red: excluded GPS, blue: "
    << "estimated laser path, green: map</text>\n";
  // 50 m grid
  for (double gx = std::ceil(x0 / 50.0) * 50.0; gx <= x1; gx += 50.0)
    s << "<line x1=\"" << px(gx) << "\" y1=\"" << py(y0) << "\" x2=\"" << px(gx) << "\" y2=\"" << py(y1)
      << "\" stroke=\"#eee\"/>\n";
  for (double gy = std::ceil(y0 / 50.0) * 50.0; gy <= y1; gy += 50.0)
    s << "<line x1=\"" << px(x0) << "\" y1=\"" << py(gy) << "\" x2=\"" << px(x1) << "\" y2=\"" << py(gy)
      << "\" stroke=\"#eee\"/>\n";
  const double t0 = r.laser_path.front().t_s, t1 = r.laser_path.back().t_s;
  for (std::size_t i = 0; i < gps.size(); ++i) {
    if (gps[i].t_s < t0 || gps[i].t_s > t1) continue;
    s << "<circle cx=\"" << px(gps[i].x_m) << "\" cy=\"" << py(gps[i].y_m) << "\" r=\"1.3\" fill=\""
      << (valid[i] ? "#999" : "#e33") << "\"/>\n";
  }
  s << "<polyline fill=\"none\" stroke=\"#1f6fd1\" stroke-width=\"1\" points=\"";
  for (const auto& p : r.laser_path) s << px(p.p.x()) << "," << py(p.p.y()) << " ";
  s << "\"/>\n";
  for (const auto& l : r.map) {
    const double radius_px = l.radius_m > 0.0 ? std::max(1.5, l.radius_m * scale) : 1.8;
    s << "<circle cx=\"" << px(l.p.x()) << "\" cy=\"" << py(l.p.y()) << "\" r=\"" << num(radius_px)
      << "\" fill=\"#2a2\" fill-opacity=\"0.7\"/>\n";
  }
  // 100 m scale bar
  s << "<path d=\"M" << num(left + 10) << " " << num(height - 20) << "h" << num(100.0 * scale)
    << "\" stroke=\"#222\" stroke-width=\"2\"/><text x=\"" << num(left + 10 + 50.0 * scale) << "\" y=\""
    << num(height - 26) << "\" font-size=\"12\" text-anchor=\"middle\">100 m</text>\n";
  s << "</svg>\n";
  std::ofstream f(file);
  if (!f) sylva::fail(sylva::ErrorCode::kInvalidArgument, "cannot write SVG file '" + file + "'");
  f << s.str();
}

}  // namespace victoria_park
