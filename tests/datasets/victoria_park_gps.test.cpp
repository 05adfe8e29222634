// sylva/datasets/victoria_park_gps.hpp: which GPS fixes to trust, and the error of a path
// against them after a rigid alignment.
#include "sylva_catch.hpp"

#include "error_helpers.hpp"

#include <cmath>
#include <vector>

#include <sylva/datasets/victoria_park_gps.hpp>

namespace unity_datasets_victoria_park_gps {

using sylva::Vec;
using sylva::datasets::TimedPosition;
using sylva::datasets::VictoriaParkGps;
using sylva::datasets::VictoriaParkOdometry;

/// A car driving straight east at `speed` m/s, odometry every 0.025 s and a fix every 0.2 s
/// for `duration` s.
struct StraightDrive {
  std::vector<VictoriaParkOdometry> odometry;
  std::vector<VictoriaParkGps> gps;
  StraightDrive(double speed, double duration) {
    for (int k = 0; k * 0.025 <= duration + 1e-9; ++k) odometry.push_back({k * 0.025, 0, speed, 0.0});
    for (int k = 0; k * 0.2 <= duration + 1e-9; ++k) gps.push_back({k * 0.2, 0, speed * k * 0.2, 0.0});
  }
};

}  // namespace unity_datasets_victoria_park_gps

using namespace unity_datasets_victoria_park_gps;

TEST_CASE("Victoria Park GPS: a path is interpolated in time and clamped at its ends", "[datasets][victoria_park]") {
  const std::vector<TimedPosition> path{{1.0, Vec<2>(0.0, 0.0)}, {2.0, Vec<2>(2.0, 4.0)}, {4.0, Vec<2>(2.0, 0.0)}};
  CHECK(sylva::datasets::interpolatePath(path, 0.0) == Vec<2>(0.0, 0.0));
  CHECK(sylva::datasets::interpolatePath(path, 1.5).isApprox(Vec<2>(1.0, 2.0)));
  CHECK(sylva::datasets::interpolatePath(path, 3.0).isApprox(Vec<2>(2.0, 2.0)));
  CHECK(sylva::datasets::interpolatePath(path, 9.0) == Vec<2>(2.0, 0.0));
  CHECK(sylva_test::throwsCode([] { sylva::datasets::interpolatePath({}, 1.0); }, sylva::ErrorCode::kInvalidArgument));
}

TEST_CASE("Victoria Park GPS: a jump and a gap invalidate their fix and the next 2 s", "[datasets][victoria_park]") {
  StraightDrive drive(5.0, 20.0);
  const double wheelbase = 2.83, offset = 0.76;
  {
    const auto valid = sylva::datasets::validVictoriaParkGpsFixes(drive.gps, drive.odometry, wheelbase, offset);
    REQUIRE(valid.size() == drive.gps.size());
    CHECK(valid[0] == 0);  // no previous fix to check it against
    for (std::size_t i = 1; i < valid.size(); ++i) CHECK(valid[i] == 1);
  }
  // Fix 30 (t = 6 s) jumps 3 m north: its step and the step back both disagree with the odometry.
  drive.gps[30].y_m += 3.0;
  // Fixes 60-66 are missing: fix 67 (t = 13.4 s) comes 1.6 s after fix 59.
  drive.gps.erase(drive.gps.begin() + 60, drive.gps.begin() + 67);
  const auto valid = sylva::datasets::validVictoriaParkGpsFixes(drive.gps, drive.odometry, wheelbase, offset);
  // The steps into and out of fix 30 are bad (the last at 6.2 s), and so is the step over the
  // gap (13.4 s); a fix is valid again more than 2 s after the last bad step. Fixes within
  // round-off of 8.2 s and 15.4 s are not checked.
  int checked = 0;
  for (std::size_t i = 1; i < valid.size(); ++i) {
    const double t = drive.gps[i].t_s;
    if (std::abs(t - 8.2) < 0.01 || std::abs(t - 15.4) < 0.01) continue;
    const bool held = (t > 5.99 && t < 8.2) || (t > 13.39 && t < 15.4);
    INFO("fix " << i << " at t = " << t);
    CHECK(valid[i] == (held ? 0 : 1));
    ++checked;
  }
  CHECK(checked == static_cast<int>(valid.size()) - 3);
}

TEST_CASE("Victoria Park GPS: a path that is a rigid copy of the fixes has no error", "[datasets][victoria_park]") {
  const StraightDrive drive(5.0, 10.0);
  const auto valid = sylva::datasets::validVictoriaParkGpsFixes(drive.gps, drive.odometry, 2.83, 0.76);
  // The estimate in a map frame turned by 30 deg and moved: the alignment undoes it.
  const double a = 30.0 * sylva::kRadPerDeg;
  std::vector<TimedPosition> path;
  for (const auto& o : drive.odometry) {
    const Vec<2> gps_frame(5.0 * o.t_s, 0.0);
    path.push_back({o.t_s, Vec<2>(std::cos(a) * gps_frame.x() + 7.0, std::sin(a) * gps_frame.x() - 2.0)});
  }
  const auto e = sylva::datasets::victoriaParkGpsError(path, drive.gps, valid);
  CHECK(e.total == static_cast<int>(drive.gps.size()));
  CHECK(e.valid == e.total - 1);
  CHECK(e.rmse_valid_m < 1e-9);
  CHECK(e.rmse_all_m < 1e-9);
  CHECK(e.transform.angle() == Approx(-a).margin(1e-12));
  REQUIRE(e.fix_error_m.size() == drive.gps.size());

  // Too few valid fixes: counts only, no alignment.
  std::vector<char> two(valid.size(), 0);
  two[1] = two[2] = 1;
  const auto few = sylva::datasets::victoriaParkGpsError(path, drive.gps, two);
  CHECK(few.valid == 2);
  CHECK(few.fix_error_m.empty());

  CHECK(sylva_test::throwsCode([&] { sylva::datasets::victoriaParkGpsError(path, drive.gps, std::vector<char>(3, 1)); },
                               sylva::ErrorCode::kInvalidArgument));
  CHECK(sylva_test::throwsCode([&] { sylva::datasets::victoriaParkGpsError({}, drive.gps, valid); },
                               sylva::ErrorCode::kInvalidArgument));
}
