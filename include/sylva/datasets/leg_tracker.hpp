#pragma once
/// @file
/// Loader of the laser scans of the leg_tracker demo recording: a stationary 2D laser scanner
/// in a room where people walk. Cite:
///
///   A. Leigh, J. Pineau, N. Olmedo, H. Zhang, "Person Tracking and Following with 2D Laser
///   Scanners", IEEE ICRA 2015 (data: repository angusleigh/leg_tracker,
///   demo_stationary_simple_environment.bag, BSD 3-Clause).
///
/// The data never ship with sylva. A recording `<name>` is two text files, as converted from
/// the bag (see the data folder's README.md):
///
///   <name>_scan_params.txt  "# comment" lines and "key value" lines: angle_min,
///                           angle_increment, n_beams, range_min, range_max, and optionally
///                           scan_time (others are ignored)
///   <name>_scans.csv        one scan per line: the stamp in seconds, then n_beams ranges in
///                           metres; "inf" (no return within range_max) and "nan" (invalid)
///                           are readings, not errors (sylva/laser/scan.hpp says what each means)
///
/// Checks (each a `sylva::Error(kMalformedData)` naming the file and the line): a file that
/// cannot be opened, a missing key, a value or field that is not a number, a scan geometry the
/// laser tools refuse (`laser::validateScanGeometry`), a line with the wrong number of fields,
/// a stamp that is not finite or does not come after the previous one, and a file of no scans.

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "sylva/core/error.hpp"
#include "sylva/datasets/numeric_table.hpp"
#include "sylva/laser/scan.hpp"

namespace sylva::datasets {

/// One leg_tracker recording: its beam geometry and every scan.
struct LegTrackerRecording {
  LaserScanGeometry geometry;
  double scan_time_s = 0.0;                 ///< nominal time between scans; 0 if the file has none
  std::vector<double> stamps_s;             ///< one per scan, increasing
  std::vector<std::vector<double>> ranges;  ///< one per scan, `geometry.beams` readings each
};

/// Reads `<name>_scan_params.txt`: the beam geometry, and the nominal scan period into
/// `*scan_time_s` when it is given (0 when the file has no scan_time).
inline LaserScanGeometry loadLegTrackerScanParams(const std::string& path,
                                                  double* scan_time_s = nullptr) {
  std::ifstream in(path);
  if (!in) failMalformed(path, 0, "cannot open the scan parameter file");
  std::map<std::string, double> values;
  std::string line;
  long number = 0;
  while (std::getline(in, line)) {
    ++number;
    if (line.empty() || line[0] == '#' || line == "\r") continue;
    std::istringstream fields(line);
    std::string key, value;
    if (!(fields >> key >> value))
      failMalformed(path, number, "expected 'key value', got '" + line + "'");
    if (key == "frame_id") continue;
    double v = 0.0;
    if (!detail::parseField(value, /*allow_non_finite=*/true, v))
      failMalformed(path, number, "the value of '" + key + "' is not a number: '" + value + "'");
    values[key] = v;
  }
  for (const char* key : {"angle_min", "angle_increment", "n_beams", "range_min", "range_max"})
    if (!values.count(key)) failMalformed(path, 0, std::string("missing key '") + key + "'");
  LaserScanGeometry g;
  g.angle_min_rad = values["angle_min"];
  g.angle_increment_rad = values["angle_increment"];
  const double beams = values["n_beams"];
  if (!(beams >= 2.0 && beams <= 100000.0) || beams != std::floor(beams))
    failMalformed(path, 0, "n_beams must be a whole number from 2 to 100000");
  g.beams = static_cast<int>(beams);
  g.min_range_m = values["range_min"];
  g.max_range_m = values["range_max"];
  try {
    laser::validateScanGeometry(g);
  } catch (const Error& e) {
    failMalformed(path, 0, e.what());
  }
  if (scan_time_s) *scan_time_s = values.count("scan_time") ? values["scan_time"] : 0.0;
  return g;
}

/// Appends every scan of `path` (`<name>_scans.csv`), each of `beams` ranges, to `out`.
inline void loadLegTrackerScans(const std::string& path, int beams, LegTrackerRecording& out) {
  NumericTableFormat format;
  format.min_fields = format.max_fields = beams + 1;  // the stamp, then the ranges
  format.delimiters = ",";
  format.allow_non_finite = true;
  readNumericTable(path, format, [&](const NumericRow& row) {
    if (!std::isfinite(row[0])) row.fail("the stamp is not finite");
    if (!out.stamps_s.empty() && !(row[0] > out.stamps_s.back())) {
      std::ostringstream os;
      os << "the stamp " << row[0] << " does not come after the previous one";
      row.fail(os.str());
    }
    out.stamps_s.push_back(row[0]);
    out.ranges.emplace_back(beams);
    for (int i = 0; i < beams; ++i) out.ranges.back()[static_cast<std::size_t>(i)] = row[i + 1];
  });
  if (out.stamps_s.empty()) failMalformed(path, 0, "no scans in the file");
}

/// Both files of the recording `name` in `dir`: `<dir>/<name>_scan_params.txt` and
/// `<dir>/<name>_scans.csv`.
inline LegTrackerRecording loadLegTrackerRecording(const std::string& dir,
                                                   const std::string& name) {
  LegTrackerRecording out;
  out.geometry = loadLegTrackerScanParams(dir + "/" + name + "_scan_params.txt", &out.scan_time_s);
  loadLegTrackerScans(dir + "/" + name + "_scans.csv", out.geometry.beams, out);
  return out;
}

}  // namespace sylva::datasets
