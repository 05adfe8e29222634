#pragma once
// A small hand-written SVG toolkit for the parking example's pictures: a canvas that
// collects elements, a linear data-to-page frame, and plot axes with a grid and ticks.
// Fixed number formatting, so a picture depends only on its data (bit for bit).

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <sylva/core/error.hpp>

namespace parking::svg {

inline std::string num(double v, int digits = 2) {
  std::ostringstream os;
  os << std::fixed << std::setprecision(digits) << v;
  std::string s = os.str();
  if (s.size() > 1 && s[0] == '-' && s.find_first_not_of("-0.") == std::string::npos)
    s = s.substr(1);  // no "-0.00"
  return s;
}

inline std::string escape(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '<')
      out += "&lt;";
    else if (c == '>')
      out += "&gt;";
    else if (c == '&')
      out += "&amp;";
    else if (c == '"')
      out += "&quot;";
    else
      out += c;
  }
  return out;
}

/// Maps data coordinates into a rectangle of the page (y up in data, down on the page).
struct Frame {
  double x0 = 0, x1 = 1, y0 = 0, y1 = 1;            ///< data range
  double left = 0, top = 0, width = 1, height = 1;  ///< page rectangle (px)
  double px(double x) const { return left + (x - x0) / (x1 - x0) * width; }
  double py(double y) const { return top + (y1 - y) / (y1 - y0) * height; }
};

using Points = std::vector<std::pair<double, double>>;  ///< data coordinates

class Canvas {
 public:
  Canvas(double width, double height) : width_(width), height_(height) {}

  void raw(const std::string& element) { body_ << element << "\n"; }

  void text(double x, double y, const std::string& s, const std::string& attrs = "") {
    body_ << "<text x=\"" << num(x) << "\" y=\"" << num(y) << "\" " << attrs << ">" << escape(s)
          << "</text>\n";
  }

  void line(double xa, double ya, double xb, double yb, const std::string& style) {
    body_ << "<line x1=\"" << num(xa) << "\" y1=\"" << num(ya) << "\" x2=\"" << num(xb)
          << "\" y2=\"" << num(yb) << "\" " << style << "/>\n";
  }

  void rect(double x, double y, double w, double h, const std::string& style) {
    body_ << "<rect x=\"" << num(x) << "\" y=\"" << num(y) << "\" width=\"" << num(w)
          << "\" height=\"" << num(h) << "\" " << style << "/>\n";
  }

  void circle(double x, double y, double r, const std::string& style) {
    body_ << "<circle cx=\"" << num(x) << "\" cy=\"" << num(y) << "\" r=\"" << num(r) << "\" "
          << style << "/>\n";
  }

  /// A polyline of data points through `f`; NaN points break the line.
  void polyline(const Frame& f, const Points& points, const std::string& style) {
    std::ostringstream os;
    bool open = false;
    for (const auto& [x, y] : points) {
      if (!std::isfinite(x) || !std::isfinite(y)) {
        if (open) os << "\"/>\n";
        open = false;
        continue;
      }
      if (!open)
        os << "<polyline fill=\"none\" " << style << " points=\"";
      else
        os << " ";
      os << num(f.px(x)) << "," << num(f.py(y));
      open = true;
    }
    if (open) os << "\"/>\n";
    body_ << os.str();
  }

  /// A filled triangle pointing along `heading` (radians, page-independent: data frame with
  /// equal scales assumed), centred at data point (x, y), `size` px long.
  void arrowhead(
      const Frame& f, double x, double y, double heading, double size, const std::string& style) {
    const double cx = f.px(x), cy = f.py(y);
    const double c = std::cos(heading), s = -std::sin(heading);  // page y points down
    const double tip_x = cx + size * c, tip_y = cy + size * s;
    const double bx = cx - 0.5 * size * c, by = cy - 0.5 * size * s;
    const double w = 0.45 * size;
    body_ << "<polygon points=\"" << num(tip_x) << "," << num(tip_y) << " " << num(bx - w * s)
          << "," << num(by + w * c) << " " << num(bx + w * s) << "," << num(by - w * c) << "\" "
          << style << "/>\n";
  }

  /// Writes the picture; throws sylva::Error(kInvalidArgument) if the file cannot be written.
  void write(const std::string& path) const {
    std::ofstream out(path);
    if (!out)
      sylva::fail(sylva::ErrorCode::kInvalidArgument, "cannot write the SVG file '" + path + "'");
    out << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << num(width_, 0) << "\" height=\""
        << num(height_, 0) << "\" viewBox=\"0 0 " << num(width_, 0) << " " << num(height_, 0)
        << "\" font-family=\"DejaVu Sans, Helvetica, Arial, sans-serif\" font-size=\"12\">\n"
        << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
        << body_.str() << "</svg>\n";
    if (!out)
      sylva::fail(sylva::ErrorCode::kInvalidArgument, "cannot write the SVG file '" + path + "'");
  }

 private:
  double width_, height_;
  std::ostringstream body_;
};

/// A round tick step (1, 2 or 5 times a power of ten) giving about `target` ticks.
inline double niceStep(double range, int target) {
  if (!(range > 0.0) || !std::isfinite(range)) return 1.0;
  const double raw = range / std::max(target, 1);
  const double power = std::pow(10.0, std::floor(std::log10(raw)));
  const double m = raw / power;
  return (m < 1.5 ? 1.0 : m < 3.5 ? 2.0 : m < 7.5 ? 5.0 : 10.0) * power;
}

/// Digits needed to print multiples of `step` exactly enough.
inline int digitsFor(double step) {
  return std::clamp(static_cast<int>(std::ceil(-std::log10(step) - 1e-9)), 0, 6);
}

/// Frame box, grid, tick labels and axis labels.
inline void axes(Canvas& c,
                 const Frame& f,
                 const std::string& x_label,
                 const std::string& y_label,
                 int x_ticks = 8,
                 int y_ticks = 6,
                 bool x_tick_labels = true) {
  const double xs = niceStep(f.x1 - f.x0, x_ticks);
  const double ys = niceStep(f.y1 - f.y0, y_ticks);
  const std::string grid = "stroke=\"#e4e4e4\" stroke-width=\"1\"";
  for (double x = std::ceil(f.x0 / xs - 1e-9) * xs; x <= f.x1 + 1e-9 * xs; x += xs) {
    c.line(f.px(x), f.top, f.px(x), f.top + f.height, grid);
    if (x_tick_labels)
      c.text(f.px(x),
             f.top + f.height + 15,
             num(x, digitsFor(xs)),
             "text-anchor=\"middle\" fill=\"#333\"");
  }
  for (double y = std::ceil(f.y0 / ys - 1e-9) * ys; y <= f.y1 + 1e-9 * ys; y += ys) {
    c.line(f.left, f.py(y), f.left + f.width, f.py(y), grid);
    c.text(f.left - 6, f.py(y) + 4, num(y, digitsFor(ys)), "text-anchor=\"end\" fill=\"#333\"");
  }
  c.rect(f.left, f.top, f.width, f.height, "fill=\"none\" stroke=\"#555\" stroke-width=\"1\"");
  if (!x_label.empty())
    c.text(f.left + 0.5 * f.width, f.top + f.height + 33, x_label, "text-anchor=\"middle\"");
  if (!y_label.empty()) {
    const double x = f.left - 48, y = f.top + 0.5 * f.height;
    c.text(x,
           y,
           y_label,
           "text-anchor=\"middle\" transform=\"rotate(-90 " + num(x) + " " + num(y) + ")\"");
  }
}

/// One legend entry: a short line (or a marker) and its label; returns the next entry's y.
inline double legendEntry(Canvas& c,
                          double x,
                          double y,
                          const std::string& style,
                          const std::string& label,
                          bool marker = false) {
  if (marker)
    c.circle(x + 11, y - 4, 3.5, style);
  else
    c.line(x, y - 4, x + 22, y - 4, style);
  c.text(x + 28, y, label);
  return y + 17;
}

}  // namespace parking::svg
