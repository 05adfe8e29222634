// The examples' SVG helper (examples/common/svg_plot.hpp): escaping, number formatting,
// the world-to-page mapping of maps and charts, covariance ellipses, the scale bar, legend
// layout, well-formed and reproducible output.
#include "sylva_catch.hpp"

#include <cmath>
#include <fstream>
#include <iterator>
#include <limits>
#include <regex>
#include <string>
#include <vector>

#include <sylva/core/angles.hpp>

#include "common/svg_plot.hpp"
#include "error_helpers.hpp"
#include "temp_folder.hpp"

namespace unity_common_svg_plot {

namespace svg = sylva_examples::svg;
using svg::Point;
using sylva::ErrorCode;
using sylva_test::throwsCode;

/// How often `part` occurs in `text`.
std::size_t count(const std::string& text, const std::string& part) {
  std::size_t n = 0;
  for (auto at = text.find(part); at != std::string::npos; at = text.find(part, at + part.size()))
    ++n;
  return n;
}

/// Whether every element of `text` that opens also closes, in order, under one <svg> root.
bool balanced(const std::string& text) {
  static const std::regex tag("<(/?)([a-zA-Z]+)[^<>]*?(/?)>");
  std::vector<std::string> open;
  int roots = 0;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), tag); it != std::sregex_iterator();
       ++it) {
    const std::smatch& m = *it;
    if (m[3] == "/") {
      if (open.empty()) return false;  // an element outside the root
      continue;
    }
    if (m[1] == "/") {
      if (open.empty() || open.back() != m[2]) return false;
      open.pop_back();
    } else {
      if (open.empty() && (m[2] != "svg" || ++roots > 1)) return false;
      open.push_back(m[2]);
    }
  }
  return open.empty() && roots == 1;
}

/// A picture with every kind of element the helper writes.
std::string everything() {
  svg::Document doc(400, 300);
  doc.styleSheet(".a { fill: red; }\n");
  const svg::Frame f =
      svg::mapFrame({-10, -5, 10, 5}, 50, svg::header(doc, 50, "A & B", {"x < y > z"}), 15);
  svg::axes(doc, f, {"x [m]", "y [m]"});
  doc.group(doc.clipTo(f));
  doc.polyline(f, {Point(0, 0), Point(1, 1), Point(2, -1)}, "stroke=\"#222\"");
  doc.ellipse(
      f, Point(1, 1), (sylva::Mat<2, 2>() << 2, 0.5, 0.5, 1).finished(), 2.0, "class=\"a\"");
  doc.dots(f, {Point(0, 0), Point(3, 3)}, "#999", 2.0);
  doc.cross(f.px(1), f.py(2), 4, "stroke=\"black\"");
  doc.arrow(f.px(0), f.py(0), 0.5, 9, "fill=\"blue\"");
  doc.endGroup();
  doc.circle(10, 10, 3, "fill=\"none\" stroke=\"#000\"");
  svg::scaleBar(doc, f.left + 10, f.bottom() - 10, 5 * f.xScale(), "5 m");
  svg::legend(
      doc,
      10,
      250,
      {{svg::swatch::line("stroke=\"red\""), "a \"quoted\" label"}, {svg::swatch::cross(""), "x"}});
  return doc.str();
}

TEST_CASE("svg escape replaces the five XML specials and keeps the rest") {
  CHECK(svg::escape("a & b < c > d \"e\" 'f'") ==
        "a &amp; b &lt; c &gt; d &quot;e&quot; &#39;f&#39;");
  CHECK(svg::escape("plain 1.5 m, +-3 sigma") == "plain 1.5 m, +-3 sigma");
  CHECK(svg::escape("&amp;") == "&amp;amp;");  // escaped text is escaped again, not passed through
}

TEST_CASE("svg numbers have fixed decimals and no negative zero") {
  CHECK(svg::num(3.14159, 2) == "3.14");
  CHECK(svg::num(2.0, 0) == "2");
  CHECK(svg::num(1234567.891, 1) == "1234567.9");  // never in exponent form
  CHECK(svg::num(-1.5, 1) == "-1.5");
  CHECK(svg::num(-10.0, 0) == "-10");
  CHECK(svg::num(-0.01, 2) == "-0.01");
  CHECK(svg::num(-0.001, 2) == "0.00");
  CHECK(svg::num(-0.0, 0) == "0");
  CHECK(svg::num(-0.04, 1) == "0.0");
  svg::Document doc(10, 10, 1);
  CHECK(doc.n(0.24) == "0.2");  // the document's own number of decimals
  CHECK(doc.n(0.26) == "0.3");
}

TEST_CASE("svg round steps and their decimals") {
  CHECK(svg::niceStep(62.0, 12.0) == Approx(5.0));
  CHECK(svg::niceStep(1.0, 8.0) == Approx(0.1));
  CHECK(svg::niceStep(0.24, 6.0) == Approx(0.05));
  CHECK(svg::niceStep(900.0, 6.0) == Approx(200.0));
  CHECK(svg::digitsFor(0.5) == 1);
  CHECK(svg::digitsFor(0.05) == 2);
  CHECK(svg::digitsFor(20.0) == 0);
  CHECK(svg::digitsFor(1.0) == 0);
}

TEST_CASE("svg map frame puts a world point on the expected pixel, y up") {
  const svg::Frame f = svg::mapFrame({-10, -5, 10, 5}, 50, 20, 4);
  CHECK(f.width == Approx(80));
  CHECK(f.height == Approx(40));
  CHECK(f.px(-10) == Approx(50));
  CHECK(f.px(10) == Approx(130));
  CHECK(f.py(5) == Approx(20));  // the top of the world is the top of the frame
  CHECK(f.py(-5) == Approx(60));
  CHECK(f.px(2.5) == Approx(100));
  CHECK(f.py(1.0) == Approx(36));
  CHECK(f.py(2.0) < f.py(1.0));  // further up in the world, higher on the page

  const svg::Frame fit = svg::fitMap({0, 0, 20, 10}, 0, 0, 400, 400);
  CHECK(fit.xScale() == Approx(20));
  CHECK(fit.yScale() == Approx(20));
  CHECK(fit.height == Approx(200));

  const svg::Frame chart = svg::chartFrame({0, -1, 10, 1}, 100, 10, 500, 100);
  CHECK(chart.xScale() == Approx(50));
  CHECK(chart.yScale() == Approx(50));
  CHECK(chart.px(5) == Approx(350));
  CHECK(chart.py(1) == Approx(10));
  CHECK(chart.py(-1) == Approx(110));
  CHECK(chart.py(0) == Approx(60));
}

TEST_CASE("svg box grows around points and circles") {
  svg::Box b;
  CHECK(b.empty());
  b.include(Point(1, 2));
  b.include(Point(-3, 0), 0.5);
  CHECK_FALSE(b.empty());
  CHECK(b.x0 == Approx(-3.5));
  CHECK(b.y0 == Approx(-0.5));
  CHECK(b.x1 == Approx(1));
  CHECK(b.y1 == Approx(2));
  const svg::Box g = b.grown(2);
  CHECK(g.width() == Approx(8.5));
  CHECK(g.height() == Approx(6.5));
}

TEST_CASE("svg scale bar is as long as the world length it names") {
  svg::Document doc(300, 200);
  const svg::Frame f = svg::mapFrame({0, 0, 20, 10}, 20, 30, 12.5);
  svg::scaleBar(doc, 40, 150, 5 * f.xScale(), "5 m", false);
  const std::string s = doc.str();
  // The bar runs from x = 40 to x = 40 + 5 m * 12.5 px/m, with its label above the middle.
  CHECK(sylva_test::contains(s, "<path d=\"M40.00 146.00V150.00H102.50V146.00\""));
  CHECK(sylva_test::contains(s, "<text x=\"71.25\" y=\"143.00\""));
  CHECK(sylva_test::contains(s, ">5 m</text>"));
  CHECK(count(s, "<rect") == 1);  // the page background only: no backdrop asked for
}

TEST_CASE("svg covariance ellipse has the sigma radii in pixels and turns with y flipped") {
  svg::Document doc(200, 200);
  const svg::Frame f = svg::mapFrame({-5, -5, 5, 5}, 0, 0, 10);
  // sigma 2 m along a world direction 30 deg counter-clockwise from x, sigma 1 m across it.
  const double a = 30.0 * sylva::kPi / 180.0;
  sylva::Mat<2, 2> r;
  r << std::cos(a), -std::sin(a), std::sin(a), std::cos(a);
  const sylva::Mat<2, 2> cov =
      r * (sylva::Vec<2>() << 4.0, 1.0).finished().asDiagonal() * r.transpose();
  doc.ellipse(f, Point(1, 2), cov, 2.0, "");
  // 2-sigma: 4 m and 2 m, 40 px and 20 px; on the page, whose y points down, the major axis
  // turns clockwise: rotate(-30).
  CHECK(sylva_test::contains(doc.str(),
                             "<ellipse cx=\"60.00\" cy=\"30.00\" rx=\"40.000\" ry=\"20.000\" "
                             "transform=\"rotate(-30.0 60.00 30.00)\"/>"));
  svg::Document round(200, 200);
  round.ellipse(f, Point(0, 0), sylva::Mat<2, 2>::Identity(), 1.0, "");
  CHECK(sylva_test::contains(round.str(), "rx=\"10.000\" ry=\"10.000\""));
}

TEST_CASE("svg polyline breaks at non-finite points and drops single points") {
  svg::Document doc(100, 100);
  const svg::Frame f = svg::mapFrame({0, 0, 10, 10}, 0, 0, 10);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  doc.polyline(f,
               {Point(0, 0),
                Point(1, 1),
                Point(nan, 0),
                Point(2, 2),
                Point(3, 3),
                Point(nan, nan),
                Point(5, 5)},
               "stroke=\"red\"");
  const std::string s = doc.str();
  CHECK(count(s, "<polyline") == 2);
  CHECK(sylva_test::contains(s, "points=\"0.00,100.00 10.00,90.00\""));
  CHECK(sylva_test::contains(s, "points=\"20.00,80.00 30.00,70.00\""));
  CHECK_FALSE(sylva_test::contains(s, "50.00,50.00"));
}

TEST_CASE("svg dots leave out points outside the frame and repeats") {
  svg::Document doc(100, 100);
  const svg::Frame f = svg::mapFrame({0, 0, 10, 10}, 0, 0, 10);
  doc.dots(f, {Point(1, 1), Point(1.01, 1.01), Point(11, 5), Point(5, 5)}, "#999", 2);
  const std::string s = doc.str();
  CHECK(count(s, "h0") == 2);
  CHECK(sylva_test::contains(s, "d=\"M10.00 90.00h0M50.00 50.00h0\""));
}

TEST_CASE("svg legend stacks rows or wraps them within a width") {
  svg::Document doc(600, 400);  // 13 px text: 21 px rows
  const std::vector<svg::LegendEntry> entries{{svg::swatch::line("stroke=\"red\""), "first"},
                                              {svg::swatch::dot(3, "fill=\"blue\""), "second"},
                                              {svg::swatch::box("fill=\"green\""), "third"}};
  CHECK(svg::legend(doc, 10, 100, entries) == Approx(163));
  CHECK(svg::legend(doc, 10, 200, entries, 500) == Approx(221));
  CHECK(svg::legend(doc, 10, 300, entries, 120) == Approx(363));  // no two entries fit in a row
  CHECK(svg::legend(doc, 10, 300, {}) == Approx(300));
  const std::string s = doc.str();
  CHECK(count(s, ">second</text>") == 3);
  CHECK(sylva_test::contains(s,
                             "<g transform=\"translate(10.00,121.00)\"><circle cx=\"12\" cy=\"6\" "
                             "r=\"3.0\" fill=\"blue\"/></g>"));
}

TEST_CASE("svg output is well formed, with the text escaped") {
  const std::string s = everything();
  CHECK(balanced(s));
  CHECK(s.rfind("<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"400\" height=\"300\"", 0) == 0);
  CHECK(sylva_test::contains(s, ">A &amp; B</text>"));
  CHECK(sylva_test::contains(s, ">x &lt; y &gt; z</text>"));
  CHECK(sylva_test::contains(s, ">a &quot;quoted&quot; label</text>"));
  CHECK(sylva_test::contains(s, "<g clip-path=\"url(#clip1)\">"));
  CHECK(sylva_test::contains(s, "<style>\n.a { fill: red; }\n</style>"));
  // The checker itself tells a broken picture.
  CHECK_FALSE(balanced("<svg><g></svg>"));
  CHECK_FALSE(balanced("<svg></svg><svg></svg>"));
  CHECK_FALSE(balanced("<svg><text></g></text></svg>"));
}

TEST_CASE("svg groups must be closed, and only once") {
  svg::Document doc(10, 10);
  CHECK(throwsCode([&] { doc.endGroup(); }, ErrorCode::kInvalidArgument));
  doc.group("fill=\"red\"");
  CHECK(throwsCode([&] { (void)doc.str(); }, ErrorCode::kInvalidArgument));
  doc.endGroup();
  CHECK(balanced(doc.str()));
}

TEST_CASE("svg the same drawing gives the same bytes, in memory and on disk") {
  const std::string first = everything();
  CHECK(everything() == first);
  sylva_test::TempFolder folder("svg_plot");
  const std::string file = (folder.path / "picture.svg").string();
  svg::Document doc(400, 300);
  const svg::Frame f =
      svg::mapFrame({-10, -5, 10, 5}, 50, svg::header(doc, 50, "A & B", {"x < y > z"}), 15);
  svg::axes(doc, f, {"x [m]", "y [m]"});
  doc.write(file);
  std::ifstream in(file, std::ios::binary);
  const std::string written((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  CHECK(written == doc.str());
  CHECK(throwsCode([&] { doc.write((folder.path / "missing" / "picture.svg").string()); },
                   ErrorCode::kInvalidArgument));
}

}  // namespace unity_common_svg_plot
