#pragma once
/// @file
/// Trunk detections of a camera, as a trunk detector would write them, and the camera's
/// intrinsics: the input of the monocular tree pipeline (`slam::MonocularTreeSlam`,
/// `forest_slam --detections FILE --camera FILE`). Both are CSV files read by
/// `readNumericTable` (a line starting with '#' is a comment; a malformed line is an error
/// naming the file and line).
///
/// Detections, one per row, frames in time order:
///
///   # time_s, u_px, v_px, w_px[, id]
///   0.1, 312.25, 401.5, 18.75, 17
///   0.1, 102.0, 388.0, 9.5, 4
///   0.2
///
///   - u, v: the centre of the trunk base's image ellipse (pixels); w: the trunk's width at its
///     base (pixels, > 0);
///   - id: optional, a whole number >= 0 naming the tree (a tracker's or a simulator's id);
///     needed only to associate by id;
///   - rows of one time form one frame; a row with the time alone is a frame without
///     detections (the filter still predicts to it); times never go back.
///
/// Camera, one row:
///
///   # fx_px, fy_px, cx_px, cy_px, width_px, height_px
///   500, 500, 320, 240, 640, 480
///
/// `writeTrunkDetections` and `writeCameraIntrinsics` write the same formats with 17
/// significant digits, so that a file written and read back holds the same doubles.

#include <cmath>
#include <cstdio>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include "sylva/core/error.hpp"
#include "sylva/core/types.hpp"
#include "sylva/datasets/numeric_table.hpp"

namespace sylva::datasets {

struct TrunkDetection {
  Vec<3> z;               ///< [u, v, w] pixels
  std::optional<Id> id;   ///< the tree, when the file names it
};

struct TrunkDetectionFrame {
  double t_s = 0.0;
  std::vector<TrunkDetection> detections;
};

/// A pinhole camera's intrinsics (pixels) and image size.
struct CameraIntrinsics {
  double fx = 0.0, fy = 0.0, cx = 0.0, cy = 0.0;
  int width = 0, height = 0;
};

/// Reads a detections file (see the file comment). Throws kMalformedData for a malformed or
/// unreadable file, a time that goes back, a width that is not positive, or an id that is not
/// a whole number >= 0; an empty file (no frame) too.
inline std::vector<TrunkDetectionFrame> readTrunkDetections(const std::string& path) {
  std::vector<TrunkDetectionFrame> frames;
  NumericTableFormat format;
  format.min_fields = 1;
  format.max_fields = 5;
  format.delimiters = ",";
  readNumericTable(path, format, [&](const NumericRow& row) {
    if (row.size() == 2 || row.size() == 3) row.fail("expected time_s alone, or time_s, u_px, v_px, w_px[, id]");
    const double t = row[0];
    if (!frames.empty()) requireNonDecreasing(row, frames.back().t_s, t, "the detection time");
    if (frames.empty() || t != frames.back().t_s) frames.push_back(TrunkDetectionFrame{t, {}});
    if (row.size() == 1) return;
    TrunkDetection d{Vec<3>(row[1], row[2], row[3]), std::nullopt};
    if (!(d.z[2] > 0.0)) row.fail("the width w_px must be > 0, got " + row.text(3));
    if (row.size() == 5) {
      const long id = row.integer(4, "the id");
      if (id < 0) row.fail("the id must be >= 0, got " + row.text(4));
      d.id = static_cast<Id>(id);
    }
    frames.back().detections.push_back(d);
  });
  if (frames.empty()) failMalformed(path, 0, "no detection and no frame in the file");
  return frames;
}

/// Reads a camera file (see the file comment). Throws kMalformedData unless it holds exactly
/// one row of six fields with positive focal lengths and a positive whole image size.
inline CameraIntrinsics readCameraIntrinsics(const std::string& path) {
  CameraIntrinsics c;
  readSingleCsvRow(path, 6, "camera", [&](const NumericRow& row) {
    c.fx = row[0];
    c.fy = row[1];
    c.cx = row[2];
    c.cy = row[3];
    const long width = row.integer(4, "the image width");
    const long height = row.integer(5, "the image height");
    if (!(c.fx > 0.0) || !(c.fy > 0.0)) row.fail("the focal lengths must be > 0");
    if (width <= 0 || height <= 0 || width > 1000000 || height > 1000000)
      row.fail("the image size must be positive (and at most 10^6 pixels a side)");
    c.width = static_cast<int>(width);
    c.height = static_cast<int>(height);
  });
  return c;
}

namespace detail {
inline std::string fullPrecision(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.17g", v);
  return buffer;
}
}  // namespace detail

/// Writes `frames` in the detections format (ids where the detections have them). Throws
/// kInvalidArgument for a value that is not finite, and kMalformedData when the file cannot be
/// written.
inline void writeTrunkDetections(const std::string& path, const std::vector<TrunkDetectionFrame>& frames) {
  std::ofstream out(path);
  if (!out) failMalformed(path, 0, "cannot open the file for writing");
  out << "# time_s, u_px, v_px, w_px[, id]\n";
  for (const TrunkDetectionFrame& f : frames) {
    if (!std::isfinite(f.t_s)) fail(ErrorCode::kInvalidArgument, "writeTrunkDetections: a frame time is not finite");
    const std::string t = detail::fullPrecision(f.t_s);
    if (f.detections.empty()) out << t << "\n";
    for (const TrunkDetection& d : f.detections) {
      if (!d.z.allFinite()) fail(ErrorCode::kInvalidArgument, "writeTrunkDetections: a detection is not finite");
      out << t << "," << detail::fullPrecision(d.z[0]) << "," << detail::fullPrecision(d.z[1]) << ","
          << detail::fullPrecision(d.z[2]);
      if (d.id) out << "," << *d.id;
      out << "\n";
    }
  }
  if (!out) failMalformed(path, 0, "writing failed");
}

/// Writes the camera file.
inline void writeCameraIntrinsics(const std::string& path, const CameraIntrinsics& c) {
  std::ofstream out(path);
  if (!out) failMalformed(path, 0, "cannot open the file for writing");
  out << "# fx_px, fy_px, cx_px, cy_px, width_px, height_px\n"
      << detail::fullPrecision(c.fx) << "," << detail::fullPrecision(c.fy) << "," << detail::fullPrecision(c.cx) << ","
      << detail::fullPrecision(c.cy) << "," << c.width << "," << c.height << "\n";
  if (!out) failMalformed(path, 0, "writing failed");
}

}  // namespace sylva::datasets
