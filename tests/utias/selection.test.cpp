// The UTIAS example's targets, grid and declared selection rule (examples/utias/selection.hpp)
// on small synthetic tables.
#include "sylva_catch.hpp"

#include <cmath>
#include <limits>
#include <vector>

#include "error_helpers.hpp"
#include "utias/selection.hpp"

namespace unity_utias_selection {

using sylva::ErrorCode;
using sylva_test::throwsCode;
using utias::RobotFigures;
using utias::TargetSummary;

/// A summary that meets all six targets, with margins set by the arguments.
TargetSummary allMet(double aligned_worst_m, double nees_max) {
  TargetSummary t;
  t.robots = 4;
  t.aligned_mean_m = 0.15;
  t.aligned_worst_m = aligned_worst_m;
  t.vicon_mean_m = 0.30;
  t.vicon_worst_m = 0.50;
  t.landmark_worst_m = 0.05;
  t.nees_min = 2.0;
  t.nees_max = nees_max;
  return t;
}

}  // namespace unity_utias_selection

using namespace unity_utias_selection;

TEST_CASE("UTIAS summarize: means and extremes of the robots' figures", "[utias]") {
  const std::vector<RobotFigures> robots = {
      {0.1, 0.4, 0.02, 2.0}, {0.3, 0.7, 0.09, 7.0}, {0.2, 0.3, 0.05, 0.5}};
  const TargetSummary t = utias::summarize(robots);
  CHECK(t.robots == 3);
  CHECK(t.aligned_mean_m == Approx(0.2));
  CHECK(t.aligned_worst_m == 0.3);
  CHECK(t.vicon_mean_m == Approx(1.4 / 3.0));
  CHECK(t.vicon_worst_m == 0.7);
  CHECK(t.landmark_worst_m == 0.09);
  CHECK(t.nees_min == 0.5);
  CHECK(t.nees_max == 7.0);
  // aligned mean 0.2 <= 0.25, worst 0.3 <= 0.4, Vicon mean 0.47 <= 0.5, worst 0.7 <= 0.8,
  // landmark 0.09 <= 0.1 met; NEES 0.5-7 not.
  CHECK(t.met() == 5);
  CHECK_FALSE(t.neesMet());
  // The NEES misses on both sides; the lower one by the larger factor: ln(0.5 / 1).
  CHECK(t.smallestMargin() == Approx(std::log(0.5)));

  CHECK(throwsCode([] { utias::summarize({}); }, ErrorCode::kInvalidArgument));
  const double nan = std::numeric_limits<double>::quiet_NaN();
  CHECK(throwsCode(
      [&] {
        utias::summarize({{0.1, nan, 0.02, 2.0}});
      },
      ErrorCode::kInvalidArgument));
}

TEST_CASE("UTIAS smallest margin: the log factor to the nearest limit", "[utias]") {
  const TargetSummary t = allMet(0.32, 5.0);
  // Margins: ln(0.25/0.15), ln(0.40/0.32), ln(0.5/0.3), ln(0.8/0.5), ln(0.1/0.05), ln(2/1),
  // ln(6/5).
  CHECK(t.met() == 6);
  CHECK(t.smallestMargin() == Approx(std::log(6.0 / 5.0)));
  CHECK(allMet(0.38, 5.0).smallestMargin() == Approx(std::log(0.40 / 0.38)));
}

TEST_CASE(
    "UTIAS selection rule: most targets first, then the largest smallest margin, then grid order",
    "[utias]") {
  TargetSummary five = allMet(0.10, 2.5);
  five.vicon_worst_m = 0.81;  // misses one target, but has wide margins elsewhere
  const TargetSummary tight = allMet(0.39, 5.9);
  const TargetSummary wide = allMet(0.30, 4.0);
  const TargetSummary wider = allMet(0.25, 3.0);

  // More targets beat a larger margin.
  CHECK(utias::selectSetting({five, tight}) == 1);
  // Equal targets: the larger smallest margin.
  CHECK(utias::selectSetting({tight, wide, five}) == 1);
  CHECK(utias::selectSetting({five, wide, tight, wider}) == 3);
  // Exact tie: the earlier setting.
  CHECK(utias::selectSetting({five, wide, wide}) == 1);
  // None meets all: the one that meets most.
  TargetSummary four = five;
  four.aligned_mean_m = 0.3;
  CHECK(utias::selectSetting({four, five}) == 1);
  CHECK(throwsCode([] { utias::selectSetting({}); }, ErrorCode::kInvalidArgument));
}

TEST_CASE("UTIAS grid: 36 absolute settings, and the compiled default is one of them", "[utias]") {
  const auto grid = utias::studyGrid();
  REQUIRE(grid.size() == 36);
  CHECK(grid.front().process == 1.0);
  CHECK(grid.front().range == 0.5);
  CHECK(grid.front().bearing_rad == 0.02);
  CHECK(grid.back().process == 4.0);
  CHECK(grid.back().range == 1.5);
  CHECK(grid.back().bearing_rad == 0.05);

  const utias::NoiseConfig base;
  const utias::NoiseConfig c = utias::applySetting(base, {4.0, 0.5, 0.05});
  CHECK(c.v_scale == Approx(0.52));
  CHECK(c.v_floor == Approx(0.008));
  CHECK(c.omega_scale == Approx(0.60));
  CHECK(c.omega_floor == Approx(0.04));
  CHECK(c.sigma_range_m == Approx(0.1));
  CHECK(c.sigma_range_per_m == Approx(0.1));
  CHECK(c.sigma_bearing_rad == 0.05);
  // Everything else is kept.
  CHECK(c.command_delay_s == base.command_delay_s);
  CHECK(c.omega_gain == base.omega_gain);
  CHECK(c.command_jitter_s == base.command_jitter_s);
  CHECK(utias::hasSetting(c, {4.0, 0.5, 0.05}));
  CHECK_FALSE(utias::hasSetting(c, {4.0, 0.5, 0.03}));

  int matches = 0;
  for (const auto& g : grid) matches += utias::hasSetting(base, g) ? 1 : 0;
  CHECK(matches == 1);

  CHECK(throwsCode(
      [&] {
        utias::applySetting(base, {0.0, 1.0, 0.03});
      },
      ErrorCode::kInvalidArgument));
}
