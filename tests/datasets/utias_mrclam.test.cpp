// loadUtiasMrclam: the UTIAS MRCLAM folder format (Leung et al., IJRR 30(8) 2011) on small
// excerpts written by the tests (CRLF, '#' headers, blank+TAB separators), every kind of
// malformed row named by file and line, misread barcodes counted, and the real Dataset 7
// when it is beside the repository.

#include <filesystem>
#include <limits>
#include <string>

#include <sylva/datasets/utias_mrclam.hpp>

#include "error_helpers.hpp"
#include "sylva_catch.hpp"
#include "temp_folder.hpp"

namespace unity_datasets_utias_mrclam {

using sylva::datasets::loadUtiasMrclam;
using sylva::datasets::UtiasDataset;
using sylva::datasets::UtiasLoadOptions;
using sylva_test::contains;
using sylva_test::TempFolder;

const std::string kHeader =
    "# UTIAS Multi-Robot Cooperative Localization and Mapping Dataset\r\n"
    "# produced by a test\r\n"
    "# Data Fomat:\r\n"
    "# columns\r\n";

/// Five robots (barcodes 5, 14, 41, 32, 23) and two landmarks (subjects 6, 7; barcodes 63, 81).
const std::string kBarcodes = kHeader +
                              "  1 \t   5 \r\n  2 \t  14 \r\n  3 \t  41 \r\n  4 \t  32 \r\n  5 \t  23 \r\n"
                              "  6 \t  63 \r\n  7 \t  81 \r\n";
const std::string kLandmarks = kHeader +
                               "  6 \t 0.58842660 \t -4.28209684 \t 0.00003949 \t 0.00059654 \r\n"
                               "  7 \t 0.68229930 \t -4.44548076 \t 0.00004113 \t 0.00059348 \r\n";
const std::string kOdometry = kHeader +
                              "1248446188.323 \t  0.086 \t -0.398 \r\n"
                              "1248446188.882 \t  0.086 \t -0.398 \r\n"
                              "1248446188.882 \t  0.085 \t -0.395 \r\n";
// Landmark 63, robot 14, landmark 81, a misread 52, another landmark at the same time.
const std::string kMeasurement = kHeader +
                                 "1248446192.940 \t  63 \t  5.414 \t -0.487 \r\n"
                                 "1248446192.940 \t  14 \t  2.000 \t  0.100 \r\n"
                                 "1248446193.100 \t  81 \t  5.632 \t -0.446 \r\n"
                                 "1248446193.200 \t  52 \t  3.000 \t  0.000 \r\n"
                                 "1248446193.200 \t  63 \t  5.400 \t -0.480 \r\n";
const std::string kGroundtruth = kHeader +
                                 "1248446182.116 \t 2.21390910 \t 4.22886590 \t -1.76340000 \r\n"
                                 "1248446182.132 \t 2.21386730 \t 4.22891460 \t -1.76340000 \r\n";

/// A complete folder with robots 1 and 2 (robot 2 a copy of robot 1).
void writeFolder(const TempFolder& dir) {
  dir.write("Barcodes.dat", kBarcodes);
  dir.write("Landmark_Groundtruth.dat", kLandmarks);
  for (const char* r : {"1", "2"}) {
    const std::string p = std::string("Robot") + r + "_";
    dir.write(p + "Odometry.dat", kOdometry);
    dir.write(p + "Measurement.dat", kMeasurement);
    dir.write(p + "Groundtruth.dat", kGroundtruth);
  }
}

UtiasLoadOptions robots12() {
  UtiasLoadOptions o;
  o.robots = {1, 2};
  return o;
}

/// The kMalformedData message of loading robots 1-2 after replacing `file` with `text`;
/// "" if it loads.
std::string loadError(const std::string& file, const std::string& text) {
  const TempFolder dir("utias_mrclam_bad");
  writeFolder(dir);
  dir.write(file, text);
  try {
    loadUtiasMrclam(dir.path.string(), robots12());
  } catch (const sylva::Error& e) {
    return e.code() == sylva::ErrorCode::kMalformedData ? e.what() : "wrong code";
  }
  return "";
}

}  // namespace unity_datasets_utias_mrclam

using namespace unity_datasets_utias_mrclam;

TEST_CASE("UTIAS loader reads CRLF files with headers, maps barcodes and keeps robots apart", "[datasets]") {
  const TempFolder dir("utias_mrclam_good");
  writeFolder(dir);
  const UtiasDataset d = loadUtiasMrclam(dir.path.string(), robots12());
  CHECK(d.barcode_of_subject.size() == 7);
  CHECK(d.subject_of_barcode.at(81) == 7);
  REQUIRE(d.landmarks.size() == 2);
  CHECK(d.landmarks[1].subject == 7);
  CHECK(d.landmarks[1].barcode == 81);
  CHECK(d.landmarks[0].position_m.y() == -4.28209684);
  CHECK(d.landmarks[1].sigma_m.y() == 0.00059348);
  // The earliest time of all files (ground truth), floored to a whole second.
  CHECK(d.time_reference_s == 1248446182.0);
  REQUIRE(d.robots.size() == 2);
  const auto& r = d.robot(2);
  CHECK(r.robot == 2);
  REQUIRE(r.odometry.size() == 3);
  CHECK(r.odometry[0].time_s == Approx(6.323).margin(1e-6));
  CHECK(r.odometry[2].time_s == r.odometry[1].time_s);  // duplicate stamps are allowed
  CHECK(r.odometry[2].u.x() == 0.085);
  CHECK(r.odometry[2].u.y() == -0.395);
  CHECK(r.measurement_rows == 5);
  REQUIRE(r.landmark_observations.size() == 3);
  CHECK(r.landmark_observations[0].subject == 6);
  CHECK(r.landmark_observations[0].barcode == 63);
  CHECK(r.landmark_observations[1].subject == 7);
  CHECK(r.landmark_observations[1].z.x() == 5.632);
  CHECK(r.landmark_observations[1].z.y() == -0.446);
  CHECK(r.landmark_observations[2].time_s == Approx(11.2).margin(1e-6));
  REQUIRE(r.robot_observations.size() == 1);
  CHECK(r.robot_observations[0].subject == 2);
  REQUIRE(r.unknown_barcode_rows.size() == 1);  // the misread barcode: counted, not used
  CHECK(r.unknown_barcode_rows[0].barcode == 52);
  CHECK(r.unknown_barcode_rows[0].line == 8);
  REQUIRE(r.groundtruth.size() == 2);
  CHECK(r.groundtruth[0].time_s == Approx(0.116).margin(1e-6));
  CHECK(r.groundtruth[1].pose.z() == -1.7634);
  CHECK(sylva_test::throwsCode([&] { (void)d.robot(3); }, sylva::ErrorCode::kInvalidArgument));
}

TEST_CASE("UTIAS loader takes an explicit time reference and LF files", "[datasets]") {
  const TempFolder dir("utias_mrclam_lf");
  writeFolder(dir);
  dir.write("Robot1_Odometry.dat", "# a\n# b\n# c\n# d\n100.5 0.1 0.2\n101.0\t0.0\t0.0\n");
  UtiasLoadOptions o;
  o.robots = {1};
  o.time_reference_s = 100.0;
  o.max_span_gap_s = std::numeric_limits<double>::infinity();  // this odometry is not of 2009
  const UtiasDataset d = loadUtiasMrclam(dir.path.string(), o);
  REQUIRE(d.robots.size() == 1);
  CHECK(d.time_reference_s == 100.0);
  CHECK(d.robots[0].odometry[0].time_s == 0.5);
  CHECK(d.robots[0].groundtruth[0].time_s == Approx(1248446082.116).margin(1e-5));
}

TEST_CASE("UTIAS loader names file and line of every malformed row", "[datasets]") {
  const std::string row = "1248446192.950 \t  63 \t  5.414 \t -0.487 \r\n";
  std::string e = loadError("Robot2_Measurement.dat", kMeasurement + "1248446192.950 \t 63 \t 5.4\r\n");
  CHECK(contains(e, "Robot2_Measurement.dat:10: expected 4 fields, got 3"));
  e = loadError("Robot1_Measurement.dat", kMeasurement + "1248446193.300 \t 6x3 \t 5.4 \t 0.1\r\n");
  CHECK(contains(e, "Robot1_Measurement.dat:10: field 2 is not a finite number: '6x3'"));
  e = loadError("Robot1_Measurement.dat", kMeasurement + row);  // 192.950 after 193.200
  CHECK(contains(e, "Robot1_Measurement.dat:10: measurement goes back in time"));
  e = loadError("Robot1_Measurement.dat", kMeasurement + "1248446193.300 \t 63.5 \t 5.4 \t 0.1\r\n");
  CHECK(contains(e, ":10: the barcode must be a whole number, got 63.5"));
  e = loadError("Robot1_Measurement.dat", kMeasurement + "1248446193.300 \t 63 \t -1 \t 0.1\r\n");
  CHECK(contains(e, ":10: the range must be > 0"));
  e = loadError("Robot1_Measurement.dat", kMeasurement + "1248446193.300 \t 63 \t 2 \t 4.0\r\n");
  CHECK(contains(e, ":10: the bearing must be in [-pi, pi]"));
  e = loadError("Robot2_Odometry.dat", kOdometry + "1248446188.000 \t 0 \t 0\r\n");
  CHECK(contains(e, "Robot2_Odometry.dat:8: odometry goes back in time"));
  e = loadError("Robot1_Odometry.dat", kOdometry + "1248446189.000 \t 0 \t nan\r\n");
  CHECK(contains(e, "Robot1_Odometry.dat:8: field 3 is not a finite number: 'nan'"));
  e = loadError("Robot1_Groundtruth.dat", kGroundtruth + "1248446182.200 \t 1 \t 2 \t 3 \t 4\r\n");
  CHECK(contains(e, "Robot1_Groundtruth.dat:7: expected 4 fields, got 5"));
  e = loadError("Robot1_Groundtruth.dat", kHeader);
  CHECK(contains(e, "Robot1_Groundtruth.dat: no ground truth rows in the file"));
  e = loadError("Barcodes.dat", kBarcodes + "  8 \t  63 \r\n");
  CHECK(contains(e, "Barcodes.dat:12: barcode 63 is listed twice"));
  e = loadError("Barcodes.dat", kBarcodes + "  7 \t  99 \r\n");
  CHECK(contains(e, "Barcodes.dat:12: subject 7 is listed twice"));
  e = loadError("Barcodes.dat", kHeader + "  1 \t   5 \r\n  6 \t  63 \r\n  7 \t  81 \r\n");
  CHECK(contains(e, "Barcodes.dat: robot subject 2 has no barcode"));
  e = loadError("Landmark_Groundtruth.dat", kLandmarks + "  9 \t 1 \t 2 \t 0 \t 0 \r\n");
  CHECK(contains(e, "Landmark_Groundtruth.dat:7: subject 9 is not a landmark of Barcodes.dat"));
  e = loadError("Landmark_Groundtruth.dat", kLandmarks + "  3 \t 1 \t 2 \t 0 \t 0 \r\n");
  CHECK(contains(e, "Landmark_Groundtruth.dat:7: subject 3 is not a landmark"));
  e = loadError("Landmark_Groundtruth.dat", kLandmarks + "  6 \t 1 \t 2 \t 0 \t 0 \r\n");
  CHECK(contains(e, "Landmark_Groundtruth.dat:7: subject 6 is listed twice"));
  // Integers beyond int's range are refused, not narrowed onto a valid barcode or subject
  // (4294967357 would wrap to barcode 63's neighbour 61, 4294967302 to landmark 6).
  for (const char* big : {"4294967357", "-4294967235", "4294967296"}) {
    e = loadError("Robot1_Measurement.dat", kMeasurement + "1248446193.300 \t " + big + " \t 5.4 \t 0.1\r\n");
    CHECK(contains(e, std::string(":10: the barcode must be in [0, 100000], got ") + big));
  }
  e = loadError("Landmark_Groundtruth.dat", kLandmarks + "  4294967302 \t 1 \t 2 \t 0 \t 0 \r\n");
  CHECK(contains(e, "Landmark_Groundtruth.dat:7: subject 4294967302 is not a landmark of Barcodes.dat"));
  CHECK(loadError("Robot1_Odometry.dat", kOdometry) == "");

  const TempFolder dir("utias_mrclam_missing");
  writeFolder(dir);
  std::filesystem::remove(dir.path / "Robot2_Groundtruth.dat");
  CHECK(sylva_test::throwsCode([&] { loadUtiasMrclam(dir.path.string(), robots12()); },
                               sylva::ErrorCode::kMalformedData));
  UtiasLoadOptions bad;
  bad.robots = {6};
  CHECK(sylva_test::throwsCode([&] { loadUtiasMrclam(dir.path.string(), bad); },
                               sylva::ErrorCode::kInvalidArgument));
}

TEST_CASE("UTIAS loader reports files that cover different time spans", "[datasets]") {
  // Ground truth of robot 1 cut 100 s short of its odometry.
  const std::string late_odometry = kOdometry + "1248446290.000 \t 0 \t 0\r\n";
  std::string e = loadError("Robot1_Odometry.dat", late_odometry);
  CHECK(contains(e, "the files cover different time spans"));
  CHECK(contains(e, "Robot1_Odometry.dat [1248446188.323, 1248446290] s"));
  CHECK(contains(e, "Robot1_Groundtruth.dat [1248446182.116, 1248446182.132] s"));
  // A measurement long after the odometry ends.
  e = loadError("Robot2_Measurement.dat", kMeasurement + "1248446300.000 \t 63 \t 5.4 \t 0.1\r\n");
  CHECK(contains(e, "Robot2_Measurement.dat [1248446192.94, 1248446300] s"));
  // Robot 2's ground truth ends 60 s after robot 1's (and its odometry with it).
  const TempFolder dir("utias_mrclam_spans");
  writeFolder(dir);
  dir.write("Robot2_Groundtruth.dat", kGroundtruth + "1248446242.000 \t 2.2 \t 4.2 \t 0.0\r\n");
  dir.write("Robot2_Odometry.dat", kOdometry + "1248446241.000 \t 0 \t 0\r\n");
  try {
    loadUtiasMrclam(dir.path.string(), robots12());
    FAIL("loaded");
  } catch (const sylva::Error& error) {
    CHECK(error.code() == sylva::ErrorCode::kMalformedData);
    CHECK(contains(error.what(), "Robot1_Groundtruth.dat [1248446182.116, 1248446182.132] s, "));
  }
  // The tolerance is the caller's: infinity accepts, a negative one is a mistake.
  UtiasLoadOptions o = robots12();
  o.max_span_gap_s = std::numeric_limits<double>::infinity();
  CHECK(loadUtiasMrclam(dir.path.string(), o).robot(2).groundtruth.size() == 3);
  o.max_span_gap_s = 61.0;
  CHECK(loadUtiasMrclam(dir.path.string(), o).robots.size() == 2);
  o.max_span_gap_s = -1.0;
  CHECK(sylva_test::throwsCode([&] { loadUtiasMrclam(dir.path.string(), o); }, sylva::ErrorCode::kInvalidArgument));
}

TEST_CASE("UTIAS loader refuses times whose difference to the time reference overflows", "[datasets]") {
  // Caught by an invariant of fuzz/utias_mrclam.cpp (loaded times are finite): -1e308 and
  // 1e308 are finite times whose spans agree, but 1e308 less the reference -1e308 is not.
  const TempFolder dir("utias_mrclam_overflow");
  writeFolder(dir);
  dir.write("Robot1_Odometry.dat", "-1e308 0 0\n1e308 0 0\n");
  dir.write("Robot1_Measurement.dat", "0 63 5 0.1\n");
  dir.write("Robot1_Groundtruth.dat", "-1e308 0 0 0\n1e308 0 0 0\n");
  UtiasLoadOptions o;
  o.robots = {1};
  std::string e;
  try {
    loadUtiasMrclam(dir.path.string(), o);
  } catch (const sylva::Error& error) {
    CHECK(error.code() == sylva::ErrorCode::kMalformedData);
    e = error.what();
  }
  CHECK(contains(e, "Robot1_Odometry.dat: the time 1e+308 s less the time reference -1e+308 s overflows"));
  // An explicit reference half-way keeps every difference finite.
  o.time_reference_s = 0.0;
  CHECK(loadUtiasMrclam(dir.path.string(), o).robot(1).groundtruth.back().time_s == 1e308);
}

TEST_CASE("UTIAS loader on the real Dataset 7 matches the counts of its README", "[datasets][data]") {
  const std::string folder = SYLVA_DATA_DIR "/utias-mrclam/MRCLAM_Dataset7";
  if (!std::filesystem::exists(folder + "/Barcodes.dat")) {
    WARN("skipped: UTIAS MRCLAM Dataset 7 not found in " << folder);
    SUCCEED("skipped");
    return;
  }
  const UtiasDataset d = loadUtiasMrclam(folder);
  CHECK(d.barcode_of_subject.size() == 20);
  CHECK(d.landmarks.size() == 15);
  CHECK(d.time_reference_s == 1248446182.0);
  // README: rows, to landmarks, to robots, unknown barcodes, per robot.
  const long rows[5] = {3228, 4518, 5399, 2377, 4760};
  const std::size_t to_landmarks[5] = {2578, 3818, 4425, 1822, 3424};
  const std::size_t to_robots[5] = {650, 700, 965, 555, 1336};
  const std::size_t unknown[5] = {0, 0, 9, 0, 0};
  REQUIRE(d.robots.size() == 5);
  for (int i = 0; i < 5; ++i) {
    const auto& r = d.robots[static_cast<std::size_t>(i)];
    INFO("robot " << r.robot);
    CHECK(r.robot == i + 1);
    CHECK(r.measurement_rows == rows[i]);
    CHECK(r.landmark_observations.size() == to_landmarks[i]);
    CHECK(r.robot_observations.size() == to_robots[i]);
    CHECK(r.unknown_barcode_rows.size() == unknown[i]);
    // Ground truth covers 900 s and starts before the odometry and the measurements.
    CHECK(r.groundtruth.front().time_s == Approx(0.116).margin(1e-6));
    CHECK(r.groundtruth.back().time_s == Approx(900.106).margin(1e-6));
    CHECK(r.odometry.front().time_s > r.groundtruth.front().time_s + 5.0);
    CHECK(r.landmark_observations.front().time_s > r.groundtruth.front().time_s);
  }
  int misread34 = 0, misread52 = 0;
  for (const auto& u : d.robot(3).unknown_barcode_rows) {
    misread34 += u.barcode == 34;
    misread52 += u.barcode == 52;
  }
  CHECK(misread34 == 1);
  CHECK(misread52 == 8);
}
