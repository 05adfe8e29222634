// The repeatability study: its starts, its summary, and that the adaptive controller parks
// every start within the thesis' repeatability, faster than with a fixed virtual edge.
#include "sylva_catch.hpp"

#include <cmath>
#include <limits>
#include <vector>

#include "error_helpers.hpp"
#include "parking/study.hpp"

namespace unity_parking_study {

using ::parking::ControllerParams;
using ::parking::Outcome;
using ::parking::Pose;
using ::parking::RobotParams;
using ::parking::StationCamera;
using ::parking::StudyOptions;
using ::parking::StudyRun;
using sylva::ErrorCode;
using sylva_test::throwsCode;

StudyRun run(Outcome outcome, double x, double y, int cycles, double time) {
  StudyRun r;
  r.outcome = outcome;
  r.error = Pose(x, y, 0.0);
  r.cycles = cycles;
  r.time_s = time;
  r.min_station_distance_m = 0.3;
  return r;
}

}  // namespace unity_parking_study

using namespace unity_parking_study;

TEST_CASE("parking study: every start lies in the region and sees the whole station", "[parking]") {
  const StationCamera cam;
  StudyOptions o;
  sylva::sim::Rng rng(9);
  const double deg = 3.14159265358979323846 / 180.0;
  for (int i = 0; i < 300; ++i) {
    const Pose s = ::parking::drawStart(cam, o, rng);
    const double r = std::hypot(s[0], s[1]);
    CHECK(r >= o.r_min_m);
    CHECK(r <= o.r_max_m);
    CHECK(std::abs(std::atan2(s[0], -s[1])) <= o.max_angle_deg * deg + 1e-12);
    const ::parking::StationView v = cam.view(s);
    CHECK(v.allVisible());
    CHECK(v.u[0] >= o.margin_px);
    CHECK(v.u[2] <= cam.params().image_width_px - o.margin_px);
  }
}

TEST_CASE("parking study: the summary spreads are half ranges over the parked runs", "[parking]") {
  const std::vector<StudyRun> runs{run(Outcome::kParked, 0.01, -0.002, 1, 10.0),
                                   run(Outcome::kParked, -0.03, 0.004, 3, 30.0),
                                   run(Outcome::kStationLost, 5.0, 5.0, 9, 99.0),
                                   run(Outcome::kTimedOut, -5.0, -5.0, 9, 99.0)};
  const ::parking::StudySummary s = ::parking::summarize(runs);
  CHECK(s.runs == 4);
  CHECK(s.parked == 2);
  CHECK(s.station_lost == 1);
  CHECK(s.timed_out == 1);
  CHECK(s.success_rate == 0.5);
  CHECK(s.x_spread_m == Approx(0.02));
  CHECK(s.y_spread_m == Approx(0.003));
  CHECK(s.x_mean_m == Approx(-0.01));
  CHECK(s.mean_cycles == 2.0);
  CHECK(s.max_cycles == 3);
  CHECK(s.mean_time_s == 20.0);
  CHECK(s.max_time_s == 30.0);
  const ::parking::StudySummary none = ::parking::summarize({run(Outcome::kCollided, 1, 1, 1, 1)});
  CHECK(none.parked == 0);
  CHECK(none.collided == 1);
  CHECK(none.success_rate == 0.0);
  CHECK(none.x_spread_m == 0.0);
}

TEST_CASE(
    "parking study: the adaptive controller parks every start within the thesis' "
    "repeatability, in fewer cycles than with a fixed c",
    "[parking]") {
  const StationCamera cam;
  StudyOptions o;
  o.runs = 60;
  o.seed = 7;
  const ::parking::StudyResult adaptive =
      ::parking::runStudy(cam, ControllerParams{}, RobotParams{}, o);
  const ::parking::StudySummary& s = adaptive.summary;
  CHECK(s.success_rate == 1.0);
  CHECK(s.x_spread_m < 0.04);
  CHECK(s.y_spread_m < 0.005);
  CHECK(s.mean_cycles < 3.0);
  ControllerParams fixed_c;
  fixed_c.adapt_c = false;
  fixed_c.c_static_px = fixed_c.c_max_px;
  const ::parking::StudySummary f = ::parking::runStudy(cam, fixed_c, RobotParams{}, o).summary;
  CHECK(f.mean_cycles > 2.0 * s.mean_cycles);
  CHECK(f.mean_time_s > s.mean_time_s);
}

TEST_CASE("parking study: a run depends only on the seed and its index", "[parking]") {
  const StationCamera cam;
  StudyOptions o;
  o.runs = 5;
  o.seed = 3;
  const ::parking::StudyResult a = ::parking::runStudy(cam, ControllerParams{}, RobotParams{}, o);
  const ::parking::StudyResult b = ::parking::runStudy(cam, ControllerParams{}, RobotParams{}, o);
  o.runs = 3;  // a shorter study holds the same first runs
  const ::parking::StudyResult c = ::parking::runStudy(cam, ControllerParams{}, RobotParams{}, o);
  for (std::size_t i = 0; i < 3; ++i) {
    CHECK(a.runs[i].start == b.runs[i].start);
    CHECK(a.runs[i].error == b.runs[i].error);
    CHECK(a.runs[i].error == c.runs[i].error);
  }
  // Run i on its own: start from deriveSeed(seed, 2 i), noise from deriveSeed(seed, 2 i + 1).
  sylva::sim::Rng start_rng(sylva::sim::deriveSeed(3, 2 * 2));
  const Pose start = ::parking::drawStart(cam, o, start_rng);
  const ::parking::EpisodeResult alone = ::parking::runEpisode(
      cam, ControllerParams{}, RobotParams{}, start, sylva::sim::deriveSeed(3, 2 * 2 + 1));
  CHECK(start == a.runs[2].start);
  CHECK(alone.error == a.runs[2].error);
}

TEST_CASE("parking study: nonsense study options are refused", "[parking]") {
  const StationCamera cam;
  StudyOptions o;
  o.runs = 0;
  CHECK(throwsCode([&] { ::parking::runStudy(cam, {}, {}, o); }, ErrorCode::kInvalidArgument));
  o = StudyOptions{};
  o.r_min_m = 2.0;
  o.r_max_m = 1.0;
  CHECK(throwsCode([&] { ::parking::runStudy(cam, {}, {}, o); }, ErrorCode::kInvalidArgument));
  o = StudyOptions{};
  o.max_angle_deg = std::numeric_limits<double>::quiet_NaN();
  CHECK(throwsCode([&] { ::parking::runStudy(cam, {}, {}, o); }, ErrorCode::kNonFinite));
  o = StudyOptions{};
  o.max_heading_offset_deg = 0.0;
  o.margin_px = 1000.0;  // no heading can show the station that far inside the image
  sylva::sim::Rng rng(1);
  CHECK(throwsCode([&] { ::parking::drawStart(cam, o, rng); }, ErrorCode::kInvalidArgument));
}
