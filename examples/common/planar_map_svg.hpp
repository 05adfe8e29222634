#pragma once
// The SVG map of one 2D SLAM run, as range_bearing_slam, laser_camera_slam and utias draw it: true and estimated landmarks (with 2-sigma ellipses), the true, estimated and
// odometry-only paths, the sensor's reach at the final pose, a legend, and an enlarged inset
// where the ellipses are largest. The drawing helpers are in examples/common/svg_plot.hpp.

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include <sylva/core/angles.hpp>
#include <sylva/core/types.hpp>

#include "svg_plot.hpp"

namespace sylva_examples {

struct SvgMapData {
  std::string title;
  std::vector<std::string> subtitle_lines;
  std::vector<sylva::Vec<2>> true_path;
  std::vector<sylva::Vec<2>> estimated_path;
  std::vector<sylva::Vec<2>> odometry_path;
  std::vector<sylva::Vec<2>> true_landmarks;
  std::vector<bool> true_landmark_mapped;  ///< parallel to true_landmarks
  struct Estimate {
    sylva::Vec<2> mean;
    sylva::Mat<2, 2> covariance;
  };
  std::vector<Estimate> estimated_landmarks;
  sylva::Vec<3> start_pose;
  sylva::Vec<3> true_final_pose;
  sylva::Vec<3> estimated_final_pose;
  sylva::Mat<2, 2> final_position_covariance;
  sylva::Vec<2> sensor_range_fov;  ///< [max range m, half angle rad], drawn at the final pose
  std::vector<std::pair<sylva::Vec<2>, sylva::Vec<2>>> walls;  ///< optional wall segments, drawn grey
};

namespace planar_map_detail {

namespace svg = sylva_examples::svg;

constexpr const char* kStyle =
    ".truepath { stroke: #222; stroke-width: 1.6; }\n"
    ".estpath { stroke: #1f6fd1; stroke-width: 1.6; }\n"
    ".odopath { stroke: #d62728; stroke-width: 1.4; stroke-dasharray: 6 4; }\n"
    ".truelm { stroke: #222; stroke-width: 1.4; }\n"
    ".unmapped { stroke: #aaa; stroke-width: 1.2; }\n"
    ".estlm { fill: #f08c00; }\n"
    ".ell { fill: #f08c00; fill-opacity: 0.18; stroke: #c06a00; stroke-width: 1; }\n"
    ".robotell { fill: #1f6fd1; fill-opacity: 0.15; stroke: #1f6fd1; stroke-width: 1; }\n"
    ".fov { fill: #1f6fd1; fill-opacity: 0.05; stroke: #1f6fd1; stroke-opacity: 0.35; "
    "stroke-width: 1; }\n";
constexpr const char* kTrueRobot = "fill=\"#222\"";
constexpr const char* kEstimatedRobot = "fill=\"#1f6fd1\" fill-opacity=\"0.8\"";

/// The centre of the inset: the patch of estimated landmarks (within `half_m` - 0.5 of one
/// of them) whose ellipses are largest, weighted by their size; the final pose without any.
inline sylva::Vec<2> insetFocus(const SvgMapData& d, double half_m) {
  sylva::Vec<2> focus = d.true_final_pose.head<2>();
  double best = -1.0;
  for (const auto& a : d.estimated_landmarks) {
    sylva::Vec<2> sum = sylva::Vec<2>::Zero();
    double weight = 0.0;
    for (const auto& b : d.estimated_landmarks) {
      const sylva::Vec<2> delta = (b.mean - a.mean).cwiseAbs();
      if (delta.x() < half_m - 0.5 && delta.y() < half_m - 0.5) {
        const double size = std::sqrt(std::max(0.0, b.covariance.trace()));
        sum += size * b.mean;
        weight += size;
      }
    }
    if (weight > best && weight > 0.0) {
      best = weight;
      focus = sum / weight;
    }
  }
  return focus;
}

/// The sensor's range and field of view at the true final pose, as a wedge.
inline void drawReach(svg::Document& doc, const svg::Frame& f, const SvgMapData& d) {
  const double r = d.sensor_range_fov[0], half = d.sensor_range_fov[1];
  const sylva::Vec<3>& p = d.true_final_pose;
  const sylva::Vec<2> a = p.head<2>() + r * sylva::Vec<2>(std::cos(p[2] - half), std::sin(p[2] - half));
  const sylva::Vec<2> b = p.head<2>() + r * sylva::Vec<2>(std::cos(p[2] + half), std::sin(p[2] + half));
  const std::string radius = doc.n(r * f.xScale());
  doc.path("M" + doc.n(f.px(p[0])) + " " + doc.n(f.py(p[1])) + "L" + doc.n(f.px(a.x())) + " " +
               doc.n(f.py(a.y())) + "A" + radius + " " + radius + " 0 " +
               (half > 0.5 * sylva::kPi ? "1" : "0") + " 0 " + doc.n(f.px(b.x())) + " " +
               doc.n(f.py(b.y())) + "Z",
           "class=\"fov\"");
}

/// Walls, paths, landmarks and the final poses in one frame; `marker` scales the symbols.
inline void drawRun(svg::Document& doc, const svg::Frame& f, const SvgMapData& d, double marker) {
  for (const auto& [a, b] : d.walls)
    doc.segment(f, a, b, "stroke=\"#9a9a9a\" stroke-width=\"3\"");
  doc.polyline(f, d.odometry_path, "class=\"odopath\"");
  doc.polyline(f, d.true_path, "class=\"truepath\"");
  doc.polyline(f, d.estimated_path, "class=\"estpath\"");
  for (std::size_t i = 0; i < d.true_landmarks.size(); ++i)
    doc.cross(f.px(d.true_landmarks[i].x()),
              f.py(d.true_landmarks[i].y()),
              4.0 * marker,
              d.true_landmark_mapped[i] ? "class=\"truelm\"" : "class=\"unmapped\"");
  for (const auto& e : d.estimated_landmarks) {
    doc.ellipse(f, e.mean, e.covariance, 2.0, "class=\"ell\"");
    doc.circle(f.px(e.mean.x()), f.py(e.mean.y()), 2.2 * marker, "class=\"estlm\"");
  }
  doc.ellipse(
      f, d.estimated_final_pose.head<2>(), d.final_position_covariance, 2.0, "class=\"robotell\"");
  for (const auto& [pose, style] : {std::pair(d.true_final_pose, kTrueRobot),
                                    std::pair(d.estimated_final_pose, kEstimatedRobot)})
    doc.arrow(f.px(pose[0]), f.py(pose[1]), pose[2], 9.0 * marker, style);
}

}  // namespace planar_map_detail

/// Writes the map to `file`. Throws sylva::Error (kInvalidArgument) if it cannot be written.
inline void writeSvgMap(const std::string& file, const SvgMapData& d) {
  namespace svg = sylva_examples::svg;
  using namespace planar_map_detail;
  svg::Box world;
  for (const auto* set : {&d.true_path, &d.estimated_path, &d.odometry_path, &d.true_landmarks})
    for (const sylva::Vec<2>& p : *set) world.include(p);
  for (const auto& e : d.estimated_landmarks) world.include(e.mean);
  world = world.grown(2.0);

  svg::Document doc(0, 0);
  doc.styleSheet(kStyle);
  const double left = 70.0;
  const double top = svg::header(doc, left, d.title, d.subtitle_lines) + 16.0;
  const svg::Frame main = svg::mapFrame(world, left, top, 980.0 / world.width());
  const double step = svg::niceStep(std::max(world.width(), world.height()), 12.0);

  // The main map: axes, the run clipped to the frame, the start, the inset's window, a scale bar.
  const double inset_half_m = 2.5;
  const sylva::Vec<2> focus = insetFocus(d, inset_half_m);
  const svg::Box inset_world{focus.x() - inset_half_m,
                             focus.y() - inset_half_m,
                             focus.x() + inset_half_m,
                             focus.y() + inset_half_m};
  svg::axes(doc, main, {"x [m]", "y [m]", step, step});
  doc.group(doc.clipTo(main));
  drawReach(doc, main, d);
  drawRun(doc, main, d, 1.0);
  doc.rect(main.px(inset_world.x0),  // the inset's window, cut at the frame like the run
           main.py(inset_world.y1),
           inset_world.width() * main.xScale(),
           inset_world.height() * main.yScale(),
           "fill=\"none\" stroke=\"#555\" stroke-dasharray=\"3 2\"");
  doc.endGroup();
  doc.circle(main.px(d.start_pose[0]),
             main.py(d.start_pose[1]),
             5,
             "fill=\"none\" stroke=\"#222\" stroke-width=\"1.5\"");
  doc.text(
      main.px(d.start_pose[0]) + 8, main.py(d.start_pose[1]) + 18, "start", "font-size=\"11\"");
  svg::scaleBar(doc,
                left + 16,
                main.bottom() - 18,
                step * main.xScale(),
                svg::num(step, svg::digitsFor(step)) + " m");

  // Legend, then the inset, in a column right of the map.
  const double side_x = main.right() + 30.0, side_width = 340.0;
  const std::string robot_swatch = "<polygon points=\"21,6 6.6,10.5 6.6,1.5\" ";
  const double legend_end =
      svg::legend(doc,
                  side_x,
                  top,
                  {{svg::swatch::line("class=\"truepath\""), "true path"},
                   {svg::swatch::line("class=\"estpath\""), "EKF-SLAM estimate"},
                   {svg::swatch::line("class=\"odopath\""), "odometry only (dead reckoning)"},
                   {svg::swatch::cross("class=\"truelm\""), "true landmark"},
                   {svg::swatch::cross("class=\"unmapped\""), "true landmark, never seen"},
                   {"<ellipse cx=\"12\" cy=\"6\" rx=\"11\" ry=\"5.5\" class=\"ell\"/><circle "
                    "cx=\"12\" cy=\"6\" r=\"2.2\" "
                    "class=\"estlm\"/>",
                    "estimated landmark, 2-sigma ellipse"},
                   {robot_swatch + kTrueRobot + "/>", "true final pose"},
                   {"<ellipse cx=\"12\" cy=\"6\" rx=\"11\" ry=\"5.5\" class=\"robotell\"/>" +
                        robot_swatch + kEstimatedRobot + "/>",
                    "estimated final pose, 2-sigma"},
                   {"<path d=\"M2 6L24 -4A26 26 0 0 1 24 16Z\" class=\"fov\"/>",
                    "sensor range and field of view"}});

  const double inset_top = legend_end + 40.0;
  const svg::Frame inset =
      svg::mapFrame(inset_world, side_x, inset_top, side_width / inset_world.width());
  const double zoom = inset.xScale() / main.xScale();
  doc.text(side_x,
           inset_top - 10,
           "detail (dashed box), " + svg::num(zoom, zoom < 10.0 ? 1 : 0) + "x enlarged, grid 1 m");
  doc.rect(inset.left, inset.top, inset.width, inset.height, "fill=\"white\"");
  svg::grid(doc, inset, 1.0, 1.0);
  doc.group(doc.clipTo(inset));
  drawRun(doc, inset, d, 1.15);
  doc.endGroup();
  doc.rect(inset.left, inset.top, inset.width, inset.height, "fill=\"none\" stroke=\"#888\"");
  svg::scaleBar(doc, side_x + 12, inset.bottom() - 12, inset.xScale(), "1 m", false);

  doc.resize(side_x + side_width + 30.0, std::max(main.bottom() + 60.0, inset.bottom() + 60.0));
  doc.write(file);
}

}  // namespace sylva_examples
