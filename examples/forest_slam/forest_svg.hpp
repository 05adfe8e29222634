#pragma once
// A top-view SVG of a forest run, like the tree-width thesis' Fig. 4.1 (forest and path) and
// Fig. 4.9 (true and estimated trees drawn as circles of their true and estimated radii, true
// and estimated trajectories). World x right, y up, drawn to scale with a metre grid, a scale
// bar and a legend. Drawn with examples/common/svg_plot.hpp.

#include <algorithm>
#include <string>
#include <vector>

#include <sylva/core/types.hpp>

#include "../common/svg_plot.hpp"

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

/// Writes the picture to `path`; throws sylva::Error (kInvalidArgument) if it cannot.
inline void writeForestSvg(const std::string& path, const ForestSvgData& data) {
  namespace svg = sylva_examples::svg;
  svg::Box world;
  for (const auto& c : data.true_trees) world.include(c.centre, c.radius_m);
  for (const auto& p : data.true_path) world.include(p);
  if (world.empty()) {  // no truth (a run on recorded detections): frame the estimates
    for (const auto& c : data.estimated_trees) world.include(c.centre, c.radius_m);
    for (const auto& p : data.estimated_points) world.include(p);
    for (const auto& p : data.estimated_path) world.include(p);
  }
  if (world.empty()) world = svg::Box{-1.0, -1.0, 1.0, 1.0};
  world = world.grown(2.0);

  svg::Document doc(0, 0);
  const double left = 50.0;
  const double top = svg::header(doc, left, data.title, data.subtitle_lines) + 12.0;
  const svg::Frame f =
      svg::mapFrame(world, left, top, 760.0 / std::max(world.width(), world.height()));
  const auto trunk_px = [&](double radius_m) { return std::max(1.0, radius_m * f.xScale()); };
  svg::axes(doc, f, {"x [m]", "y [m]", 5.0, 5.0});
  doc.group("fill=\"#8c6d3f\" fill-opacity=\"0.55\" stroke=\"#5b4526\" stroke-width=\"1\"");
  for (const auto& c : data.true_trees)
    doc.circle(f.px(c.centre.x()), f.py(c.centre.y()), trunk_px(c.radius_m), "");
  doc.endGroup();
  doc.polyline(f, data.true_path, "stroke=\"#2a7f2a\" stroke-width=\"2\"");
  doc.polyline(
      f, data.estimated_path, "stroke=\"#c0392b\" stroke-width=\"1.5\" stroke-dasharray=\"5,3\"");
  doc.group("fill=\"none\" stroke=\"#1f5fbf\" stroke-width=\"1.5\"");
  for (const auto& c : data.estimated_trees)
    doc.circle(f.px(c.centre.x()), f.py(c.centre.y()), trunk_px(c.radius_m), "");
  for (const auto& p : data.estimated_points) doc.cross(f.px(p.x()), f.py(p.y()), 4.0, "");
  doc.endGroup();
  if (data.mark_start && !data.true_path.empty())
    doc.circle(
        f.px(data.true_path.front().x()), f.py(data.true_path.front().y()), 5, "fill=\"#2a7f2a\"");
  svg::scaleBar(doc, left + 14, f.bottom() - 12, 5.0 * f.xScale(), "5 m");

  std::vector<svg::LegendEntry> legend{
      {svg::swatch::dot(6, "fill=\"#8c6d3f\" fill-opacity=\"0.55\" stroke=\"#5b4526\""),
       "true tree (true radius)"},
      {svg::swatch::line("stroke=\"#2a7f2a\" stroke-width=\"2\""), "true trajectory"}};
  if (!data.estimated_trees.empty() || !data.estimated_points.empty() ||
      !data.estimated_path.empty()) {
    legend.push_back({svg::swatch::dot(6, "fill=\"none\" stroke=\"#1f5fbf\" stroke-width=\"1.5\""),
                      "estimated tree (estimated radius)"});
    legend.push_back(
        {svg::swatch::cross("stroke=\"#1f5fbf\" stroke-width=\"1.5\""), "estimate without radius"});
    legend.push_back(
        {svg::swatch::line("stroke=\"#c0392b\" stroke-width=\"1.5\" stroke-dasharray=\"5,3\""),
         "estimated trajectory"});
  }
  const double end = svg::legend(doc, left, f.bottom() + 46, legend, f.width);
  doc.text(left, end + 8, "trunks drawn to scale; x right, y up", "fill=\"#555\"");
  doc.resize(f.right() + 20, end + 22);
  doc.write(path);
}

}  // namespace forest_slam
