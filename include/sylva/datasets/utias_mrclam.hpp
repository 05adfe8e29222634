#pragma once
/// @file
/// `loadUtiasMrclam`: loader of one dataset folder of the UTIAS Multi-Robot Cooperative
/// Localization and Mapping (MRCLAM) collection:
///
///   K. Y. K. Leung, Y. Halpern, T. D. Barfoot, H. H. T. Liu, "The UTIAS Multi-Robot
///   Cooperative Localization and Mapping Dataset", International Journal of Robotics
///   Research 30(8):969-974, 2011.
///
/// A folder (e.g. MRCLAM_Dataset7) holds five robots (subjects 1-5) that observe 15
/// barcoded landmarks (subjects 6-20) and each other, with Vicon ground truth:
///
///   Barcodes.dat              subject  barcode
///   Landmark_Groundtruth.dat  subject  x[m]  y[m]  x_std[m]  y_std[m]
///   RobotN_Odometry.dat       time[s]  v[m/s]  omega[rad/s]    (velocity commands, ~67 Hz)
///   RobotN_Measurement.dat    time[s]  barcode  range[m]  bearing[rad]
///   RobotN_Groundtruth.dat    time[s]  x[m]  y[m]  theta[rad]  (Vicon)
///
/// The format is read by `readNumericTable` ('#' header lines, CRLF, blank and TAB
/// separators, trailing blanks). What this loader adds:
/// - Times are Unix seconds (1.2e9, millisecond resolution). Every time is returned relative
///   to `UtiasDataset::time_reference_s`: by default the earliest time of all files read,
///   rounded down to a whole second; `UtiasLoadOptions::time_reference_s` sets it instead.
/// - Column 2 of a measurement is a barcode, mapped to its subject through Barcodes.dat.
///   Observations of landmarks (subjects > 5) and of other robots (subjects 1-5) are kept
///   apart. A barcode that is not in Barcodes.dat (the real data have misreads, e.g. 34 and
///   52 in Dataset 7, robot 3) is a misdetection, not a malformed file: the row is kept out
///   of both lists and recorded in `UtiasRobotData::unknown_barcode_rows` (file line and
///   barcode), so the caller can count and report it.
/// - Times must not go backward within a file; equal consecutive times (several
///   measurements of one image, the odometry's duplicate stamps) are allowed.
/// - The files of one recording must cover one time span, within
///   `UtiasLoadOptions::max_span_gap_s` (30 s; Dataset 7's files differ by at most 8.6 s):
///   a robot's odometry and ground truth start and end together, its measurements lie within
///   them, and every robot's ground truth ends with the others'. A file cut short (a
///   truncated copy) is reported this way; a cut shorter than the tolerance is not seen.
///
/// Errors, all `sylva::Error(kMalformedData)` naming the file and, for a row, its line: a
/// missing file, a field that is not a finite number, a wrong number of columns, a whole
/// number with a fraction (subject, barcode), time going backward, a subject or barcode
/// listed twice in Barcodes.dat, a robot subject (1-5) missing from Barcodes.dat, a landmark
/// ground truth row of a subject that is not a landmark of Barcodes.dat, a range <= 0, a
/// bearing or heading outside [-pi, pi] (beyond the rounding of the files' last decimal),
/// an empty data file, files whose time spans disagree (see above), a time whose difference to
/// the time reference overflows (e.g. -1e308 and 1e308 in one file). A robot number outside 1-5
/// or a negative or NaN `max_span_gap_s` in the options is the caller's mistake:
/// kInvalidArgument.

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "sylva/core/angles.hpp"
#include "sylva/core/error.hpp"
#include "sylva/core/types.hpp"
#include "sylva/datasets/numeric_table.hpp"

namespace sylva::datasets {

/// Subjects 1..kUtiasRobotCount are the robots; higher subjects are landmarks.
inline constexpr int kUtiasRobotCount = 5;

struct UtiasLandmark {
  int subject = 0;
  int barcode = 0;
  Vec<2> position_m = Vec<2>::Zero();  ///< Vicon world frame
  Vec<2> sigma_m = Vec<2>::Zero();     ///< Vicon standard deviations of x and y
};

struct UtiasCommand {
  double time_s = 0.0;  ///< relative to UtiasDataset::time_reference_s
  Vec<2> u = Vec<2>::Zero();  ///< [v (m/s), omega (rad/s)] commanded
};

struct UtiasObservation {
  double time_s = 0.0;
  int subject = 0;  ///< from Barcodes.dat
  int barcode = 0;  ///< as read
  Vec<2> z = Vec<2>::Zero();  ///< [range (m), bearing (rad)] in the robot body frame
};

struct UtiasPose {
  double time_s = 0.0;
  Vec<3> pose = Vec<3>::Zero();  ///< [x, y, theta] Vicon world frame
};

/// A measurement row whose barcode is not in Barcodes.dat (kept out of the lists).
struct UtiasUnknownBarcode {
  long line = 0;
  int barcode = 0;
};

struct UtiasRobotData {
  int robot = 0;  ///< 1..5
  std::vector<UtiasCommand> odometry;
  std::vector<UtiasObservation> landmark_observations;  ///< subjects > kUtiasRobotCount
  std::vector<UtiasObservation> robot_observations;     ///< other robots' tags
  std::vector<UtiasUnknownBarcode> unknown_barcode_rows;  ///< misreads, see the file comment
  std::vector<UtiasPose> groundtruth;
  long measurement_rows = 0;  ///< all data rows of RobotN_Measurement.dat
};

struct UtiasDataset {
  std::string folder;
  double time_reference_s = 0.0;       ///< Unix time subtracted from every time
  std::map<int, int> barcode_of_subject;
  std::map<int, int> subject_of_barcode;
  std::vector<UtiasLandmark> landmarks;  ///< in file order
  std::vector<UtiasRobotData> robots;    ///< in the order asked for

  const UtiasRobotData& robot(int number) const {
    for (const auto& r : robots)
      if (r.robot == number) return r;
    fail(ErrorCode::kInvalidArgument, "UtiasDataset: robot " + std::to_string(number) + " was not loaded");
  }
};

struct UtiasLoadOptions {
  std::vector<int> robots = {1, 2, 3, 4, 5};
  /// Unix time subtracted from every time; NaN: the earliest time read, floored to 1 s.
  double time_reference_s = std::numeric_limits<double>::quiet_NaN();
  /// Largest disagreement (s) allowed between the time spans of a recording's files (see the
  /// file comment); infinity turns the check off.
  double max_span_gap_s = 30.0;
};

namespace detail {

inline NumericTableFormat utiasColumns(int n) {
  NumericTableFormat f;
  f.min_fields = n;
  f.max_fields = n;
  return f;
}

/// Reads a time-stamped table, checking that its times do not go back; returns the row count.
template <typename OnRow>
long readUtiasTimedTable(const std::string& path, int columns, const char* what, OnRow&& on_row) {
  double previous = -std::numeric_limits<double>::infinity();
  long rows = 0;
  readNumericTable(path, utiasColumns(columns), [&](const NumericRow& row) {
    requireNonDecreasing(row, previous, row[0], what);
    previous = row[0];
    ++rows;
    on_row(row);
  });
  if (rows == 0) failMalformed(path, 0, std::string("no ") + what + " rows in the file");
  return rows;
}

}  // namespace detail

/// Loads Barcodes.dat, Landmark_Groundtruth.dat and, for each robot in `options.robots`, its
/// odometry, measurements and ground truth from `folder`. See the file comment for the rules.
inline UtiasDataset loadUtiasMrclam(const std::string& folder, const UtiasLoadOptions& options = {}) {
  for (const int r : options.robots)
    if (r < 1 || r > kUtiasRobotCount)
      fail(ErrorCode::kInvalidArgument,
           "loadUtiasMrclam: robot " + std::to_string(r) + " does not exist (robots are 1-5)");
  if (!(options.max_span_gap_s >= 0.0))
    fail(ErrorCode::kInvalidArgument, "loadUtiasMrclam: max_span_gap_s must be >= 0 (infinity: no check)");
  UtiasDataset data;
  data.folder = folder;
  const std::string dir = folder.empty() || folder.back() == '/' ? folder : folder + "/";

  // Barcodes.dat: subject -> barcode, both unique.
  const std::string barcodes = dir + "Barcodes.dat";
  readNumericTable(barcodes, detail::utiasColumns(2), [&](const NumericRow& row) {
    const long subject = row.integer(0, "the subject");
    const long barcode = row.integer(1, "the barcode");
    if (subject < 1 || subject > 1000 || barcode < 0 || barcode > 100000)
      row.fail("subject " + row.text(0) + " or barcode " + row.text(1) + " out of range");
    if (!data.barcode_of_subject.emplace(int(subject), int(barcode)).second)
      row.fail("subject " + row.text(0) + " is listed twice");
    if (!data.subject_of_barcode.emplace(int(barcode), int(subject)).second)
      row.fail("barcode " + row.text(1) + " is listed twice");
  });
  for (int r = 1; r <= kUtiasRobotCount; ++r)
    if (!data.barcode_of_subject.count(r))
      failMalformed(barcodes, 0, "robot subject " + std::to_string(r) + " has no barcode");

  const std::string landmarks = dir + "Landmark_Groundtruth.dat";
  readNumericTable(landmarks, detail::utiasColumns(5), [&](const NumericRow& row) {
    const long subject = row.integer(0, "the subject");
    // (Range-checked before it is narrowed: 4294967302 is no subject 6.)
    const auto it = subject >= 1 && subject <= 1000 ? data.barcode_of_subject.find(int(subject))
                                                    : data.barcode_of_subject.end();
    if (subject <= kUtiasRobotCount || it == data.barcode_of_subject.end())
      row.fail("subject " + row.text(0) + " is not a landmark of Barcodes.dat");
    for (const auto& l : data.landmarks)
      if (l.subject == subject) row.fail("subject " + row.text(0) + " is listed twice");
    UtiasLandmark l;
    l.subject = int(subject);
    l.barcode = it->second;
    l.position_m = Vec<2>(row[1], row[2]);
    l.sigma_m = Vec<2>(row[3], row[4]);
    if (row[3] < 0.0 || row[4] < 0.0) row.fail("a standard deviation is negative");
    data.landmarks.push_back(l);
  });
  if (data.landmarks.empty()) failMalformed(landmarks, 0, "no landmarks in the file");

  // Raw Unix times first; the reference is subtracted once all files are read. A double
  // holds a Unix time to about 2e-7 s, far below the files' millisecond resolution.
  double earliest = std::numeric_limits<double>::infinity();
  const double gap = options.max_span_gap_s;
  std::vector<FileTimeSpan> groundtruth_spans;
  for (const int r : options.robots) {
    UtiasRobotData robot;
    robot.robot = r;
    const std::string prefix = dir + "Robot" + std::to_string(r) + "_";
    detail::readUtiasTimedTable(prefix + "Odometry.dat", 3, "odometry", [&](const NumericRow& row) {
      robot.odometry.push_back({row[0], Vec<2>(row[1], row[2])});
    });
    robot.measurement_rows =
        detail::readUtiasTimedTable(prefix + "Measurement.dat", 4, "measurement", [&](const NumericRow& row) {
          const long barcode = row.integer(1, "the barcode");
          if (barcode < 0 || barcode > 100000) row.fail("the barcode must be in [0, 100000], got " + row.text(1));
          if (!(row[2] > 0.0)) row.fail("the range must be > 0, got " + row.text(2));
          if (std::abs(row[3]) > kPi + 1e-3) row.fail("the bearing must be in [-pi, pi], got " + row.text(3));
          const auto it = data.subject_of_barcode.find(int(barcode));
          if (it == data.subject_of_barcode.end()) {
            robot.unknown_barcode_rows.push_back({row.line(), int(barcode)});
            return;
          }
          const UtiasObservation obs{row[0], it->second, int(barcode), Vec<2>(row[2], row[3])};
          (it->second <= kUtiasRobotCount ? robot.robot_observations : robot.landmark_observations).push_back(obs);
        });
    detail::readUtiasTimedTable(prefix + "Groundtruth.dat", 4, "ground truth", [&](const NumericRow& row) {
      // Written with 4 decimals: pi appears as 3.1416.
      if (std::abs(row[3]) > kPi + 1e-4) row.fail("the heading must be in [-pi, pi], got " + row.text(3));
      robot.groundtruth.push_back({row[0], Vec<3>(row[1], row[2], row[3])});
    });
    // One recording, one time span (see the file comment).
    const FileTimeSpan odometry{prefix + "Odometry.dat", robot.odometry.front().time_s, robot.odometry.back().time_s};
    const FileTimeSpan truth{prefix + "Groundtruth.dat", robot.groundtruth.front().time_s,
                                  robot.groundtruth.back().time_s};
    if (std::abs(odometry.first - truth.first) > gap || std::abs(odometry.last - truth.last) > gap)
      failTimeSpanMismatch(odometry, truth, gap);
    for (const auto* list : {&robot.landmark_observations, &robot.robot_observations}) {
      if (list->empty()) continue;
      const FileTimeSpan seen{prefix + "Measurement.dat", list->front().time_s, list->back().time_s};
      if (seen.first < odometry.first - gap || seen.last > odometry.last + gap)
        failTimeSpanMismatch(seen, odometry, gap);
    }
    if (!groundtruth_spans.empty() && std::abs(groundtruth_spans.front().last - truth.last) > gap)
      failTimeSpanMismatch(groundtruth_spans.front(), truth, gap);
    groundtruth_spans.push_back(truth);
    earliest = std::min({earliest, robot.odometry.front().time_s, robot.groundtruth.front().time_s});
    if (!robot.landmark_observations.empty())
      earliest = std::min(earliest, robot.landmark_observations.front().time_s);
    if (!robot.robot_observations.empty()) earliest = std::min(earliest, robot.robot_observations.front().time_s);
    data.robots.push_back(std::move(robot));
  }

  const double ref = std::isnan(options.time_reference_s)
                         ? (std::isfinite(earliest) ? std::floor(earliest) : 0.0)
                         : options.time_reference_s;
  if (!std::isfinite(ref)) fail(ErrorCode::kInvalidArgument, "loadUtiasMrclam: the time reference is not finite");
  data.time_reference_s = ref;
  for (auto& robot : data.robots) {
    const std::string prefix = dir + "Robot" + std::to_string(robot.robot) + "_";
    // Each time is finite, but its difference to the reference may not be (-1e308 and 1e308).
    const auto shift = [&](auto& list, const char* file) {
      for (auto& item : list) {
        const double raw = item.time_s;
        item.time_s -= ref;
        if (std::isfinite(item.time_s)) continue;
        std::ostringstream os;
        os.precision(15);
        os << "the time " << raw << " s less the time reference " << ref << " s overflows";
        failMalformed(prefix + file, 0, os.str());
      }
    };
    shift(robot.odometry, "Odometry.dat");
    shift(robot.landmark_observations, "Measurement.dat");
    shift(robot.robot_observations, "Measurement.dat");
    shift(robot.groundtruth, "Groundtruth.dat");
  }
  return data;
}

}  // namespace sylva::datasets
