// Fuzz target: sylva::datasets::loadUtiasMrclam, the UTIAS MRCLAM folder loader.
//
// Input: one option byte, then the folder's files separated by '@', in this order:
//   Barcodes.dat @ Landmark_Groundtruth.dat @ then for each robot asked for, in increasing
//   order: RobotN_Odometry.dat @ RobotN_Measurement.dat @ RobotN_Groundtruth.dat
// A file without a part in the input is missing from the folder.
// Option byte: bits 0-4 ask for robots 1-5; bit 5 sets the time reference to 0 s (else the
// loader picks the earliest time); bit 6 keeps the default time-span check between the files
// (max_span_gap_s), clear it turns the check off (infinity); bit 7 asks for robot 0 too, the
// caller's mistake (kInvalidArgument). So 'A' is robot 1, 'C' robots 1-2, '_' all five, 'a'
// robot 1 with the time reference, '!' robot 1 with the reference and without the check.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <set>
#include <string>
#include <vector>

#include <sylva/datasets/utias_mrclam.hpp>

#include "fuzz_common.hpp"

namespace {

using namespace sylva::datasets;
using sylva_fuzz::require;

template <typename List>
void requireTimesInOrder(const List& list) {
  for (std::size_t i = 0; i < list.size(); ++i) {
    require(std::isfinite(list[i].time_s), "a loaded time is not finite");
    require(i == 0 || list[i - 1].time_s <= list[i].time_s, "loaded times go back");
  }
}

void requireObservations(const UtiasDataset& d, const std::vector<UtiasObservation>& list, bool robots) {
  requireTimesInOrder(list);
  for (const UtiasObservation& o : list) {
    const auto it = d.subject_of_barcode.find(o.barcode);
    require(it != d.subject_of_barcode.end() && it->second == o.subject, "an observation's subject is not its barcode's");
    require((o.subject <= kUtiasRobotCount) == robots, "an observation is in the wrong list");
    require(o.z.x() > 0.0 && std::isfinite(o.z.x()) && std::abs(o.z.y()) <= sylva::kPi + 1e-3,
            "an observation's range or bearing is out of bounds");
  }
}

/// What the loader promises about a folder it accepted (see utias_mrclam.hpp).
void check(const UtiasDataset& d, const UtiasLoadOptions& options) {
  require(std::isfinite(d.time_reference_s), "the time reference is not finite");
  require(d.barcode_of_subject.size() == d.subject_of_barcode.size(), "the barcode maps differ in size");
  for (const auto& [subject, barcode] : d.barcode_of_subject)
    require(d.subject_of_barcode.at(barcode) == subject, "the barcode maps disagree");
  for (int r = 1; r <= kUtiasRobotCount; ++r) require(d.barcode_of_subject.count(r) == 1, "a robot has no barcode");
  require(!d.landmarks.empty(), "no landmarks");
  std::set<int> subjects;
  for (const UtiasLandmark& l : d.landmarks) {
    require(subjects.insert(l.subject).second, "a landmark is listed twice");
    require(l.subject > kUtiasRobotCount && d.barcode_of_subject.at(l.subject) == l.barcode, "a landmark's barcode is wrong");
    require(l.position_m.allFinite() && l.sigma_m.allFinite() && l.sigma_m.minCoeff() >= 0.0, "a landmark is not finite");
  }
  require(d.robots.size() == options.robots.size(), "a robot is missing");
  for (std::size_t i = 0; i < d.robots.size(); ++i) {
    const UtiasRobotData& r = d.robots[i];
    require(r.robot == options.robots[i], "the robots are out of order");
    require(!r.odometry.empty() && !r.groundtruth.empty(), "an empty table was accepted");
    requireTimesInOrder(r.odometry);
    requireTimesInOrder(r.groundtruth);
    for (const UtiasCommand& c : r.odometry) require(c.u.allFinite(), "a command is not finite");
    for (const UtiasPose& p : r.groundtruth)
      require(p.pose.allFinite() && std::abs(p.pose.z()) <= sylva::kPi + 1e-4, "a pose is out of bounds");
    requireObservations(d, r.landmark_observations, false);
    requireObservations(d, r.robot_observations, true);
    for (const UtiasUnknownBarcode& u : r.unknown_barcode_rows)
      require(u.barcode >= 0 && d.subject_of_barcode.count(u.barcode) == 0, "an unknown barcode is known");
    require(r.measurement_rows == static_cast<long>(r.landmark_observations.size() + r.robot_observations.size() +
                                                    r.unknown_barcode_rows.size()),
            "measurement rows were lost");
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace sylva_fuzz;
  static const Scratch dir("utias_mrclam");
  if (size < 1) return 0;
  UtiasLoadOptions options;
  options.robots.clear();
  if (data[0] & 0x80) options.robots.push_back(0);
  std::vector<std::string> files = {"Barcodes.dat", "Landmark_Groundtruth.dat"};
  for (int r = 1; r <= kUtiasRobotCount; ++r) {
    if (!(data[0] & (1u << (r - 1)))) continue;
    options.robots.push_back(r);
    for (const char* table : {"Odometry", "Measurement", "Groundtruth"})
      files.push_back("Robot" + std::to_string(r) + "_" + table + ".dat");
  }
  if (data[0] & 0x20) options.time_reference_s = 0.0;
  if (!(data[0] & 0x40)) options.max_span_gap_s = HUGE_VAL;
  writeFiles(dir, files, split(asText(data + 1, size - 1), files.size()));
  return run([&] { check(loadUtiasMrclam(dir.path().string(), options), options); });
}
