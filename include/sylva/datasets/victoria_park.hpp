#pragma once
/// @file
/// Loaders for the Victoria Park data set (a utility car with a SICK laser driving among the
/// trees of Victoria Park, Sydney; ACFR, J. Guivant and E. Nebot). Cite:
///
///   J. Guivant, E. Nebot, "Optimization of the Simultaneous Localization and Map-Building
///   Algorithm for Real-Time Implementation", IEEE Trans. Robotics and Automation 17(3),
///   242-257, 2001.
///   J. Guivant, E. Nebot, S. Baiker, "Autonomous navigation and map building using laser
///   range sensors in outdoor applications", Journal of Robotic Systems 17(10), 565-583, 2000.
///
/// The data never ship with sylva. The three plain-text files read here (whitespace
/// separated, no header; see the data folder's README.md) share one clock in seconds,
/// t = (t_ms_raw - 20967) / 1000:
///
///   measurements.dat  t, range (m, laser to the trunk centre), bearing (rad, 0..pi: 0 to the
///                     car's right, pi/2 straight ahead), trunk diameter (m); one row per
///                     detected trunk, rows of one laser scan share t -> `VictoriaParkScan`
///   odometry.txt      t, t_raw (ms), encoder speed v_e (m/s, rear left wheel), steering
///                     angle alpha (rad, positive = left)           -> `VictoriaParkOdometry`
///   gps.txt           t, t_raw (ms), x east (m), y north (m)       -> `VictoriaParkGps`
///
/// Checks (each a `sylva::Error(kMalformedData)` naming the file and line): the number of
/// fields, numbers in every field, time never going back, t_raw a whole number, range > 0,
/// bearing in [0, pi], diameter > 0, |steering| < pi/2. An empty file is an error too, and so
/// are files of one folder that cover different time spans (`loadVictoriaPark`). The
/// loaders convert nothing: the bearing stays in the laser's 0..pi convention
/// (`carBearing` gives the car-frame bearing, bearing - pi/2).

#include <cmath>
#include <string>
#include <vector>

#include "sylva/core/angles.hpp"
#include "sylva/datasets/numeric_table.hpp"

namespace sylva::datasets {

/// One detected trunk, as in measurements.dat.
struct VictoriaParkDetection {
  double range_m;      ///< laser to the trunk centre
  double bearing_rad;  ///< laser convention, 0 (right) .. pi (left), pi/2 ahead
  double diameter_m;   ///< trunk diameter estimated from the segment's angular width
};

/// The car-frame bearing (x forward, y left) of a laser bearing in the 0..pi convention.
inline double carBearing(const VictoriaParkDetection& d) { return d.bearing_rad - 0.5 * kPi; }

/// All trunks detected in one laser scan.
struct VictoriaParkScan {
  double t_s;
  std::vector<VictoriaParkDetection> detections;
};

struct VictoriaParkOdometry {
  double t_s;
  long t_raw_ms;
  double speed_mps;     ///< encoder speed v_e on the rear left wheel
  double steering_rad;  ///< front-wheel steering angle alpha, positive = turning left
};

struct VictoriaParkGps {
  double t_s;
  long t_raw_ms;
  double x_m;  ///< local east
  double y_m;  ///< local north
};

/// Reads measurements.dat: one scan per distinct time, in file order.
inline std::vector<VictoriaParkScan> loadVictoriaParkMeasurements(const std::string& path) {
  std::vector<VictoriaParkScan> scans;
  NumericTableFormat format;
  format.min_fields = format.max_fields = 4;
  readNumericTable(path, format, [&](const NumericRow& row) {
    const double t = row[0];
    if (!scans.empty()) requireNonDecreasing(row, scans.back().t_s, t, "the scan time");
    if (!(row[1] > 0.0)) row.fail("the range must be > 0, got " + row.text(1));
    if (!(row[2] >= 0.0 && row[2] <= kPi)) row.fail("the bearing must lie in [0, pi] (laser convention), got " + row.text(2));
    if (!(row[3] > 0.0)) row.fail("the diameter must be > 0, got " + row.text(3));
    if (scans.empty() || t != scans.back().t_s) scans.push_back(VictoriaParkScan{t, {}});
    scans.back().detections.push_back(VictoriaParkDetection{row[1], row[2], row[3]});
  });
  if (scans.empty()) failMalformed(path, 0, "no detections in the file");
  return scans;
}

/// Reads odometry.txt.
inline std::vector<VictoriaParkOdometry> loadVictoriaParkOdometry(const std::string& path) {
  std::vector<VictoriaParkOdometry> samples;
  NumericTableFormat format;
  format.min_fields = format.max_fields = 4;
  readNumericTable(path, format, [&](const NumericRow& row) {
    if (!samples.empty()) requireNonDecreasing(row, samples.back().t_s, row[0], "the odometry time");
    const long raw = row.integer(1, "the raw time (ms)");
    if (!(std::abs(row[3]) < 0.5 * kPi)) row.fail("the steering angle must lie in (-pi/2, pi/2), got " + row.text(3));
    samples.push_back(VictoriaParkOdometry{row[0], raw, row[2], row[3]});
  });
  if (samples.empty()) failMalformed(path, 0, "no odometry in the file");
  return samples;
}

/// Reads gps.txt.
inline std::vector<VictoriaParkGps> loadVictoriaParkGps(const std::string& path) {
  std::vector<VictoriaParkGps> fixes;
  NumericTableFormat format;
  format.min_fields = format.max_fields = 4;
  readNumericTable(path, format, [&](const NumericRow& row) {
    if (!fixes.empty()) requireNonDecreasing(row, fixes.back().t_s, row[0], "the GPS time");
    fixes.push_back(VictoriaParkGps{row[0], row.integer(1, "the raw time (ms)"), row[2], row[3]});
  });
  if (fixes.empty()) failMalformed(path, 0, "no GPS fixes in the file");
  return fixes;
}

/// The three files of the data set's folder.
struct VictoriaParkData {
  std::vector<VictoriaParkScan> scans;
  std::vector<VictoriaParkOdometry> odometry;
  std::vector<VictoriaParkGps> gps;
};

/// Reads measurements.dat, odometry.txt and gps.txt from `folder`. The three files must start
/// and end within `max_span_gap_s` of each other (the real files: within 1 s); a file cut
/// short is reported as kMalformedData naming both spans. Infinity turns the check off; a
/// negative or NaN gap is kInvalidArgument.
inline VictoriaParkData loadVictoriaPark(const std::string& folder, double max_span_gap_s = 30.0) {
  if (!(max_span_gap_s >= 0.0))
    fail(ErrorCode::kInvalidArgument, "loadVictoriaPark: max_span_gap_s must be >= 0 (infinity: no check)");
  VictoriaParkData data;
  data.scans = loadVictoriaParkMeasurements(folder + "/measurements.dat");
  data.odometry = loadVictoriaParkOdometry(folder + "/odometry.txt");
  data.gps = loadVictoriaParkGps(folder + "/gps.txt");
  const FileTimeSpan spans[3] = {{folder + "/odometry.txt", data.odometry.front().t_s, data.odometry.back().t_s},
                                 {folder + "/measurements.dat", data.scans.front().t_s, data.scans.back().t_s},
                                 {folder + "/gps.txt", data.gps.front().t_s, data.gps.back().t_s}};
  for (const FileTimeSpan& other : {spans[1], spans[2]})
    if (std::abs(other.first - spans[0].first) > max_span_gap_s || std::abs(other.last - spans[0].last) > max_span_gap_s)
      failTimeSpanMismatch(spans[0], other, max_span_gap_s);
  return data;
}

}  // namespace sylva::datasets
