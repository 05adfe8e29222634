#include "sylva_catch.hpp"

#include "error_helpers.hpp"
#include "temp_folder.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include <sylva/datasets/leg_tracker.hpp>

namespace unity_datasets_leg_tracker {

using sylva_test::contains;
using sylva_test::TempFolder;

const char* kParams =
    "# LaserScan parameters\n"
    "frame_id laser\n"
    "angle_min -1.5\n"
    "angle_max 1.5\n"
    "angle_increment 1.0\n"
    "n_beams 4\n"
    "range_min 0.02\n"
    "range_max 5.6\n"
    "scan_time 0.1\n";

/// The kMalformedData message of loading `csv` (with valid parameters), "" if it loads.
std::string loadError(const TempFolder& dir, const std::string& csv) {
  dir.write("rec_scan_params.txt", kParams);
  dir.write("rec_scans.csv", csv);
  return sylva_test::errorMessage([&] { sylva::datasets::loadLegTrackerRecording(dir.path.string(), "rec"); },
                                  sylva::ErrorCode::kMalformedData);
}

}  // namespace unity_datasets_leg_tracker

using namespace unity_datasets_leg_tracker;

TEST_CASE("leg_tracker loader: parameters and scans, inf and nan included", "[datasets][leg_tracker]") {
  const TempFolder dir("good");
  dir.write("rec_scan_params.txt", kParams);
  dir.write("rec_scans.csv",
            "100.0,1.0,inf,nan,2.5\n"
            "100.1,1.1,1.2,1.3,INF\r\n"
            "\n"
            "100.2, 0.5 ,5.0,-inf,3\n");
  const auto data = sylva::datasets::loadLegTrackerRecording(dir.path.string(), "rec");
  CHECK(data.geometry.beams == 4);
  CHECK(data.geometry.angle_min_rad == -1.5);
  CHECK(data.geometry.angle_increment_rad == 1.0);
  CHECK(data.geometry.max_range_m == 5.6);
  CHECK(data.scan_time_s == 0.1);
  REQUIRE(data.ranges.size() == 3);
  CHECK(data.stamps_s[2] == 100.2);
  CHECK(std::isinf(data.ranges[0][1]));
  CHECK(std::isnan(data.ranges[0][2]));
  CHECK(std::isinf(data.ranges[1][3]));
  CHECK(data.ranges[2][0] == 0.5);
  CHECK(data.ranges[2][3] == 3.0);
}

TEST_CASE("leg_tracker loader: a malformed line is reported with file name and line number", "[datasets][leg_tracker]") {
  const TempFolder dir("bad");
  const std::string ok = "100.0,1,2,3,4\n";
  std::string e = loadError(dir, ok + "100.1,1,2,x3,4\n");
  CHECK(contains(e, "rec_scans.csv:2:"));
  CHECK(contains(e, "field 4 is not a number: 'x3'"));
  e = loadError(dir, ok + ok.substr(0, 0) + "100.1,1,2,3\n");
  CHECK(contains(e, "rec_scans.csv:2:"));
  CHECK(contains(e, "expected 5 fields, got 4"));
  CHECK(contains(loadError(dir, ok + "100.1,1,2,3,4,5\n"), "expected 5 fields, got 6"));
  CHECK(contains(loadError(dir, ok + "100.1,1,2,3,\n"), ":2: the line ends with an empty field"));
  CHECK(contains(loadError(dir, ok + "100.1,1,,3,4\n"), "field 3 is not a number: ''"));
  CHECK(contains(loadError(dir, ok + "99.0,1,2,3,4\n"), ":2: the stamp 99 does not come after"));
  CHECK(contains(loadError(dir, ok + "nan,1,2,3,4\n"), ":2: the stamp is not finite"));
  CHECK(contains(loadError(dir, "\n\n"), "no scans in the file"));
  CHECK(contains(loadError(dir, ok + "1e999,1,2,3,4\n"), "field 1 is not a number"));
  CHECK(loadError(dir, ok) == "");
}

TEST_CASE("leg_tracker loader: bad parameter files and missing files", "[datasets][leg_tracker]") {
  const TempFolder dir("params");
  const auto paramsError = [&](const std::string& text) {
    const std::string path = dir.write("p.txt", text);
    return sylva_test::errorMessage([&] { sylva::datasets::loadLegTrackerScanParams(path); },
                                    sylva::ErrorCode::kMalformedData);
  };
  CHECK(contains(paramsError("angle_min -1\nangle_increment 0.1\nn_beams 10\nrange_min 0.1\n"), "missing key 'range_max'"));
  CHECK(contains(paramsError("angle_min -1\nangle_increment zero\n"), "p.txt:2: the value of 'angle_increment' is not a number"));
  CHECK(contains(paramsError("lonely\n"), "p.txt:1: expected 'key value'"));
  CHECK(contains(paramsError("angle_min -1\nangle_increment 0.1\nn_beams 10.5\nrange_min 0.1\nrange_max 5\n"), "n_beams"));
  CHECK(contains(paramsError("angle_min -1\nangle_increment -0.1\nn_beams 10\nrange_min 0.1\nrange_max 5\n"), "increment"));
  CHECK(paramsError("angle_min -1\nangle_increment 0.1\nn_beams 10\nrange_min 0.1\nrange_max 5\n") == "");
  CHECK(sylva_test::throwsCode([&] { sylva::datasets::loadLegTrackerRecording((dir.path / "absent").string(), "rec"); },
                               sylva::ErrorCode::kMalformedData));
}
