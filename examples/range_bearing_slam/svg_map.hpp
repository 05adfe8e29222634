#pragma once
// A hand-written SVG map of one 2D SLAM run for the range_bearing_slam example: true and
// estimated landmarks (with 2-sigma ellipses), the true, estimated and odometry-only paths,
// a metre grid with ticks, a scale bar, a legend, and an enlarged inset around the final
// robot pose where the ellipses are large enough to see. The output depends only on the
// data (fixed number formatting), so it is reproducible bit for bit.

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Eigenvalues>

#include <sylva/core/angles.hpp>
#include <sylva/core/error.hpp>
#include <sylva/core/types.hpp>

namespace range_bearing_slam {

using sylva::Mat;
using sylva::Vec;

struct SvgMapData {
  std::string title;
  std::vector<std::string> subtitle_lines;
  std::vector<Vec<2>> true_path;
  std::vector<Vec<2>> estimated_path;
  std::vector<Vec<2>> odometry_path;
  std::vector<Vec<2>> true_landmarks;
  std::vector<bool> true_landmark_mapped;  ///< parallel to true_landmarks
  struct Estimate {
    Vec<2> mean;
    Mat<2, 2> covariance;
  };
  std::vector<Estimate> estimated_landmarks;
  Vec<3> start_pose;
  Vec<3> true_final_pose;
  Vec<3> estimated_final_pose;
  Mat<2, 2> final_position_covariance;
  Vec<2> sensor_range_fov;  ///< [max range m, half angle rad], drawn at the final pose
  std::vector<std::pair<Vec<2>, Vec<2>>> walls;  ///< optional wall segments, drawn grey
};

namespace detail {

/// Axis-aligned box in world metres.
struct Box {
  double x0, y0, x1, y1;
  void include(const Vec<2>& p) {
    x0 = std::min(x0, p.x());
    y0 = std::min(y0, p.y());
    x1 = std::max(x1, p.x());
    y1 = std::max(y1, p.y());
  }
  double width() const { return x1 - x0; }
  double height() const { return y1 - y0; }
};

/// World metres -> SVG pixels (y flipped so that world y points up).
struct View {
  Box world;
  double left, top, scale;
  double px(double x) const { return left + (x - world.x0) * scale; }
  double py(double y) const { return top + (world.y1 - y) * scale; }
};

inline std::string num(double v, int digits = 2) {
  std::ostringstream os;
  os << std::fixed << std::setprecision(digits) << v;
  std::string s = os.str();
  if (s == "-0.00" || s == "-0.0" || s == "-0") s = s.substr(1);
  return s;
}

inline std::string escape(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

inline std::string polyline(const View& v,
                            const std::vector<Vec<2>>& points,
                            const std::string& style) {
  std::ostringstream os;
  os << "<polyline fill=\"none\" " << style << " points=\"";
  for (std::size_t i = 0; i < points.size(); ++i)
    os << (i ? " " : "") << num(v.px(points[i].x())) << "," << num(v.py(points[i].y()));
  os << "\"/>\n";
  return os.str();
}

/// The k-sigma ellipse of a 2x2 covariance as an SVG <ellipse> (radii in pixels).
inline std::string ellipse(
    const View& v, const Vec<2>& c, const Mat<2, 2>& cov, double k, const std::string& style) {
  Eigen::SelfAdjointEigenSolver<Mat<2, 2>> eig(0.5 * (cov + cov.transpose()));
  const Vec<2> radii = k * eig.eigenvalues().cwiseMax(0.0).cwiseSqrt() * v.scale;
  const Vec<2> major = eig.eigenvectors().col(1);
  // SVG rotates clockwise in screen coordinates, whose y points down: negate the angle.
  const double angle_deg = -std::atan2(major.y(), major.x()) * 180.0 / sylva::kPi;
  std::ostringstream os;
  os << "<ellipse cx=\"" << num(v.px(c.x())) << "\" cy=\"" << num(v.py(c.y())) << "\" rx=\""
     << num(radii[1], 3) << "\" ry=\"" << num(radii[0], 3) << "\" transform=\"rotate("
     << num(angle_deg) << " " << num(v.px(c.x())) << " " << num(v.py(c.y())) << ")\" " << style
     << "/>\n";
  return os.str();
}

inline std::string cross(const View& v, const Vec<2>& p, double half_px, const std::string& style) {
  const double x = v.px(p.x());
  const double y = v.py(p.y());
  std::ostringstream os;
  os << "<path d=\"M" << num(x - half_px) << " " << num(y - half_px) << "L" << num(x + half_px)
     << " " << num(y + half_px) << "M" << num(x - half_px) << " " << num(y + half_px) << "L"
     << num(x + half_px) << " " << num(y - half_px) << "\" " << style << "/>\n";
  return os.str();
}

/// A robot marker: a triangle at the pose pointing along the heading.
inline std::string robot(const View& v,
                         const Vec<3>& pose,
                         double size_px,
                         const std::string& style) {
  const double x = v.px(pose[0]);
  const double y = v.py(pose[1]);
  const double c = std::cos(pose[2]);
  const double s = -std::sin(pose[2]);  // screen y points down
  auto corner = [&](double f, double l) {
    return num(x + size_px * (f * c - l * s)) + "," + num(y + size_px * (f * s + l * c));
  };
  return "<polygon points=\"" + corner(1.0, 0.0) + " " + corner(-0.6, 0.55) + " " +
         corner(-0.6, -0.55) + "\" " + style + "/>\n";
}

/// Grid step (m) giving about `target` lines over `extent` metres: 1, 2 or 5 times 10^k.
inline double niceStep(double extent, double target) {
  const double raw = extent / target;
  const double p = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (m * p >= raw) return m * p;
  return 10.0 * p;
}

inline std::string grid(const View& v, double step, bool labels, int font_px) {
  std::ostringstream os;
  const Box& w = v.world;
  for (double x = std::ceil(w.x0 / step) * step; x <= w.x1 + 1e-9; x += step) {
    os << "<line x1=\"" << num(v.px(x)) << "\" y1=\"" << num(v.py(w.y0)) << "\" x2=\""
       << num(v.px(x)) << "\" y2=\"" << num(v.py(w.y1)) << "\" class=\"grid\"/>\n";
    if (labels)
      os << "<text x=\"" << num(v.px(x)) << "\" y=\"" << num(v.py(w.y0) + font_px + 4)
         << "\" text-anchor=\"middle\" class=\"tick\">" << num(x, step < 1.0 ? 1 : 0)
         << "</text>\n";
  }
  for (double y = std::ceil(w.y0 / step) * step; y <= w.y1 + 1e-9; y += step) {
    os << "<line x1=\"" << num(v.px(w.x0)) << "\" y1=\"" << num(v.py(y)) << "\" x2=\""
       << num(v.px(w.x1)) << "\" y2=\"" << num(v.py(y)) << "\" class=\"grid\"/>\n";
    if (labels)
      os << "<text x=\"" << num(v.px(w.x0) - 6) << "\" y=\"" << num(v.py(y) + 0.35 * font_px)
         << "\" text-anchor=\"end\" class=\"tick\">" << num(y, step < 1.0 ? 1 : 0) << "</text>\n";
  }
  return os.str();
}

}  // namespace detail

/// Writes the map to `file`. Throws sylva::Error (kInvalidArgument) if it cannot be written.
inline void writeSvgMap(const std::string& file, const SvgMapData& d) {
  using namespace detail;
  // ---- world extent: everything that is drawn, plus a margin
  Box world{1e300, 1e300, -1e300, -1e300};
  for (const auto* set : {&d.true_path, &d.estimated_path, &d.odometry_path, &d.true_landmarks})
    for (const Vec<2>& p : *set) world.include(p);
  for (const auto& e : d.estimated_landmarks) world.include(e.mean);
  const double margin = 2.0;
  world = Box{world.x0 - margin, world.y0 - margin, world.x1 + margin, world.y1 + margin};

  // ---- page layout
  const double plot_width = 980.0;
  const double scale = plot_width / world.width();
  const double plot_height = world.height() * scale;
  const double left = 70.0;
  const double header = 40.0 + 20.0 * static_cast<double>(d.subtitle_lines.size()) + 16.0;
  const double top = header;
  const double side_x = left + plot_width + 30.0;  // legend and inset column
  const double side_width = 340.0;
  const View main{world, left, top, scale};

  // Inset: a square window over the patch of estimated landmarks with the largest ellipses
  // (the greatest sum of their 2-sigma major semi-axes), where the ellipses are big enough to
  // compare with the true positions.
  const double inset_half_m = 2.5;
  const double inset_px = side_width;
  Vec<2> focus = d.true_final_pose.head<2>();
  {
    double best = -1.0;
    for (const auto& a : d.estimated_landmarks) {
      Vec<2> sum = Vec<2>::Zero();
      double weight = 0.0;
      for (const auto& b : d.estimated_landmarks) {
        const Vec<2> delta = (b.mean - a.mean).cwiseAbs();
        if (delta.x() < inset_half_m - 0.5 && delta.y() < inset_half_m - 0.5) {
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
  }
  const Box inset_world{focus.x() - inset_half_m,
                        focus.y() - inset_half_m,
                        focus.x() + inset_half_m,
                        focus.y() + inset_half_m};
  const double legend_height = 250.0;
  const double inset_top = top + legend_height + 40.0;
  const View inset{inset_world, side_x, inset_top, inset_px / (2.0 * inset_half_m)};
  const double zoom = inset.scale / main.scale;

  const double page_width = side_x + side_width + 30.0;
  const double page_height = std::max(top + plot_height + 60.0, inset_top + inset_px + 60.0);

  std::ostringstream svg;
  svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << num(page_width, 0)
      << "\" height=\"" << num(page_height, 0) << "\" viewBox=\"0 0 " << num(page_width, 0) << " "
      << num(page_height, 0) << "\" font-family=\"DejaVu Sans, Helvetica, Arial, sans-serif\">\n";
  svg << "<style>\n"
         "  .grid { stroke: #e3e3e3; stroke-width: 1; }\n"
         "  .tick { font-size: 12px; fill: #555; }\n"
         "  .frame { fill: none; stroke: #888; stroke-width: 1; }\n"
         "  .label { font-size: 13px; fill: #222; }\n"
         "  .truepath { stroke: #222; stroke-width: 1.6; }\n"
         "  .estpath { stroke: #1f6fd1; stroke-width: 1.6; }\n"
         "  .odopath { stroke: #d62728; stroke-width: 1.4; stroke-dasharray: 6 4; }\n"
         "  .truelm { stroke: #222; stroke-width: 1.4; }\n"
         "  .unmapped { stroke: #aaa; stroke-width: 1.2; }\n"
         "  .estlm { fill: #f08c00; }\n"
         "  .ell { fill: #f08c00; fill-opacity: 0.18; stroke: #c06a00; stroke-width: 1; }\n"
         "  .robotell { fill: #1f6fd1; fill-opacity: 0.15; stroke: #1f6fd1; stroke-width: 1; }\n"
         "  .fov { fill: #1f6fd1; fill-opacity: 0.05; stroke: #1f6fd1; stroke-opacity: 0.35; "
         "stroke-width: 1; }\n"
         "</style>\n";
  svg << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  svg << "<text x=\"" << num(left)
      << "\" y=\"28\" font-size=\"20\" font-weight=\"bold\" fill=\"#111\">" << escape(d.title)
      << "</text>\n";
  for (std::size_t i = 0; i < d.subtitle_lines.size(); ++i)
    svg << "<text x=\"" << num(left) << "\" y=\"" << num(50.0 + 20.0 * static_cast<double>(i))
        << "\" font-size=\"14\" fill=\"#333\">" << escape(d.subtitle_lines[i]) << "</text>\n";

  // ---- main map
  const double step = niceStep(std::max(world.width(), world.height()), 12.0);
  svg << "<g id=\"map\">\n";
  svg << "<clipPath id=\"mapclip\"><rect x=\"" << num(left) << "\" y=\"" << num(top)
      << "\" width=\"" << num(plot_width) << "\" height=\"" << num(plot_height)
      << "\"/></clipPath>\n";
  svg << grid(main, step, true, 12);
  svg << "<rect x=\"" << num(left) << "\" y=\"" << num(top) << "\" width=\"" << num(plot_width)
      << "\" height=\"" << num(plot_height) << "\" class=\"frame\"/>\n";
  svg << "<text x=\"" << num(left + 0.5 * plot_width) << "\" y=\"" << num(top + plot_height + 36)
      << "\" text-anchor=\"middle\" class=\"label\">x [m]</text>\n";
  svg << "<text transform=\"rotate(-90 " << num(left - 46) << " " << num(top + 0.5 * plot_height)
      << ")\" x=\"" << num(left - 46) << "\" y=\"" << num(top + 0.5 * plot_height)
      << "\" text-anchor=\"middle\" class=\"label\">y [m]</text>\n";
  svg << "<g clip-path=\"url(#mapclip)\">\n";
  // Sensor footprint at the final pose.
  {
    const double r = d.sensor_range_fov[0];
    const double half = d.sensor_range_fov[1];
    const Vec<3>& p = d.true_final_pose;
    const Vec<2> a = p.head<2>() + r * Vec<2>(std::cos(p[2] - half), std::sin(p[2] - half));
    const Vec<2> b = p.head<2>() + r * Vec<2>(std::cos(p[2] + half), std::sin(p[2] + half));
    svg << "<path d=\"M" << num(main.px(p[0])) << " " << num(main.py(p[1])) << "L"
        << num(main.px(a.x())) << " " << num(main.py(a.y())) << "A" << num(r * scale) << " "
        << num(r * scale) << " 0 " << (half > 0.5 * sylva::kPi ? 1 : 0) << " 0 "
        << num(main.px(b.x())) << " " << num(main.py(b.y())) << "Z\" class=\"fov\"/>\n";
  }
  for (const auto& w : d.walls)
    svg << "<line x1=\"" << num(main.px(w.first.x())) << "\" y1=\"" << num(main.py(w.first.y())) << "\" x2=\""
        << num(main.px(w.second.x())) << "\" y2=\"" << num(main.py(w.second.y()))
        << "\" stroke=\"#9a9a9a\" stroke-width=\"3\"/>\n";
  svg << polyline(main, d.odometry_path, "class=\"odopath\"");
  svg << polyline(main, d.true_path, "class=\"truepath\"");
  svg << polyline(main, d.estimated_path, "class=\"estpath\"");
  for (std::size_t i = 0; i < d.true_landmarks.size(); ++i)
    svg << cross(main,
                 d.true_landmarks[i],
                 4.0,
                 d.true_landmark_mapped[i] ? "class=\"truelm\"" : "class=\"unmapped\"");
  for (const auto& e : d.estimated_landmarks) {
    svg << ellipse(main, e.mean, e.covariance, 2.0, "class=\"ell\"");
    svg << "<circle cx=\"" << num(main.px(e.mean.x())) << "\" cy=\"" << num(main.py(e.mean.y()))
        << "\" r=\"2.2\" class=\"estlm\"/>\n";
  }
  svg << robot(main, d.true_final_pose, 9.0, "fill=\"#222\"");
  svg << robot(main, d.estimated_final_pose, 9.0, "fill=\"#1f6fd1\" fill-opacity=\"0.8\"");
  svg << "</g>\n";
  // Start marker and inset window.
  svg << "<circle cx=\"" << num(main.px(d.start_pose[0])) << "\" cy=\""
      << num(main.py(d.start_pose[1]))
      << "\" r=\"5\" fill=\"none\" stroke=\"#222\" stroke-width=\"1.5\"/>\n";
  svg << "<text x=\"" << num(main.px(d.start_pose[0]) + 8) << "\" y=\""
      << num(main.py(d.start_pose[1]) + 18) << "\" class=\"tick\">start</text>\n";
  svg << "<rect x=\"" << num(main.px(inset_world.x0)) << "\" y=\"" << num(main.py(inset_world.y1))
      << "\" width=\"" << num(inset_world.width() * scale) << "\" height=\""
      << num(inset_world.height() * scale)
      << "\" fill=\"none\" stroke=\"#555\" stroke-width=\"1\" "
         "stroke-dasharray=\"3 2\"/>\n";
  // Scale bar (bottom left, inside the frame).
  {
    const double bar_m = step;
    const double x0 = left + 16.0;
    const double y0 = top + plot_height - 18.0;
    svg << "<rect x=\"" << num(x0 - 6) << "\" y=\"" << num(y0 - 20) << "\" width=\""
        << num(bar_m * scale + 12) << "\" height=\"28\" fill=\"white\" fill-opacity=\"0.85\"/>\n";
    svg << "<path d=\"M" << num(x0) << " " << num(y0 - 4) << "V" << num(y0) << "H"
        << num(x0 + bar_m * scale) << "V" << num(y0 - 4)
        << "\" fill=\"none\" stroke=\"#222\" stroke-width=\"2\"/>\n";
    svg << "<text x=\"" << num(x0 + 0.5 * bar_m * scale) << "\" y=\"" << num(y0 - 7)
        << "\" text-anchor=\"middle\" class=\"tick\">" << num(bar_m, 0) << " m</text>\n";
  }
  svg << "</g>\n";

  // ---- legend
  {
    const double x = side_x;
    double y = top + 8.0;
    svg << "<g id=\"legend\">\n";
    svg << "<rect x=\"" << num(x - 10) << "\" y=\"" << num(top - 6) << "\" width=\""
        << num(side_width + 10) << "\" height=\"" << num(legend_height)
        << "\" fill=\"#fafafa\" stroke=\"#ccc\"/>\n";
    auto line_entry = [&](const std::string& cls, const std::string& text) {
      svg << "<line x1=\"" << num(x) << "\" y1=\"" << num(y + 6) << "\" x2=\"" << num(x + 34)
          << "\" y2=\"" << num(y + 6) << "\" class=\"" << cls << "\"/>\n";
      svg << "<text x=\"" << num(x + 44) << "\" y=\"" << num(y + 10) << "\" class=\"label\">"
          << escape(text) << "</text>\n";
      y += 24.0;
    };
    line_entry("truepath", "true path");
    line_entry("estpath", "EKF-SLAM estimate");
    line_entry("odopath", "odometry only (dead reckoning)");
    auto symbol_entry = [&](const std::string& symbol, const std::string& text) {
      svg << symbol;
      svg << "<text x=\"" << num(x + 44) << "\" y=\"" << num(y + 10) << "\" class=\"label\">"
          << escape(text) << "</text>\n";
      y += 24.0;
    };
    const View legend_view{Box{0, 0, 1, 1}, 0.0, 0.0, 1.0};  // identity: world = pixels
    auto at = [&](double px, double py) { return Vec<2>(px, 1.0 - py); };
    symbol_entry(cross(legend_view, at(x + 17, y + 6), 4.0, "class=\"truelm\""), "true landmark");
    symbol_entry(cross(legend_view, at(x + 17, y + 6), 4.0, "class=\"unmapped\""),
                 "true landmark, never seen");
    symbol_entry("<ellipse cx=\"" + num(x + 17) + "\" cy=\"" + num(y + 6) +
                     "\" rx=\"12\" ry=\"6\" class=\"ell\"/><circle cx=\"" + num(x + 17) +
                     "\" cy=\"" + num(y + 6) + "\" r=\"2.2\" class=\"estlm\"/>\n",
                 "estimated landmark, 2-sigma ellipse");
    symbol_entry(robot(legend_view, Vec<3>(x + 17, 1.0 - (y + 6), 0.0), 9.0, "fill=\"#222\""),
                 "true final pose");
    symbol_entry(robot(legend_view,
                       Vec<3>(x + 17, 1.0 - (y + 6), 0.0),
                       9.0,
                       "fill=\"#1f6fd1\" fill-opacity=\"0.8\""),
                 "estimated final pose, 2-sigma");
    symbol_entry("<path d=\"M" + num(x + 4) + " " + num(y + 12) + "L" + num(x + 30) + " " + num(y) +
                     "A28 28 0 0 1 " + num(x + 30) + " " + num(y + 24) + "Z\" class=\"fov\"/>\n",
                 "sensor range and field of view");
    svg << "</g>\n";
  }

  // ---- inset
  {
    svg << "<g id=\"inset\">\n";
    svg << "<text x=\"" << num(side_x) << "\" y=\"" << num(inset_top - 10) << "\" class=\"label\">"
        << "detail (dashed box), " << num(zoom, 0) << "x enlarged, grid 1 m</text>\n";
    svg << "<clipPath id=\"insetclip\"><rect x=\"" << num(side_x) << "\" y=\"" << num(inset_top)
        << "\" width=\"" << num(inset_px) << "\" height=\"" << num(inset_px) << "\"/></clipPath>\n";
    svg << "<rect x=\"" << num(side_x) << "\" y=\"" << num(inset_top) << "\" width=\""
        << num(inset_px) << "\" height=\"" << num(inset_px) << "\" fill=\"white\"/>\n";
    svg << grid(inset, 1.0, false, 11);
    svg << "<g clip-path=\"url(#insetclip)\">\n";
    svg << polyline(inset, d.odometry_path, "class=\"odopath\"");
    svg << polyline(inset, d.true_path, "class=\"truepath\"");
    svg << polyline(inset, d.estimated_path, "class=\"estpath\"");
    for (std::size_t i = 0; i < d.true_landmarks.size(); ++i)
      svg << cross(inset,
                   d.true_landmarks[i],
                   5.0,
                   d.true_landmark_mapped[i] ? "class=\"truelm\"" : "class=\"unmapped\"");
    for (const auto& e : d.estimated_landmarks) {
      svg << ellipse(inset, e.mean, e.covariance, 2.0, "class=\"ell\"");
      svg << "<circle cx=\"" << num(inset.px(e.mean.x())) << "\" cy=\"" << num(inset.py(e.mean.y()))
          << "\" r=\"2.5\" class=\"estlm\"/>\n";
    }
    svg << ellipse(inset,
                   d.estimated_final_pose.head<2>(),
                   d.final_position_covariance,
                   2.0,
                   "class=\"robotell\"");
    svg << robot(inset, d.true_final_pose, 10.0, "fill=\"#222\"");
    svg << robot(inset, d.estimated_final_pose, 10.0, "fill=\"#1f6fd1\" fill-opacity=\"0.8\"");
    svg << "</g>\n";
    svg << "<rect x=\"" << num(side_x) << "\" y=\"" << num(inset_top) << "\" width=\""
        << num(inset_px) << "\" height=\"" << num(inset_px) << "\" class=\"frame\"/>\n";
    // 1 m scale bar.
    const double x0 = side_x + 12.0;
    const double y0 = inset_top + inset_px - 12.0;
    svg << "<path d=\"M" << num(x0) << " " << num(y0 - 4) << "V" << num(y0) << "H"
        << num(x0 + inset.scale) << "V" << num(y0 - 4)
        << "\" fill=\"none\" stroke=\"#222\" stroke-width=\"2\"/>\n";
    svg << "<text x=\"" << num(x0 + 0.5 * inset.scale) << "\" y=\"" << num(y0 - 7)
        << "\" text-anchor=\"middle\" class=\"tick\">1 m</text>\n";
    svg << "</g>\n";
  }
  svg << "</svg>\n";

  std::ofstream out(file);
  if (!out)
    sylva::fail(sylva::ErrorCode::kInvalidArgument,
                "cannot open SVG file '" + file + "' for writing");
  out << svg.str();
  if (!out)
    sylva::fail(sylva::ErrorCode::kInvalidArgument, "could not write SVG file '" + file + "'");
}

}  // namespace range_bearing_slam
