// Fuzz target: the leg_tracker recording loader, sylva::datasets::loadLegTrackerRecording
// (a "key value" parameter file and a CSV of scans).
//
// Input: rec_scan_params.txt @ rec_scans.csv (a file without a part is missing).

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

#include <sylva/datasets/leg_tracker.hpp>

#include "fuzz_common.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace sylva_fuzz;
  static const Scratch dir("leg_tracker");
  writeFiles(dir, {"rec_scan_params.txt", "rec_scans.csv"}, split(asText(data, size), 2));
  return run([&] {
    const sylva::datasets::LegTrackerRecording scans = sylva::datasets::loadLegTrackerRecording(dir.path().string(), "rec");
    const sylva::LaserScanGeometry& g = scans.geometry;
    require(g.beams >= 2 && g.beams <= 100000, "the beam count is out of bounds");
    require(std::isfinite(g.angle_min_rad) && g.angle_increment_rad > 0.0 && g.min_range_m >= 0.0 &&
                g.max_range_m > g.min_range_m && std::isfinite(g.max_range_m),
            "the scan geometry is out of bounds");
    require(!scans.stamps_s.empty() && scans.stamps_s.size() == scans.ranges.size(), "scans and stamps differ in number");
    for (std::size_t i = 0; i < scans.stamps_s.size(); ++i) {
      require(std::isfinite(scans.stamps_s[i]) && (i == 0 || scans.stamps_s[i - 1] < scans.stamps_s[i]),
              "scan stamps do not increase");
      require(scans.ranges[i].size() == static_cast<std::size_t>(g.beams), "a scan has the wrong number of ranges");
    }
  });
}
