#pragma once
// Hand-written SVG pictures of the moving_objects program. Output depends only on the data
// (fixed number formatting), so a run's pictures are reproducible byte for byte.
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
#include <fstream>
#include <iomanip>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include <sylva/core/angles.hpp>
#include <sylva/core/error.hpp>
#include <sylva/core/types.hpp>

#include "object_position.hpp"

namespace moving_objects::svg {

using sylva::Vec;

inline std::string num(double v, int digits = 1) {
  std::ostringstream os;
  os << std::fixed << std::setprecision(digits) << v;
  std::string s = os.str();
  if (s.find_first_not_of("-0.") == std::string::npos && s[0] == '-') s = s.substr(1);
  return s;
}

inline std::string escape(const std::string& text) {
  std::string out;
  for (const char c : text) {
    if (c == '&') out += "&amp;";
    else if (c == '<') out += "&lt;";
    else if (c == '>') out += "&gt;";
    else out += c;
  }
  return out;
}

/// World metres -> pixels in a panel, y up.
struct View {
  double x0, y0, x1, y1;       // world box
  double left, top, scale;     // panel origin (px) and px per metre
  double px(double x) const { return left + (x - x0) * scale; }
  double py(double y) const { return top + (y1 - y) * scale; }
  double width() const { return (x1 - x0) * scale; }
  double height() const { return (y1 - y0) * scale; }
};

class Document {
 public:
  Document(double width, double height) : width_(width), height_(height) {}
  std::ostringstream& body() { return body_; }

  void text(double x, double y, const std::string& s, double size = 13, const std::string& extra = "") {
    body_ << "<text x=\"" << num(x) << "\" y=\"" << num(y) << "\" font-size=\"" << num(size) << "\"" << extra
          << ">" << escape(s) << "</text>\n";
  }
  void line(const View& v, const Vec<2>& a, const Vec<2>& b, const std::string& style) {
    body_ << "<line x1=\"" << num(v.px(a.x())) << "\" y1=\"" << num(v.py(a.y())) << "\" x2=\"" << num(v.px(b.x()))
          << "\" y2=\"" << num(v.py(b.y())) << "\" " << style << "/>\n";
  }
  void polyline(const View& v, const std::vector<Vec<2>>& points, const std::string& style) {
    if (points.size() < 2) return;
    body_ << "<polyline fill=\"none\" " << style << " points=\"";
    for (std::size_t i = 0; i < points.size(); ++i)
      body_ << (i ? " " : "") << num(v.px(points[i].x())) << "," << num(v.py(points[i].y()));
    body_ << "\"/>\n";
  }
  void circle(const View& v, const Vec<2>& c, double radius_px, const std::string& style) {
    body_ << "<circle cx=\"" << num(v.px(c.x())) << "\" cy=\"" << num(v.py(c.y())) << "\" r=\"" << num(radius_px, 2)
          << "\" " << style << "/>\n";
  }
  void worldCircle(const View& v, const Vec<2>& c, double radius_m, const std::string& style) {
    circle(v, c, radius_m * v.scale, style);
  }
  void box(const View& v, const Box2& b, const std::string& style) {
    body_ << "<rect x=\"" << num(v.px(b.min.x())) << "\" y=\"" << num(v.py(b.max.y())) << "\" width=\""
          << num(std::max(1.0, (b.max.x() - b.min.x()) * v.scale)) << "\" height=\""
          << num(std::max(1.0, (b.max.y() - b.min.y()) * v.scale)) << "\" " << style << "/>\n";
  }
  void star(const View& v, const Vec<2>& c, double r_px, const std::string& style) {
    body_ << "<polygon " << style << " points=\"";
    for (int k = 0; k < 10; ++k) {
      const double a = -sylva::kPi / 2 + k * sylva::kPi / 5;
      const double r = (k % 2 == 0) ? r_px : 0.45 * r_px;
      body_ << (k ? " " : "") << num(v.px(c.x()) + r * std::cos(a)) << "," << num(v.py(c.y()) + r * std::sin(a));
    }
    body_ << "\"/>\n";
  }
  /// Metre grid with labels every `step` metres inside the view, and a frame.
  void grid(const View& v, double step) {
    body_ << "<g stroke=\"#e6e6e6\" stroke-width=\"1\">\n";
    for (double x = std::ceil(v.x0 / step) * step; x <= v.x1 + 1e-9; x += step)
      body_ << "<line x1=\"" << num(v.px(x)) << "\" y1=\"" << num(v.top) << "\" x2=\"" << num(v.px(x)) << "\" y2=\""
            << num(v.top + v.height()) << "\"/>\n";
    for (double y = std::ceil(v.y0 / step) * step; y <= v.y1 + 1e-9; y += step)
      body_ << "<line x1=\"" << num(v.left) << "\" y1=\"" << num(v.py(y)) << "\" x2=\"" << num(v.left + v.width())
            << "\" y2=\"" << num(v.py(y)) << "\"/>\n";
    body_ << "</g>\n";
    const int digits = step < 1.0 ? 1 : 0;
    body_ << "<g font-size=\"10\" fill=\"#666\">\n";
    for (double x = std::ceil(v.x0 / step) * step; x <= v.x1 + 1e-9; x += step)
      body_ << "<text x=\"" << num(v.px(x)) << "\" y=\"" << num(v.top + v.height() + 12) << "\" text-anchor=\"middle\">"
            << num(x, digits) << "</text>\n";
    for (double y = std::ceil(v.y0 / step) * step; y <= v.y1 + 1e-9; y += step)
      body_ << "<text x=\"" << num(v.left - 4) << "\" y=\"" << num(v.py(y) + 3) << "\" text-anchor=\"end\">" << num(y, digits)
            << "</text>\n";
    body_ << "</g>\n";
    body_ << "<rect x=\"" << num(v.left) << "\" y=\"" << num(v.top) << "\" width=\"" << num(v.width()) << "\" height=\""
          << num(v.height()) << "\" fill=\"none\" stroke=\"#999\"/>\n";
  }
  /// Legend entries: (svg snippet drawn in a 20x12 box at the origin, label).
  void legend(double x, double y, const std::vector<std::pair<std::string, std::string>>& entries, double row = 17) {
    for (std::size_t i = 0; i < entries.size(); ++i) {
      const double yy = y + i * row;
      body_ << "<g transform=\"translate(" << num(x) << "," << num(yy - 9) << ")\">" << entries[i].first << "</g>\n";
      text(x + 26, yy + 1, entries[i].second, 12);
    }
  }

  void write(const std::string& path) const {
    std::ofstream out(path);
    if (!out) sylva::fail(sylva::ErrorCode::kInvalidArgument, "cannot write the SVG file '" + path + "'");
    out << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << num(width_, 0) << "\" height=\"" << num(height_, 0)
        << "\" viewBox=\"0 0 " << num(width_, 0) << " " << num(height_, 0)
        << "\" font-family=\"DejaVu Sans, Arial, sans-serif\">\n"
        << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
        << body_.str() << "</svg>\n";
    if (!out) sylva::fail(sylva::ErrorCode::kInvalidArgument, "writing the SVG file '" + path + "' failed");
  }

 private:
  double width_, height_;
  std::ostringstream body_;
};

/// A view of the world box [x0, x1] x [y0, y1] scaled to fit `max_w` x `max_h` pixels.
inline View fit(double x0, double y0, double x1, double y1, double left, double top, double max_w, double max_h) {
  const double scale = std::min(max_w / (x1 - x0), max_h / (y1 - y0));
  return View{x0, y0, x1, y1, left, top, scale};
}

}  // namespace moving_objects::svg
