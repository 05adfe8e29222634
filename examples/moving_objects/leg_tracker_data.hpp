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

#include "scan.hpp"

namespace moving_objects {

struct RealScans {
  ScanGeometry geometry;
  double scan_time_s = 0.0;          ///< nominal time between scans (params file), 0 if absent
  std::vector<double> stamps_s;
  std::vector<std::vector<double>> ranges;
};

namespace detail {

[[noreturn]] inline void malformed(const std::string& file, long line, const std::string& what) {
  std::ostringstream os;
  os << file;
  if (line > 0) os << ":" << line;
  os << ": " << what;
  sylva::fail(sylva::ErrorCode::kMalformedData, os.str());
}

/// A whole field as a double; "inf", "nan" (any case, optional sign) included.
inline bool parseNumber(const std::string& text, double& value) {
  std::size_t b = 0, e = text.size();
  while (b < e && (text[b] == ' ' || text[b] == '\t')) ++b;
  while (e > b && (text[e - 1] == ' ' || text[e - 1] == '\t' || text[e - 1] == '\r')) --e;
  if (b == e) return false;
  const std::string field = text.substr(b, e - b);
  char* end = nullptr;
  errno = 0;
  value = std::strtod(field.c_str(), &end);
  return end == field.c_str() + field.size() && errno != ERANGE;
}

}  // namespace detail

inline ScanGeometry loadScanParams(const std::string& path, double* scan_time_s = nullptr) {
  std::ifstream in(path);
  if (!in) detail::malformed(path, 0, "cannot open the scan parameter file");
  std::map<std::string, double> values;
  std::string line;
  long number = 0;
  while (std::getline(in, line)) {
    ++number;
    if (line.empty() || line[0] == '#' || line == "\r") continue;
    std::istringstream fields(line);
    std::string key, value;
    if (!(fields >> key >> value)) detail::malformed(path, number, "expected 'key value', got '" + line + "'");
    if (key == "frame_id") continue;
    double v = 0.0;
    if (!detail::parseNumber(value, v)) detail::malformed(path, number, "the value of '" + key + "' is not a number: '" + value + "'");
    values[key] = v;
  }
  for (const char* key : {"angle_min", "angle_increment", "n_beams", "range_min", "range_max"})
    if (!values.count(key)) detail::malformed(path, 0, std::string("missing key '") + key + "'");
  ScanGeometry g;
  g.angle_min_rad = values["angle_min"];
  g.angle_increment_rad = values["angle_increment"];
  const double beams = values["n_beams"];
  if (!(beams >= 2.0 && beams <= 100000.0) || beams != std::floor(beams))
    detail::malformed(path, 0, "n_beams must be a whole number from 2 to 100000");
  g.beams = static_cast<int>(beams);
  g.range_min_m = values["range_min"];
  g.range_max_m = values["range_max"];
  try {
    g.validate();
  } catch (const sylva::Error& e) {
    detail::malformed(path, 0, e.what());
  }
  if (scan_time_s) *scan_time_s = values.count("scan_time") ? values["scan_time"] : 0.0;
  return g;
}

/// Reads every scan of `path`, each with `beams` ranges.
inline void loadScans(const std::string& path, int beams, RealScans& out) {
  std::ifstream in(path);
  if (!in) detail::malformed(path, 0, "cannot open the scan file");
  std::string line, field;
  long number = 0;
  while (std::getline(in, line)) {
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    if (line.back() == ',') detail::malformed(path, number, "the line ends with an empty field");
    std::vector<double> values;
    values.reserve(static_cast<std::size_t>(beams) + 1);
    std::istringstream fields(line);
    while (std::getline(fields, field, ',')) {
      double v = 0.0;
      if (!detail::parseNumber(field, v)) {
        std::ostringstream os;
        os << "field " << values.size() + 1 << " is not a number: '" << field << "'";
        detail::malformed(path, number, os.str());
      }
      values.push_back(v);
    }
    if (static_cast<int>(values.size()) != beams + 1) {
      std::ostringstream os;
      os << "expected a stamp and " << beams << " ranges (" << beams + 1 << " fields), got "
         << values.size() << " fields";
      detail::malformed(path, number, os.str());
    }
    if (!std::isfinite(values[0])) detail::malformed(path, number, "the stamp is not finite");
    if (!out.stamps_s.empty() && !(values[0] > out.stamps_s.back())) {
      std::ostringstream os;
      os << "the stamp " << values[0] << " does not come after the previous one";
      detail::malformed(path, number, os.str());
    }
    out.stamps_s.push_back(values[0]);
    out.ranges.emplace_back(values.begin() + 1, values.end());
  }
  if (out.stamps_s.empty()) detail::malformed(path, 0, "no scans in the file");
}

/// Both files of a recording: `<dir>/<name>_scan_params.txt` and `<dir>/<name>_scans.csv`.
inline RealScans loadLegTrackerRecording(const std::string& dir, const std::string& name) {
  RealScans out;
  out.geometry = loadScanParams(dir + "/" + name + "_scan_params.txt", &out.scan_time_s);
  loadScans(dir + "/" + name + "_scans.csv", out.geometry.beams, out);
  return out;
}

}  // namespace moving_objects
