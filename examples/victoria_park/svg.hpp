#pragma once
// SVG of one Victoria Park run: the GPS fixes (valid and excluded), the estimated laser path
// and the map (trunk circles to scale for the tree variant, dots for points), in the GPS
// frame after the rigid alignment. Drawn with examples/common/svg_plot.hpp.

#include <algorithm>
#include <iomanip>
#include <sstream>
#include <string>
#include <vector>

#include <sylva/datasets/victoria_park.hpp>

#include "../common/svg_plot.hpp"
#include "slam_run.hpp"

namespace victoria_park {

inline void writeSvg(const std::string& file,
                     const RunResult& r,
                     const std::vector<sylva::datasets::VictoriaParkGps>& gps,
                     const std::vector<char>& valid,
                     const std::string& title) {
  namespace svg = sylva_examples::svg;
  svg::Box world;
  for (const auto& p : r.laser_path) world.include(p.p);
  for (const auto& l : r.map) world.include(l.p);
  world = world.grown(10.0);

  svg::Document doc(0, 0, 1);
  std::ostringstream summary;
  summary << std::setprecision(3) << "GPS RMS " << r.gps.rmse_valid_m << " m (valid fixes), median "
          << r.gps.median_valid_m << " m, all fixes " << r.gps.rmse_all_m << " m; " << r.landmarks
          << " landmarks";
  const double left = 60.0;
  const double top = svg::header(doc, left, title, {summary.str()}) + 12.0;
  const svg::Frame f =
      svg::mapFrame(world, left, top, 900.0 / std::max(world.width(), world.height()));
  svg::axes(doc, f, {"x [m]", "y [m]", 50.0, 50.0});
  std::vector<svg::Point> fixes[2];  // excluded, valid
  const double t0 = r.laser_path.front().t_s, t1 = r.laser_path.back().t_s;
  for (std::size_t i = 0; i < gps.size(); ++i)
    if (gps[i].t_s >= t0 && gps[i].t_s <= t1)
      fixes[valid[i] ? 1 : 0].emplace_back(gps[i].x_m, gps[i].y_m);
  doc.dots(f, fixes[1], "#999", 2.6);
  doc.dots(f, fixes[0], "#e33", 2.6);
  std::vector<svg::Point> path;
  for (const auto& p : r.laser_path) path.push_back(p.p);
  doc.polyline(f, path, "stroke=\"#1f6fd1\" stroke-width=\"1\"");
  doc.group("fill=\"#2a2\" fill-opacity=\"0.7\"");
  for (const auto& l : r.map)
    doc.circle(f.px(l.p.x()),
               f.py(l.p.y()),
               l.radius_m > 0.0 ? std::max(1.5, l.radius_m * f.xScale()) : 1.8,
               "");
  doc.endGroup();
  svg::scaleBar(doc, left + 14, f.bottom() - 12, 100.0 * f.xScale(), "100 m");
  const double end = svg::legend(doc,
                                 left,
                                 f.bottom() + 46,
                                 {{svg::swatch::dot(1.5, "fill=\"#999\""), "GPS fix, valid"},
                                  {svg::swatch::dot(1.5, "fill=\"#e33\""), "GPS fix, excluded"},
                                  {svg::swatch::line("stroke=\"#1f6fd1\""), "estimated laser path"},
                                  {svg::swatch::dot(3, "fill=\"#2a2\" fill-opacity=\"0.7\""),
                                   "map landmark (trees: trunk to scale)"}},
                                 f.width);
  doc.resize(f.right() + 20, end + 10);
  doc.write(file);
}

}  // namespace victoria_park
