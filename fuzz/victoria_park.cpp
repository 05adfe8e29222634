// Fuzz target: the Victoria Park loaders (sylva/datasets/victoria_park.hpp).
//
// Input: one byte that picks the loader by its value modulo 4 ('0' measurements.dat, '1'
// odometry.txt, '2' gps.txt, '3' the folder: the three files separated by '@', in that
// order; a file without a part is missing), then the file(s). For the folder, bit 2 of the
// byte turns the check of the files' time spans off ('7': max_span_gap_s = infinity).

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <sylva/datasets/victoria_park.hpp>

#include "fuzz_common.hpp"

namespace {

using namespace sylva::datasets;
using sylva_fuzz::require;

void check(const std::vector<VictoriaParkScan>& scans) {
  require(!scans.empty(), "no scans");
  for (std::size_t i = 0; i < scans.size(); ++i) {
    require(std::isfinite(scans[i].t_s) && (i == 0 || scans[i - 1].t_s < scans[i].t_s), "scan times do not increase");
    require(!scans[i].detections.empty(), "a scan without detections");
    for (const VictoriaParkDetection& d : scans[i].detections)
      require(d.range_m > 0.0 && std::isfinite(d.range_m) && d.bearing_rad >= 0.0 && d.bearing_rad <= sylva::kPi &&
                  d.diameter_m > 0.0 && std::isfinite(d.diameter_m),
              "a detection is out of bounds");
  }
}

void check(const std::vector<VictoriaParkOdometry>& odometry) {
  require(!odometry.empty(), "no odometry");
  for (std::size_t i = 0; i < odometry.size(); ++i) {
    const VictoriaParkOdometry& o = odometry[i];
    require(std::isfinite(o.t_s) && (i == 0 || odometry[i - 1].t_s <= o.t_s), "odometry times go back");
    require(std::isfinite(o.speed_mps) && std::abs(o.steering_rad) < 0.5 * sylva::kPi, "odometry is out of bounds");
  }
}

void check(const std::vector<VictoriaParkGps>& gps) {
  require(!gps.empty(), "no GPS fixes");
  for (std::size_t i = 0; i < gps.size(); ++i) {
    const VictoriaParkGps& g = gps[i];
    require(std::isfinite(g.t_s) && (i == 0 || gps[i - 1].t_s <= g.t_s), "GPS times go back");
    require(std::isfinite(g.x_m) && std::isfinite(g.y_m), "a GPS fix is not finite");
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace sylva_fuzz;
  static const Scratch dir("victoria_park");
  if (size < 1) return 0;
  const std::string_view text = asText(data + 1, size - 1);
  const std::string folder = dir.path().string();
  switch (data[0] % 4) {
    case 0: {
      const std::string path = dir.write("measurements.dat", text);
      return run([&] { check(loadVictoriaParkMeasurements(path)); });
    }
    case 1: {
      const std::string path = dir.write("odometry.txt", text);
      return run([&] { check(loadVictoriaParkOdometry(path)); });
    }
    case 2: {
      const std::string path = dir.write("gps.txt", text);
      return run([&] { check(loadVictoriaParkGps(path)); });
    }
    default:
      writeFiles(dir, {"measurements.dat", "odometry.txt", "gps.txt"}, split(text, 3));
      return run([&] {
        const VictoriaParkData d = (data[0] & 4) ? loadVictoriaPark(folder, HUGE_VAL) : loadVictoriaPark(folder);
        check(d.scans);
        check(d.odometry);
        check(d.gps);
      });
  }
}
