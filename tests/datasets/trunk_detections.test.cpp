// Trunk detections and camera intrinsics (datasets/trunk_detections.hpp): what a file means,
// an exact round trip through the writers, and a clear error for each malformed line.

#include "sylva_catch.hpp"

#include <cmath>
#include <string>
#include <vector>

#include <sylva/datasets/trunk_detections.hpp>

#include "temp_folder.hpp"

// Own namespace: the tests of a folder are compiled as one unity translation unit.
namespace unity_datasets_trunk_detections {

using namespace sylva;
using namespace sylva::datasets;
using sylva_test::contains;
using sylva_test::TempFolder;

std::string errorOf(const TempFolder& dir, const std::string& text) {
  const std::string path = dir.write("bad.csv", text);
  try {
    readTrunkDetections(path);
  } catch (const Error& e) {
    return e.code() == ErrorCode::kMalformedData ? e.what() : std::string("wrong code: ") + e.what();
  }
  return "no error";
}

TEST_CASE("Trunk detections: rows of one time form one frame, a time alone is an empty frame",
          "[datasets][trunk_detections]") {
  const TempFolder dir("trunk_detections");
  const std::string path = dir.write("d.csv",
                                     "# time_s, u_px, v_px, w_px[, id]\n"
                                     "0.1, 312.25, 401.5, 18.75, 17\n"
                                     "0.1,102,388,9.5\r\n"
                                     "0.2\n"
                                     "\n"
                                     "0.3, 5, 6, 7, 0\n");
  const auto frames = readTrunkDetections(path);
  REQUIRE(frames.size() == 3);
  CHECK(frames[0].t_s == 0.1);
  REQUIRE(frames[0].detections.size() == 2);
  CHECK(frames[0].detections[0].z == Vec<3>(312.25, 401.5, 18.75));
  CHECK(frames[0].detections[0].id == Id{17});
  CHECK(!frames[0].detections[1].id);
  CHECK(frames[1].t_s == 0.2);
  CHECK(frames[1].detections.empty());
  CHECK(frames[2].detections[0].id == Id{0});
}

TEST_CASE("Trunk detections and camera: written and read back, the same doubles", "[datasets][trunk_detections]") {
  const TempFolder dir("trunk_detections_round_trip");
  std::vector<TrunkDetectionFrame> frames = {
      {0.1, {{Vec<3>(1.0 / 3.0, 2.0 / 7.0, 1e-3), Id{4}}, {Vec<3>(-0.5, 1e6 + 0.123456789, 3.25), std::nullopt}}},
      {0.1 + 0.2, {}},
      {0.7, {{Vec<3>(std::nextafter(100.0, 200.0), 5.0, 6.0), Id{123456789}}}}};
  writeTrunkDetections((dir.path / "d.csv").string(), frames);
  const auto back = readTrunkDetections((dir.path / "d.csv").string());
  REQUIRE(back.size() == frames.size());
  for (std::size_t k = 0; k < frames.size(); ++k) {
    CHECK(back[k].t_s == frames[k].t_s);
    REQUIRE(back[k].detections.size() == frames[k].detections.size());
    for (std::size_t i = 0; i < frames[k].detections.size(); ++i) {
      CHECK(back[k].detections[i].z == frames[k].detections[i].z);
      CHECK(back[k].detections[i].id == frames[k].detections[i].id);
    }
  }
  const CameraIntrinsics camera{500.5, 499.25, 320.0 + 1.0 / 3.0, 240.0, 640, 480};
  writeCameraIntrinsics((dir.path / "c.csv").string(), camera);
  const CameraIntrinsics read = readCameraIntrinsics((dir.path / "c.csv").string());
  CHECK(read.fx == camera.fx);
  CHECK(read.fy == camera.fy);
  CHECK(read.cx == camera.cx);
  CHECK(read.cy == camera.cy);
  CHECK(read.width == 640);
  CHECK(read.height == 480);
}

TEST_CASE("Trunk detections: a malformed line is an error naming the file and line", "[datasets][trunk_detections]") {
  const TempFolder dir("trunk_detections_bad");
  CHECK(contains(errorOf(dir, "0.1, 1, 2\n"), "bad.csv:1: expected time_s alone"));
  CHECK(contains(errorOf(dir, "0.1, 1, 2, 0\n"), "bad.csv:1: the width w_px must be > 0"));
  CHECK(contains(errorOf(dir, "0.1, 1, 2, 3, 4.5\n"), "bad.csv:1: the id must be a whole number"));
  CHECK(contains(errorOf(dir, "0.1, 1, 2, 3, -4\n"), "bad.csv:1: the id must be >= 0"));
  CHECK(contains(errorOf(dir, "0.2, 1, 2, 3\n0.1, 1, 2, 3\n"), "bad.csv:2: the detection time goes back"));
  CHECK(contains(errorOf(dir, "0.1, 1, 2, 3, 4, 5\n"), "bad.csv:1: expected 1 to 5 fields, got 6"));
  CHECK(contains(errorOf(dir, "0.1, 1, nan, 3\n"), "bad.csv:1: field 3 is not a finite number"));
  CHECK(contains(errorOf(dir, "0.1, 1, 2,\n"), "bad.csv:1: the line ends with an empty field"));
  CHECK(contains(errorOf(dir, "# only a comment\n"), "no detection and no frame"));
  CHECK(contains(errorOf(dir, "0.1, 1, 2, 3\n0.2, 1, 2"), "bad.csv:2: expected time_s alone"));  // truncated
}

TEST_CASE("Camera intrinsics: one row of six fields, positive focal lengths and size", "[datasets][trunk_detections]") {
  const TempFolder dir("camera_intrinsics_bad");
  const auto error = [&](const std::string& text) {
    try {
      readCameraIntrinsics(dir.write("c.csv", text));
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  CHECK(contains(error("500, 500, 320, 240, 640\n"), "c.csv:1: expected 6 fields, got 5"));
  CHECK(contains(error("500, 500, 320, 240, 640, 480\n1, 1, 1, 1, 1, 1\n"), "c.csv:2: a camera file holds one row"));
  CHECK(contains(error("0, 500, 320, 240, 640, 480\n"), "the focal lengths must be > 0"));
  CHECK(contains(error("500, 500, 320, 240, 640.5, 480\n"), "the image width must be a whole number"));
  CHECK(contains(error("500, 500, 320, 240, 0, 480\n"), "the image size must be positive"));
  CHECK(contains(error(""), "no camera row"));
  CHECK(contains(error("500, 500, 320, 240, 640, 480\n"), "no error"));
}

}  // namespace unity_datasets_trunk_detections
