// The real-data loaders for Python: Victoria Park and UTIAS MRCLAM as dicts of numpy arrays.
// The files are parsed by sylva's C++ loaders, so a malformed or truncated file raises
// sylva.Error (MALFORMED_DATA) naming the file and line.

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "sylva/datasets/utias_mrclam.hpp"
#include "sylva/datasets/victoria_park.hpp"

#include "arrays.hpp"
#include "models.hpp"

namespace sylva_py {

namespace {

namespace ds = sylva::datasets;

/// A numpy array of n values (or n x cols), filled by get(i, column).
template <typename T, typename Get>
py::array_t<T> column(std::size_t n, int cols, Get&& get) {
  const auto rows = static_cast<py::ssize_t>(n);
  py::array_t<T> out =
      cols == 0 ? py::array_t<T>(rows) : py::array_t<T>({rows, static_cast<py::ssize_t>(cols)});
  if (cols == 0) {
    for (py::ssize_t i = 0; i < rows; ++i) out.mutable_at(i) = get(static_cast<std::size_t>(i), 0);
  } else {
    for (py::ssize_t i = 0; i < rows; ++i)
      for (int c = 0; c < cols; ++c) out.mutable_at(i, c) = get(static_cast<std::size_t>(i), c);
  }
  return out;
}

py::dict observations(const std::vector<ds::UtiasObservation>& obs) {
  py::dict d;
  d["t"] = column<double>(obs.size(), 0, [&](std::size_t i, int) { return obs[i].time_s; });
  d["subject"] = column<int>(obs.size(), 0, [&](std::size_t i, int) { return obs[i].subject; });
  d["barcode"] = column<int>(obs.size(), 0, [&](std::size_t i, int) { return obs[i].barcode; });
  d["z"] = column<double>(obs.size(), 2, [&](std::size_t i, int c) { return obs[i].z[c]; });
  return d;
}

}  // namespace

void bindDatasets(py::module_& m) {
  m.def(
      "load_victoria_park",
      [](const std::string& folder, double max_span_gap_s) {
        const ds::VictoriaParkData data = ds::loadVictoriaPark(folder, max_span_gap_s);
        py::dict out;
        const auto& odo = data.odometry;
        py::dict odometry;
        odometry["t"] =
            column<double>(odo.size(), 0, [&](std::size_t i, int) { return odo[i].t_s; });
        odometry["t_raw_ms"] = column<std::int64_t>(
            odo.size(), 0, [&](std::size_t i, int) { return odo[i].t_raw_ms; });
        odometry["speed"] =
            column<double>(odo.size(), 0, [&](std::size_t i, int) { return odo[i].speed_mps; });
        odometry["steering"] =
            column<double>(odo.size(), 0, [&](std::size_t i, int) { return odo[i].steering_rad; });
        out["odometry"] = odometry;
        const auto& gps = data.gps;
        py::dict fixes;
        fixes["t"] = column<double>(gps.size(), 0, [&](std::size_t i, int) { return gps[i].t_s; });
        fixes["t_raw_ms"] = column<std::int64_t>(
            gps.size(), 0, [&](std::size_t i, int) { return gps[i].t_raw_ms; });
        fixes["xy"] = column<double>(
            gps.size(), 2, [&](std::size_t i, int c) { return c == 0 ? gps[i].x_m : gps[i].y_m; });
        out["gps"] = fixes;
        // Scans as one flat list of detections: scan k holds detections start[k] .. start[k + 1].
        std::vector<const ds::VictoriaParkDetection*> flat;
        std::vector<std::int64_t> start{0};
        for (const auto& scan : data.scans) {
          for (const auto& d : scan.detections) flat.push_back(&d);
          start.push_back(static_cast<std::int64_t>(flat.size()));
        }
        py::dict scans;
        scans["t"] = column<double>(
            data.scans.size(), 0, [&](std::size_t i, int) { return data.scans[i].t_s; });
        scans["start"] =
            py::array_t<std::int64_t>(static_cast<py::ssize_t>(start.size()), start.data());
        scans["range"] =
            column<double>(flat.size(), 0, [&](std::size_t i, int) { return flat[i]->range_m; });
        scans["bearing"] = column<double>(
            flat.size(), 0, [&](std::size_t i, int) { return flat[i]->bearing_rad; });
        scans["diameter"] =
            column<double>(flat.size(), 0, [&](std::size_t i, int) { return flat[i]->diameter_m; });
        out["scans"] = scans;
        return out;
      },
      py::arg("folder"),
      py::arg("max_span_gap_s") = 30.0,
      "Reads Victoria Park (measurements.dat, odometry.txt, gps.txt) from folder. Returns a dict "
      "of dicts of arrays: "
      "odometry {t, t_raw_ms, speed (encoder, m/s), steering (rad)}, gps {t, t_raw_ms, xy (n, 2)} "
      "and scans {t (m,), "
      "start (m + 1,), range, bearing (laser convention: pi/2 ahead), diameter}, where scan k "
      "holds the detections "
      "start[k]:start[k + 1].");

  m.def(
      "load_utias_mrclam",
      [](const std::string& folder,
         const std::vector<int>& robots,
         double time_reference_s,
         double max_span_gap_s) {
        ds::UtiasLoadOptions options;
        options.robots = robots;
        options.time_reference_s = time_reference_s;
        options.max_span_gap_s = max_span_gap_s;
        const ds::UtiasDataset data = ds::loadUtiasMrclam(folder, options);
        py::dict out;
        out["time_reference_s"] = data.time_reference_s;
        const auto& lm = data.landmarks;
        py::dict landmarks;
        landmarks["subject"] =
            column<int>(lm.size(), 0, [&](std::size_t i, int) { return lm[i].subject; });
        landmarks["barcode"] =
            column<int>(lm.size(), 0, [&](std::size_t i, int) { return lm[i].barcode; });
        landmarks["position"] =
            column<double>(lm.size(), 2, [&](std::size_t i, int c) { return lm[i].position_m[c]; });
        landmarks["sigma"] =
            column<double>(lm.size(), 2, [&](std::size_t i, int c) { return lm[i].sigma_m[c]; });
        out["landmarks"] = landmarks;
        py::dict robot_dict;
        for (const auto& r : data.robots) {
          py::dict d;
          d["odometry"] = py::dict(
              py::arg("t") = column<double>(
                  r.odometry.size(), 0, [&](std::size_t i, int) { return r.odometry[i].time_s; }),
              py::arg("u") = column<double>(
                  r.odometry.size(), 2, [&](std::size_t i, int c) { return r.odometry[i].u[c]; }));
          d["landmark_observations"] = observations(r.landmark_observations);
          d["robot_observations"] = observations(r.robot_observations);
          d["groundtruth"] = py::dict(
              py::arg("t") =
                  column<double>(r.groundtruth.size(),
                                 0,
                                 [&](std::size_t i, int) { return r.groundtruth[i].time_s; }),
              py::arg("pose") = column<double>(r.groundtruth.size(), 3, [&](std::size_t i, int c) {
                return r.groundtruth[i].pose[c];
              }));
          d["unknown_barcode_rows"] =
              py::dict(py::arg("line") = column<std::int64_t>(
                           r.unknown_barcode_rows.size(),
                           0,
                           [&](std::size_t i, int) { return r.unknown_barcode_rows[i].line; }),
                       py::arg("barcode") =
                           column<int>(r.unknown_barcode_rows.size(), 0, [&](std::size_t i, int) {
                             return r.unknown_barcode_rows[i].barcode;
                           }));
          d["measurement_rows"] = r.measurement_rows;
          robot_dict[py::int_(r.robot)] = d;
        }
        out["robots"] = robot_dict;
        return out;
      },
      py::arg("folder"),
      py::arg("robots") = std::vector<int>{1, 2, 3, 4, 5},
      py::arg("time_reference_s") = std::numeric_limits<double>::quiet_NaN(),
      py::arg("max_span_gap_s") = 30.0,
      "Reads one UTIAS MRCLAM dataset folder. Returns a dict: time_reference_s (Unix time "
      "subtracted from every "
      "time; NaN asks for the earliest time read, floored to 1 s), landmarks {subject, barcode, "
      "position (n, 2), sigma "
      "(n, 2)} and robots {number: {odometry {t, u (n, 2) [v, omega]}, landmark_observations and "
      "robot_observations "
      "{t, subject, barcode, z (n, 2) [range, bearing]}, groundtruth {t, pose (n, 3)}, "
      "unknown_barcode_rows {line, "
      "barcode}, measurement_rows}}.");
}

}  // namespace sylva_py
