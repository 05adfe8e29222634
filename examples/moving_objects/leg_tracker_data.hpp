#pragma once
// Loader of the leg_tracker demo scans (A. Leigh, J. Pineau, N. Olmedo, H. Zhang, "Person
// Tracking and Following with 2D Laser Scanners", ICRA 2015; data: repository
// angusleigh/leg_tracker, demo_stationary_simple_environment.bag, BSD 3-Clause), as
// converted to text for this project (see the data folder's README.md):
//
//   <name>_scan_params.txt   "# comment" lines and "key value" lines: angle_min,
//                            angle_increment, n_beams, range_min, range_max (others ignored)
//   <name>_scans.csv         one scan per line: stamp_s, then n_beams ranges in metres;
//                            "inf" (no return within range_max) and "nan" (invalid) allowed
//
// The data are never copied into the repository; the program reads them from --data.
//
// Errors: a file that cannot be opened, a missing key, a field that is not a number, a
// line with the wrong number of fields, or stamps that do not increase throw
// sylva::Error(kMalformedData) naming the file and the line.

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <sylva/core/error.hpp>
#include <sylva/datasets/numeric_table.hpp>
#include <sylva/laser/scan.hpp>

namespace moving_objects {

using namespace sylva::laser;  // the detector and its scans (include/sylva/laser)
using sylva::LaserScanGeometry;

struct RealScans {
  LaserScanGeometry geometry;
  double scan_time_s = 0.0;          ///< nominal time between scans (params file), 0 if absent
  std::vector<double> stamps_s;
  std::vector<std::vector<double>> ranges;
};

inline LaserScanGeometry loadScanParams(const std::string& path, double* scan_time_s = nullptr) {
  std::ifstream in(path);
  if (!in) sylva::datasets::failMalformed(path, 0, "cannot open the scan parameter file");
  std::map<std::string, double> values;
  std::string line;
  long number = 0;
  while (std::getline(in, line)) {
    ++number;
    if (line.empty() || line[0] == '#' || line == "\r") continue;
    std::istringstream fields(line);
    std::string key, value;
    if (!(fields >> key >> value)) sylva::datasets::failMalformed(path, number, "expected 'key value', got '" + line + "'");
    if (key == "frame_id") continue;
    double v = 0.0;
    if (!sylva::datasets::detail::parseField(value, /*allow_non_finite=*/true, v)) sylva::datasets::failMalformed(path, number, "the value of '" + key + "' is not a number: '" + value + "'");
    values[key] = v;
  }
  for (const char* key : {"angle_min", "angle_increment", "n_beams", "range_min", "range_max"})
    if (!values.count(key)) sylva::datasets::failMalformed(path, 0, std::string("missing key '") + key + "'");
  LaserScanGeometry g;
  g.angle_min_rad = values["angle_min"];
  g.angle_increment_rad = values["angle_increment"];
  const double beams = values["n_beams"];
  if (!(beams >= 2.0 && beams <= 100000.0) || beams != std::floor(beams))
    sylva::datasets::failMalformed(path, 0, "n_beams must be a whole number from 2 to 100000");
  g.beams = static_cast<int>(beams);
  g.min_range_m = values["range_min"];
  g.max_range_m = values["range_max"];
  try {
    validateScanGeometry(g);
  } catch (const sylva::Error& e) {
    sylva::datasets::failMalformed(path, 0, e.what());
  }
  if (scan_time_s) *scan_time_s = values.count("scan_time") ? values["scan_time"] : 0.0;
  return g;
}

/// Reads every scan of `path`, each with `beams` ranges.
inline void loadScans(const std::string& path, int beams, RealScans& out) {
  sylva::datasets::NumericTableFormat format;
  format.min_fields = format.max_fields = beams + 1;  // the stamp, then the ranges
  format.delimiters = ",";
  format.allow_non_finite = true;
  sylva::datasets::readNumericTable(path, format, [&](const sylva::datasets::NumericRow& row) {
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
  if (out.stamps_s.empty()) sylva::datasets::failMalformed(path, 0, "no scans in the file");
}

/// Both files of a recording: `<dir>/<name>_scan_params.txt` and `<dir>/<name>_scans.csv`.
inline RealScans loadLegTrackerRecording(const std::string& dir, const std::string& name) {
  RealScans out;
  out.geometry = loadScanParams(dir + "/" + name + "_scan_params.txt", &out.scan_time_s);
  loadScans(dir + "/" + name + "_scans.csv", out.geometry.beams, out);
  return out;
}

}  // namespace moving_objects
