// Victoria Park loaders: small files written by the tests (good rows, every kind of
// malformed row, reported with file and line), and the real files when they are present.

#include "sylva_catch.hpp"

#include "error_helpers.hpp"
#include "temp_folder.hpp"

#include <cmath>
#include <filesystem>
#include <string>

#include <sylva/datasets.hpp>

namespace unity_datasets_victoria_park {

using sylva_test::contains;
using sylva_test::TempFolder;
namespace ds = sylva::datasets;

/// The kMalformedData message of `load(path)` for a file holding `text`, "" if it loads.
template <typename Load>
std::string loadError(const TempFolder& dir, const std::string& name, const std::string& text, Load load) {
  const std::string path = dir.write(name, text);
  return sylva_test::errorMessage([&] { load(path); }, sylva::ErrorCode::kMalformedData);
}

}  // namespace unity_datasets_victoria_park

using namespace unity_datasets_victoria_park;

TEST_CASE("Victoria Park measurements: rows of one time form one scan", "[datasets][victoria_park]") {
  const TempFolder dir("vp_measurements");
  const std::string path = dir.write("measurements.dat",
                                     "     0.852   20.46202    0.88575    0.35404\n"
                                     "     0.852   29.59859    1.02102    0.25717\r\n"
                                     "\n"
                                     "     1.065   28.68462    1.57080    0.24923\n"
                                     "     1.279    5.00000    3.14159    0.10000   \n");
  const auto scans = ds::loadVictoriaParkMeasurements(path);
  REQUIRE(scans.size() == 3);
  CHECK(scans[0].t_s == 0.852);
  REQUIRE(scans[0].detections.size() == 2);
  CHECK(scans[0].detections[1].range_m == 29.59859);
  CHECK(scans[0].detections[1].bearing_rad == 1.02102);
  CHECK(scans[0].detections[1].diameter_m == 0.25717);
  CHECK(scans[1].detections.size() == 1);
  CHECK(ds::carBearing(scans[1].detections[0]) == Approx(0.0).margin(1e-5));  // straight ahead
  CHECK(ds::carBearing(scans[2].detections[0]) == Approx(0.5 * sylva::kPi).margin(1e-5));  // left
}

TEST_CASE("Victoria Park measurements: malformed lines name the file and the line", "[datasets][victoria_park]") {
  const TempFolder dir("vp_measurements_bad");
  const auto load = [](const std::string& p) { ds::loadVictoriaParkMeasurements(p); };
  const std::string ok = "1.0 10.0 1.5 0.3\n";
  const auto error = [&](const std::string& text) { return loadError(dir, "m.dat", text, load); };
  CHECK(error(ok) == "");
  CHECK(contains(error(ok + "1.2 10.0 1.5\n"), "m.dat:2: expected 4 fields, got 3"));
  CHECK(contains(error(ok + "1.2 10.0 1.5 0.3 7\n"), "m.dat:2: expected 4 fields, got 5"));
  CHECK(contains(error(ok + "1.2 ten 1.5 0.3\n"), "m.dat:2: field 2 is not a finite number: 'ten'"));
  CHECK(contains(error(ok + "1.2 nan 1.5 0.3\n"), "m.dat:2: field 2"));
  CHECK(contains(error(ok + "0.9 10.0 1.5 0.3\n"), "m.dat:2: the scan time goes back in time"));
  CHECK(contains(error(ok + "1.2 0.0 1.5 0.3\n"), "m.dat:2: the range must be > 0"));
  CHECK(contains(error(ok + "1.2 10.0 -0.1 0.3\n"), "m.dat:2: the bearing must lie in [0, pi]"));
  CHECK(contains(error(ok + "1.2 10.0 3.2 0.3\n"), "m.dat:2: the bearing must lie in [0, pi]"));
  CHECK(contains(error(ok + "1.2 10.0 1.5 0\n"), "m.dat:2: the diameter must be > 0"));
  CHECK(contains(error("\n# nothing\n"), "m.dat: no detections in the file"));
  CHECK(contains(loadError(dir, "x", "", [](const std::string& p) { ds::loadVictoriaParkMeasurements(p + "_absent"); }),
                 "cannot open the file"));
}

TEST_CASE("Victoria Park odometry and GPS: values and malformed lines", "[datasets][victoria_park]") {
  const TempFolder dir("vp_odometry_gps");
  const auto odometry = ds::loadVictoriaParkOdometry(
      dir.write("odometry.txt", "0.973 21940 0.0 -0.0034717200000000006\n0.998 21965 1.5 0.25\n"));
  REQUIRE(odometry.size() == 2);
  CHECK(odometry[0].t_raw_ms == 21940);
  CHECK(odometry[0].steering_rad == -0.0034717200000000006);
  CHECK(odometry[1].speed_mps == 1.5);
  const auto gps = ds::loadVictoriaParkGps(
      dir.write("gps.txt", "0.000 20967 -67.64927093982358 -41.71421779374552\n1.001 21968 -67.7 -41.6\n"));
  REQUIRE(gps.size() == 2);
  CHECK(gps[0].t_raw_ms == 20967);
  CHECK(gps[0].x_m == -67.64927093982358);
  CHECK(gps[1].y_m == -41.6);

  const auto odo = [](const std::string& p) { ds::loadVictoriaParkOdometry(p); };
  const auto fix = [](const std::string& p) { ds::loadVictoriaParkGps(p); };
  const std::string ok = "1.0 21967 1.0 0.1\n";
  CHECK(contains(loadError(dir, "o.txt", ok + "1.025 21992.5 1.0 0.1\n", odo), "o.txt:2: the raw time (ms) must be a whole number"));
  CHECK(contains(loadError(dir, "o.txt", ok + "1.025 21992 1.0 1.6\n", odo), "o.txt:2: the steering angle must lie in (-pi/2, pi/2)"));
  CHECK(contains(loadError(dir, "o.txt", ok + "0.5 21992 1.0 0.1\n", odo), "o.txt:2: the odometry time goes back in time"));
  CHECK(contains(loadError(dir, "o.txt", ok + ok + "1.05 22017 1.0\n", odo), "o.txt:3: expected 4 fields, got 3"));
  CHECK(contains(loadError(dir, "o.txt", "", odo), "o.txt: no odometry in the file"));
  CHECK(contains(loadError(dir, "g.txt", ok + "1.2 22167 x 3\n", fix), "g.txt:2: field 3 is not a finite number: 'x'"));
  CHECK(contains(loadError(dir, "g.txt", ok + "0.2 22167 2 3\n", fix), "g.txt:2: the GPS time goes back in time"));
  CHECK(contains(loadError(dir, "g.txt", "\r\n", fix), "g.txt: no GPS fixes in the file"));
}

TEST_CASE("Victoria Park: a folder whose files cover different time spans is reported", "[datasets][victoria_park]") {
  const TempFolder dir("victoria_park_spans");
  const std::string scans = "0.852 20.46 0.88 0.35\n100.0 18.1 2.88 0.16\n";
  const std::string odometry = "0.973 21940 0.0 0.0\n100.2 121167 1.0 0.0\n";
  dir.write("measurements.dat", scans);
  dir.write("odometry.txt", odometry);
  dir.write("gps.txt", "0.000 20967 1 2\n99.5 120467 3 4\n");
  CHECK(ds::loadVictoriaPark(dir.path.string()).gps.size() == 2);
  // GPS cut 60 s short of the odometry: named with both spans.
  dir.write("gps.txt", "0.000 20967 1 2\n40.0 60967 3 4\n");
  std::string error;
  try {
    ds::loadVictoriaPark(dir.path.string());
  } catch (const sylva::Error& e) {
    error = e.code() == sylva::ErrorCode::kMalformedData ? e.what() : "wrong code";
  }
  CHECK(contains(error, "the files cover different time spans: "));
  CHECK(contains(error, "odometry.txt [0.973, 100.2] s, "));
  CHECK(contains(error, "gps.txt [0, 40] s (more than 30 s apart"));
  CHECK(ds::loadVictoriaPark(dir.path.string(), 61.0).gps.size() == 2);
  CHECK(sylva_test::throwsCode([&] { ds::loadVictoriaPark(dir.path.string(), -1.0); }, sylva::ErrorCode::kInvalidArgument));
}

TEST_CASE("Victoria Park: the real files match the counts of the data README", "[datasets][victoria_park][data]") {
  const std::string folder = SYLVA_DATA_DIR "/victoria-park";
  if (!std::filesystem::exists(folder + "/measurements.dat")) {
    WARN("skipped: no Victoria Park data at " << folder);
    return;
  }
  const ds::VictoriaParkData data = ds::loadVictoriaPark(folder);
  std::size_t detections = 0;
  std::size_t most = 0;
  for (const auto& scan : data.scans) {
    detections += scan.detections.size();
    most = std::max(most, scan.detections.size());
  }
  CHECK(detections == 52974);
  CHECK(data.scans.size() == 7230);
  CHECK(most == 18);
  CHECK(data.scans.front().t_s == 0.852);
  CHECK(data.odometry.size() == 61945);
  CHECK(data.odometry.front().t_s == 0.973);
  CHECK(data.odometry.back().t_s == 1549.573);
  CHECK(data.gps.size() == 4466);
  CHECK(data.gps.front().t_raw_ms == 20967);
  // The common time base: t = (t_raw - 20967) / 1000.
  for (const auto& o : data.odometry) REQUIRE(std::abs(o.t_s - (o.t_raw_ms - 20967) / 1000.0) < 1e-9);
  for (const auto& g : data.gps) REQUIRE(std::abs(g.t_s - (g.t_raw_ms - 20967) / 1000.0) < 1e-9);
}
