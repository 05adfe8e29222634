#pragma once
// SVG pictures for the example programs: a document with the few shapes they draw (text,
// lines, circles, polylines, dots, crosses, arrows, covariance ellipses), a frame that maps
// world coordinates onto the page (maps: one scale for x and y; charts: one per axis; y up in
// both), and what every picture repeats: title, grid, axes with ticks and labels, scale bar,
// legend. Numbers are written with a fixed number of decimals, so the same data give the
// same file byte for byte. Presentation code of the examples: include/sylva never uses it.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <fstream>
#include <iomanip>
#include <limits>
#include <locale>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Eigenvalues>

#include <sylva/core/angles.hpp>
#include <sylva/core/error.hpp>
#include <sylva/core/types.hpp>

namespace sylva_examples::svg {

using Point = sylva::Vec<2>;

/// `v` with `digits` decimals in the classic locale; a negative zero is written "0".
inline std::string num(double v, int digits = 2) {
  std::ostringstream os;
  os.imbue(std::locale::classic());
  os << std::fixed << std::setprecision(digits) << v;
  std::string s = os.str();
  if (s.size() > 1 && s[0] == '-' && s.find_first_not_of("0.", 1) == std::string::npos)
    s.erase(0, 1);
  return s;
}

/// `text` safe inside an element or a quoted attribute.
inline std::string escape(const std::string& text) {
  std::string out;
  for (const char c : text) {
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
      case '\'':
        out += "&#39;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

/// A round step (1, 2 or 5 times a power of ten) giving about `target` steps over `extent`.
inline double niceStep(double extent, double target) {
  if (!(extent > 0.0) || !std::isfinite(extent) || !(target > 0.0)) return 1.0;
  const double raw = extent / target;
  const double power = std::pow(10.0, std::floor(std::log10(raw)));
  const double m = raw / power;
  return (m < 1.5 ? 1.0 : m < 3.5 ? 2.0 : m < 7.5 ? 5.0 : 10.0) * power;
}

/// Decimals that print every multiple of a round `step` exactly (0.5 -> 1, 20 -> 0).
inline int digitsFor(double step) {
  return std::clamp(static_cast<int>(std::ceil(-std::log10(step) - 1e-9)), 0, 6);
}

/// An axis-aligned box in world units; starts empty and grows by include().
struct Box {
  double x0 = std::numeric_limits<double>::infinity(), y0 = x0;
  double x1 = -std::numeric_limits<double>::infinity(), y1 = x1;

  void include(const Point& p, double radius = 0.0) {
    x0 = std::min(x0, p.x() - radius), y0 = std::min(y0, p.y() - radius);
    x1 = std::max(x1, p.x() + radius), y1 = std::max(y1, p.y() + radius);
  }
  bool empty() const { return !(x1 >= x0 && y1 >= y0); }
  Box grown(double margin) const { return Box{x0 - margin, y0 - margin, x1 + margin, y1 + margin}; }
  double width() const { return x1 - x0; }
  double height() const { return y1 - y0; }
};

/// World (or data) coordinates -> a rectangle of the page, y up in the world, down on the page.
struct Frame {
  Box world;
  double left = 0.0, top = 0.0, width = 1.0, height = 1.0;  ///< page rectangle (px)

  double xScale() const { return width / world.width(); }  ///< px per world unit along x
  double yScale() const { return height / world.height(); }
  double px(double x) const { return left + (x - world.x0) * xScale(); }
  double py(double y) const { return top + (world.y1 - y) * yScale(); }
  double right() const { return left + width; }
  double bottom() const { return top + height; }
};

/// A map: `px_per_unit` pixels per world unit on both axes.
inline Frame mapFrame(const Box& world, double left, double top, double px_per_unit) {
  return Frame{world, left, top, world.width() * px_per_unit, world.height() * px_per_unit};
}

/// A map as large as fits in `max_width` x `max_height` pixels.
inline Frame fitMap(
    const Box& world, double left, double top, double max_width, double max_height) {
  return mapFrame(
      world, left, top, std::min(max_width / world.width(), max_height / world.height()));
}

/// A chart: the data box stretched over the rectangle (each axis its own scale).
inline Frame chartFrame(const Box& data, double left, double top, double width, double height) {
  return Frame{data, left, top, width, height};
}

/// A picture being drawn. Methods that take a Frame take world coordinates, the others page
/// pixels; `attrs` are SVG attributes written as they are ("stroke=\"#222\"", "class=\"x\"").
class Document {
 public:
  /// A white page; coordinates are written with `digits` decimals, text at `font_px`.
  explicit Document(double width, double height, int digits = 2, double font_px = 13.0)
      : width_(width), height_(height), digits_(digits), font_px_(font_px) {}

  void resize(double width, double height) { width_ = width, height_ = height; }
  double width() const { return width_; }
  double height() const { return height_; }
  double fontPx() const { return font_px_; }
  std::string n(double v) const { return num(v, digits_); }

  /// A style sheet for class="..." attributes (shortens pictures of many equal shapes).
  void styleSheet(const std::string& css) { style_ = css; }

  void text(double x, double y, const std::string& s, const std::string& attrs = "") {
    body_ << "<text x=\"" << n(x) << "\" y=\"" << n(y) << "\"" << sep(attrs) << ">" << escape(s)
          << "</text>\n";
  }
  void line(double xa, double ya, double xb, double yb, const std::string& attrs) {
    body_ << "<line x1=\"" << n(xa) << "\" y1=\"" << n(ya) << "\" x2=\"" << n(xb) << "\" y2=\""
          << n(yb) << "\"" << sep(attrs) << "/>\n";
  }
  void rect(double x, double y, double w, double h, const std::string& attrs) {
    body_ << "<rect x=\"" << n(x) << "\" y=\"" << n(y) << "\" width=\"" << n(w) << "\" height=\""
          << n(h) << "\"" << sep(attrs) << "/>\n";
  }
  void circle(double x, double y, double r, const std::string& attrs) {
    body_ << "<circle cx=\"" << n(x) << "\" cy=\"" << n(y) << "\" r=\"" << n(r) << "\""
          << sep(attrs) << "/>\n";
  }
  void path(const std::string& d, const std::string& attrs) {
    body_ << "<path d=\"" << d << "\"" << sep(attrs) << "/>\n";
  }
  void polygon(const std::vector<Point>& page_points, const std::string& attrs) {
    body_ << "<polygon points=\"" << pointList(page_points) << "\"" << sep(attrs) << "/>\n";
  }
  /// An x-shaped mark, `half` px from the centre to each end.
  void cross(double x, double y, double half, const std::string& attrs) {
    path("M" + n(x - half) + " " + n(y - half) + "L" + n(x + half) + " " + n(y + half) + "M" +
             n(x - half) + " " + n(y + half) + "L" + n(x + half) + " " + n(y - half),
         attrs);
  }
  /// A triangle at (x, y) pointing along `heading` (radians, world convention: counter-
  /// clockwise from +x with y up), `size` px from the centre to the tip.
  void arrow(double x, double y, double heading, double size, const std::string& attrs) {
    const double c = std::cos(heading), s = -std::sin(heading);  // the page's y points down
    const auto corner = [&](double ahead, double aside) {
      return Point(x + size * (ahead * c - aside * s), y + size * (ahead * s + aside * c));
    };
    polygon({corner(1.0, 0.0), corner(-0.6, 0.5), corner(-0.6, -0.5)}, attrs);
  }

  /// A straight segment between two world points.
  void segment(const Frame& f, const Point& a, const Point& b, const std::string& attrs) {
    line(f.px(a.x()), f.py(a.y()), f.px(b.x()), f.py(b.y()), attrs);
  }

  /// A polyline through world points; a non-finite point breaks it into pieces.
  void polyline(const Frame& f, const std::vector<Point>& points, const std::string& attrs) {
    std::vector<Point> piece;
    for (std::size_t i = 0; i <= points.size(); ++i) {
      if (i < points.size() && points[i].allFinite()) {
        piece.emplace_back(f.px(points[i].x()), f.py(points[i].y()));
        continue;
      }
      if (piece.size() >= 2)
        body_ << "<polyline points=\"" << pointList(piece) << "\" fill=\"none\"" << sep(attrs)
              << "/>\n";
      piece.clear();
    }
  }

  /// Many world points as round dots `diameter` px wide, one <path> for all; points outside
  /// the frame and repeats within half a pixel are left out.
  void dots(const Frame& f,
            const std::vector<Point>& points,
            const std::string& colour,
            double diameter) {
    std::set<std::pair<long, long>> seen;
    std::string d;
    for (const Point& p : points) {
      const double x = f.px(p.x()), y = f.py(p.y());
      if (!(x >= f.left && x <= f.right() && y >= f.top && y <= f.bottom())) continue;
      if (seen.insert({std::lround(2.0 * x), std::lround(2.0 * y)}).second)
        d += "M" + n(x) + " " + n(y) + "h0";
    }
    if (!d.empty())
      path(d,
           "fill=\"none\" stroke=\"" + colour + "\" stroke-width=\"" + n(diameter) +
               "\" stroke-linecap=\"round\"");
  }

  /// The `k`-sigma ellipse of a world covariance, exact for any frame (the covariance is
  /// carried onto the page, whose y points down, before its axes are taken).
  void ellipse(const Frame& f,
               const Point& mean,
               const sylva::Mat<2, 2>& covariance,
               double k,
               const std::string& attrs) {
    const sylva::Mat<2, 2> to_page =
        (sylva::Vec<2>() << f.xScale(), -f.yScale()).finished().asDiagonal();
    const sylva::Mat<2, 2> page = to_page * (0.5 * (covariance + covariance.transpose())) * to_page;
    const Eigen::SelfAdjointEigenSolver<sylva::Mat<2, 2>> eig(page);
    const Point radii = k * eig.eigenvalues().cwiseMax(0.0).cwiseSqrt();  // ascending
    const Point major = eig.eigenvectors().col(1);
    const double x = f.px(mean.x()), y = f.py(mean.y());
    double degrees = std::atan2(major.y(), major.x()) * 180.0 / sylva::kPi;
    if (degrees > 90.0) degrees -= 180.0;  // an axis has no sign: keep the angle in (-90, 90]
    if (degrees <= -90.0) degrees += 180.0;
    body_ << "<ellipse cx=\"" << n(x) << "\" cy=\"" << n(y) << "\" rx=\""
          << num(radii[1], digits_ + 1) << "\" ry=\"" << num(radii[0], digits_ + 1)
          << "\" transform=\"rotate(" << num(degrees, 1) << " " << n(x) << " " << n(y) << ")\""
          << sep(attrs) << "/>\n";
  }

  /// Defines a clip path of the frame's rectangle; returns the attribute that applies it.
  std::string clipTo(const Frame& f) {
    const std::string id = "clip" + std::to_string(++clips_);
    body_ << "<clipPath id=\"" << id << "\"><rect x=\"" << n(f.left) << "\" y=\"" << n(f.top)
          << "\" width=\"" << n(f.width) << "\" height=\"" << n(f.height) << "\"/></clipPath>\n";
    return "clip-path=\"url(#" + id + ")\"";
  }
  /// A group: what is drawn until endGroup() shares `attrs`.
  void group(const std::string& attrs) {
    body_ << "<g" << sep(attrs) << ">\n";
    ++open_groups_;
  }
  void endGroup() {
    if (open_groups_ == 0)
      sylva::fail(sylva::ErrorCode::kInvalidArgument, "svg::Document: endGroup() without group()");
    body_ << "</g>\n";
    --open_groups_;
  }
  /// An element written as it is (the caller formats and escapes it).
  void raw(const std::string& element) { body_ << element << "\n"; }

  /// The whole picture. Throws sylva::Error (kInvalidArgument) while a group is open.
  std::string str() const {
    if (open_groups_ != 0)
      sylva::fail(sylva::ErrorCode::kInvalidArgument, "svg::Document: a group is not closed");
    std::ostringstream out;
    out << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << num(width_, 0) << "\" height=\""
        << num(height_, 0) << "\" viewBox=\"0 0 " << num(width_, 0) << " " << num(height_, 0)
        << "\" font-family=\"DejaVu Sans, Helvetica, Arial, sans-serif\" font-size=\""
        << num(font_px_, 0) << "\">\n";
    if (!style_.empty()) out << "<style>\n" << style_ << "</style>\n";
    out << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n" << body_.str() << "</svg>\n";
    return out.str();
  }
  /// Writes the picture to `file`; throws sylva::Error (kInvalidArgument) if it cannot.
  void write(const std::string& file) const {
    const std::string text = str();
    std::ofstream out(file, std::ios::binary);
    if (!out)
      sylva::fail(sylva::ErrorCode::kInvalidArgument,
                  "cannot open the SVG file '" + file + "' for writing");
    out << text;
    if (!out)
      sylva::fail(sylva::ErrorCode::kInvalidArgument,
                  "could not write the SVG file '" + file + "'");
  }

 private:
  static std::string sep(const std::string& attrs) { return attrs.empty() ? attrs : " " + attrs; }
  std::string pointList(const std::vector<Point>& page_points) const {
    std::string s;
    for (std::size_t i = 0; i < page_points.size(); ++i)
      s += (i ? " " : "") + n(page_points[i].x()) + "," + n(page_points[i].y());
    return s;
  }

  double width_, height_;
  int digits_;
  double font_px_;
  std::string style_;
  std::ostringstream body_;
  int clips_ = 0;
  int open_groups_ = 0;
};

/// Bold title and plain lines under it, from the top left; returns the first y below them.
inline double header(Document& doc,
                     double x,
                     const std::string& title,
                     const std::vector<std::string>& lines) {
  doc.text(x, 26, title, "font-size=\"18\" font-weight=\"bold\" fill=\"#111\"");
  for (std::size_t i = 0; i < lines.size(); ++i)
    doc.text(x, 48 + 18 * static_cast<double>(i), lines[i], "fill=\"#333\"");
  return 48 + 18 * static_cast<double>(lines.size());
}

/// Grid lines at the multiples of the steps inside the frame (a step of 0 draws none).
inline void grid(Document& doc,
                 const Frame& f,
                 double x_step,
                 double y_step,
                 const std::string& attrs = "stroke=\"#e4e4e4\"") {
  const Box& w = f.world;
  if (x_step > 0.0)
    for (auto i = static_cast<long>(std::ceil(w.x0 / x_step - 1e-9));
         i * x_step <= w.x1 + 1e-9 * x_step;
         ++i)
      doc.line(f.px(i * x_step), f.top, f.px(i * x_step), f.bottom(), attrs);
  if (y_step > 0.0)
    for (auto i = static_cast<long>(std::ceil(w.y0 / y_step - 1e-9));
         i * y_step <= w.y1 + 1e-9 * y_step;
         ++i)
      doc.line(f.left, f.py(i * y_step), f.right(), f.py(i * y_step), attrs);
}

/// What axes() draws around a frame.
struct Axes {
  std::string x_label, y_label;             ///< under the frame, and turned along its left side
  double x_step = 0.0, y_step = 0.0;        ///< between ticks; 0: a round step for about 8 and 6
  bool x_numbers = true, y_numbers = true;  ///< tick labels
};

/// Grid, frame, tick labels at the grid lines and axis labels.
inline void axes(Document& doc, const Frame& f, const Axes& a) {
  const Box& w = f.world;
  const double xs = a.x_step > 0.0 ? a.x_step : niceStep(w.width(), 8.0);
  const double ys = a.y_step > 0.0 ? a.y_step : niceStep(w.height(), 6.0);
  grid(doc, f, xs, ys);
  doc.rect(f.left, f.top, f.width, f.height, "fill=\"none\" stroke=\"#888\"");
  const std::string tick = "font-size=\"11\" fill=\"#555\"";
  if (a.x_numbers)
    for (auto i = static_cast<long>(std::ceil(w.x0 / xs - 1e-9)); i * xs <= w.x1 + 1e-9 * xs; ++i)
      doc.text(f.px(i * xs),
               f.bottom() + 14,
               num(i * xs, digitsFor(xs)),
               tick + " text-anchor=\"middle\"");
  std::size_t widest = 0;  // characters of the longest y tick label, to keep the y label clear
  if (a.y_numbers)
    for (auto i = static_cast<long>(std::ceil(w.y0 / ys - 1e-9)); i * ys <= w.y1 + 1e-9 * ys; ++i) {
      const std::string label = num(i * ys, digitsFor(ys));
      widest = std::max(widest, label.size());
      doc.text(f.left - 5, f.py(i * ys) + 4, label, tick + " text-anchor=\"end\"");
    }
  if (!a.x_label.empty())
    doc.text(f.left + 0.5 * f.width,
             f.bottom() + (a.x_numbers ? 32 : 18),
             a.x_label,
             "text-anchor=\"middle\"");
  if (!a.y_label.empty()) {
    const double x = f.left - 16 - 6.5 * static_cast<double>(widest), y = f.top + 0.5 * f.height;
    doc.text(x,
             y,
             a.y_label,
             "text-anchor=\"middle\" transform=\"rotate(-90 " + doc.n(x) + " " + doc.n(y) + ")\"");
  }
}

/// A scale bar `length_px` long from (x, y) to the right, its label centred above it; with
/// `backdrop`, on a white patch so that it reads over a busy map.
inline void scaleBar(Document& doc,
                     double x,
                     double y,
                     double length_px,
                     const std::string& label,
                     bool backdrop = true) {
  if (backdrop) doc.rect(x - 6, y - 21, length_px + 12, 27, "fill=\"white\" fill-opacity=\"0.85\"");
  doc.path("M" + doc.n(x) + " " + doc.n(y - 4) + "V" + doc.n(y) + "H" + doc.n(x + length_px) + "V" +
               doc.n(y - 4),
           "fill=\"none\" stroke=\"#222\" stroke-width=\"2\"");
  doc.text(x + 0.5 * length_px, y - 7, label, "font-size=\"11\" text-anchor=\"middle\"");
}

/// One legend row: a swatch (SVG drawn in a 24 x 12 px box from its top left corner, see
/// the swatch functions) and its label.
struct LegendEntry {
  std::string swatch;
  std::string label;
};

namespace swatch {
inline std::string line(const std::string& attrs) {
  return "<line x1=\"0\" y1=\"6\" x2=\"24\" y2=\"6\" " + attrs + "/>";
}
inline std::string dot(double radius, const std::string& attrs) {
  return "<circle cx=\"12\" cy=\"6\" r=\"" + num(radius, 1) + "\" " + attrs + "/>";
}
inline std::string box(const std::string& attrs) {
  return "<rect x=\"2\" y=\"0\" width=\"20\" height=\"12\" " + attrs + "/>";
}
inline std::string cross(const std::string& attrs) {
  return "<path d=\"M8 2L16 10M8 10L16 2\" " + attrs + "/>";
}
}  // namespace swatch

/// The entries from (x, y) down, one per row; with `wrap_width` > 0, side by side and on to
/// the next row when the next one would pass x + wrap_width. Returns the y below the last row.
inline double legend(Document& doc,
                     double x,
                     double y,
                     const std::vector<LegendEntry>& entries,
                     double wrap_width = 0.0) {
  const double row = doc.fontPx() + 8.0;
  double at = x;
  for (std::size_t i = 0; i < entries.size(); ++i) {
    const double item = 40.0 + 0.6 * doc.fontPx() * static_cast<double>(entries[i].label.size());
    if (i > 0 && (wrap_width <= 0.0 || at + item > x + wrap_width)) at = x, y += row;
    doc.raw("<g transform=\"translate(" + doc.n(at) + "," + doc.n(y) + ")\">" + entries[i].swatch +
            "</g>");
    doc.text(at + 30, y + 10, entries[i].label);
    at += item;
  }
  return entries.empty() ? y : y + row;
}

}  // namespace sylva_examples::svg
