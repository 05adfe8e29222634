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
#include "sylva/datasets/victoria_park_gps.hpp"
#include "sylva/eval/rigid_2d.hpp"
#include "sylva/motion/ackermann_2d.hpp"

#include "arrays.hpp"
#include "models.hpp"

namespace sylva_py {

namespace {

namespace ds = sylva::datasets;

py::dict observations(const std::vector<ds::UtiasObservation>& obs) {
  py::dict d;
  d["t"] = arrayOf<double>(obs.size(), 0, [&](std::size_t i, int) { return obs[i].time_s; });
  d["subject"] = arrayOf<int>(obs.size(), 0, [&](std::size_t i, int) { return obs[i].subject; });
  d["barcode"] = arrayOf<int>(obs.size(), 0, [&](std::size_t i, int) { return obs[i].barcode; });
  d["z"] = arrayOf<double>(obs.size(), 2, [&](std::size_t i, int c) { return obs[i].z[c]; });
  return d;
}

/// A 1-D float64 array of the dict's entry `key`, with its length checked against n (< 0: any).
py::array_t<double> entry(const py::dict& d, const char* key, const std::string& what) {
  if (!d.contains(key))
    sylva::fail(sylva::ErrorCode::kInvalidArgument, what + ": no entry '" + key + "'");
  return asDoubleArray(d[key], what + "['" + key + "']");
}

/// The GPS fixes of a load_victoria_park() dict as the C++ loader's structs.
std::vector<ds::VictoriaParkGps> gpsFixes(const py::dict& data) {
  const py::dict gps = data["gps"];
  const auto t = entry(gps, "t", "data['gps']");
  const auto xy = entry(gps, "xy", "data['gps']");
  if (t.ndim() != 1 || xy.ndim() != 2 || xy.shape(0) != t.shape(0) || xy.shape(1) != 2)
    sylva::fail(sylva::ErrorCode::kInvalidArgument, "data['gps']: t (n,) and xy (n, 2) expected");
  std::vector<ds::VictoriaParkGps> fixes(static_cast<std::size_t>(t.shape(0)));
  for (py::ssize_t i = 0; i < t.shape(0); ++i)
    fixes[static_cast<std::size_t>(i)] = {t.at(i), 0, xy.at(i, 0), xy.at(i, 1)};
  return fixes;
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
            arrayOf<double>(odo.size(), 0, [&](std::size_t i, int) { return odo[i].t_s; });
        odometry["t_raw_ms"] = arrayOf<std::int64_t>(
            odo.size(), 0, [&](std::size_t i, int) { return odo[i].t_raw_ms; });
        odometry["speed"] =
            arrayOf<double>(odo.size(), 0, [&](std::size_t i, int) { return odo[i].speed_mps; });
        odometry["steering"] =
            arrayOf<double>(odo.size(), 0, [&](std::size_t i, int) { return odo[i].steering_rad; });
        out["odometry"] = odometry;
        const auto& gps = data.gps;
        py::dict fixes;
        fixes["t"] = arrayOf<double>(gps.size(), 0, [&](std::size_t i, int) { return gps[i].t_s; });
        fixes["t_raw_ms"] = arrayOf<std::int64_t>(
            gps.size(), 0, [&](std::size_t i, int) { return gps[i].t_raw_ms; });
        fixes["xy"] = arrayOf<double>(
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
        scans["t"] = arrayOf<double>(
            data.scans.size(), 0, [&](std::size_t i, int) { return data.scans[i].t_s; });
        scans["start"] = toArray(start);
        scans["range"] =
            arrayOf<double>(flat.size(), 0, [&](std::size_t i, int) { return flat[i]->range_m; });
        scans["bearing"] = arrayOf<double>(
            flat.size(), 0, [&](std::size_t i, int) { return flat[i]->bearing_rad; });
        scans["diameter"] = arrayOf<double>(
            flat.size(), 0, [&](std::size_t i, int) { return flat[i]->diameter_m; });
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
      "victoria_park_valid_gps",
      [](const py::dict& data, double wheelbase_m, double encoder_offset_m, double hold_s) {
        const py::dict odo = data["odometry"];
        const auto t = entry(odo, "t", "data['odometry']");
        const auto speed = entry(odo, "speed", "data['odometry']");
        const auto steering = entry(odo, "steering", "data['odometry']");
        if (t.ndim() != 1 || speed.shape(0) != t.shape(0) || steering.shape(0) != t.shape(0))
          sylva::fail(sylva::ErrorCode::kInvalidArgument,
                      "data['odometry']: t, speed and steering of one length expected");
        std::vector<ds::VictoriaParkOdometry> samples(static_cast<std::size_t>(t.shape(0)));
        for (py::ssize_t i = 0; i < t.shape(0); ++i)
          samples[static_cast<std::size_t>(i)] = {t.at(i), 0, speed.at(i), steering.at(i)};
        const auto valid = ds::validVictoriaParkGpsFixes(
            gpsFixes(data), samples, wheelbase_m, encoder_offset_m, hold_s);
        return arrayOf<bool>(valid.size(), 0, [&](std::size_t i, int) { return valid[i] != 0; });
      },
      py::arg("data"),
      py::arg("wheelbase_m") = 2.83,
      py::arg("encoder_offset_m") = 0.76,
      py::arg("hold_s") = ds::kVictoriaParkGpsHoldS,
      "Which GPS fixes of a load_victoria_park() dict are trusted: a fix whose step disagrees with "
      "the distance "
      "driven, and those within hold_s after it, are not (sylva/datasets/victoria_park_gps.hpp).");
  m.def(
      "victoria_park_gps_error",
      [](const py::handle& path_t,
         const py::handle& path_xy,
         const py::dict& data,
         const py::handle& valid_obj) {
        const auto t = asDoubleArray(path_t, "path_t");
        const auto xy = toRows<2>(path_xy, "path_xy");
        if (t.ndim() != 1 || static_cast<std::size_t>(t.shape(0)) != xy.size())
          sylva::fail(sylva::ErrorCode::kInvalidArgument,
                      "path_t: one time per row of path_xy expected");
        std::vector<ds::TimedPosition> path(xy.size());
        for (std::size_t i = 0; i < xy.size(); ++i)
          path[i] = {t.at(static_cast<py::ssize_t>(i)), xy[i]};
        const py::array_t<bool> valid_arr =
            py::array_t<bool, py::array::forcecast>::ensure(valid_obj);
        if (!valid_arr || valid_arr.ndim() != 1)
          sylva::fail(sylva::ErrorCode::kInvalidArgument, "valid: a 1-D boolean array expected");
        std::vector<char> valid(static_cast<std::size_t>(valid_arr.shape(0)));
        for (py::ssize_t i = 0; i < valid_arr.shape(0); ++i)
          valid[static_cast<std::size_t>(i)] = valid_arr.at(i) ? 1 : 0;
        const ds::VictoriaParkGpsError e = ds::victoriaParkGpsError(path, gpsFixes(data), valid);
        py::dict out;
        out["rmse_valid_m"] = e.rmse_valid_m;
        out["median_valid_m"] = e.median_valid_m;
        out["rmse_all_m"] = e.rmse_all_m;
        out["max_valid_m"] = e.max_valid_m;
        out["valid"] = e.valid;
        out["total"] = e.total;
        out["transform"] = e.transform;
        out["fix_t"] = toArray(e.fix_t_s);
        out["fix_error_m"] = toArray(e.fix_error_m);
        return out;
      },
      py::arg("path_t"),
      py::arg("path_xy"),
      py::arg("data"),
      py::arg("valid"),
      "Aligns an estimated laser path (times (n,), positions (n, 2) in the map frame) to the valid "
      "GPS fixes of a "
      "load_victoria_park() dict and measures the error of each fix: a dict of rmse_valid_m, "
      "median_valid_m, "
      "rmse_all_m, max_valid_m, valid, total, transform (Rigid2, map to GPS frame), fix_t and "
      "fix_error_m.");
  m.def(
      "ackermann_axle_motion",
      [](double speed_mps, double steering_rad, double wheelbase_m, double encoder_offset_m) {
        double v_c = 0.0, omega = 0.0;
        sylva::Ackermann2D(wheelbase_m, encoder_offset_m)
            .axleMotion(speed_mps, steering_rad, v_c, omega);
        return py::make_tuple(v_c, omega);
      },
      py::arg("speed_mps"),
      py::arg("steering_rad"),
      py::arg("wheelbase_m"),
      py::arg("encoder_offset_m") = 0.0,
      "The speed of the rear axle's centre and the turn rate (v_c, omega) for an encoder speed and "
      "a steering angle "
      "(sylva::Ackermann2D).");

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
            arrayOf<int>(lm.size(), 0, [&](std::size_t i, int) { return lm[i].subject; });
        landmarks["barcode"] =
            arrayOf<int>(lm.size(), 0, [&](std::size_t i, int) { return lm[i].barcode; });
        landmarks["position"] = arrayOf<double>(
            lm.size(), 2, [&](std::size_t i, int c) { return lm[i].position_m[c]; });
        landmarks["sigma"] =
            arrayOf<double>(lm.size(), 2, [&](std::size_t i, int c) { return lm[i].sigma_m[c]; });
        out["landmarks"] = landmarks;
        py::dict robot_dict;
        for (const auto& r : data.robots) {
          py::dict d;
          d["odometry"] = py::dict(
              py::arg("t") = arrayOf<double>(
                  r.odometry.size(), 0, [&](std::size_t i, int) { return r.odometry[i].time_s; }),
              py::arg("u") = arrayOf<double>(
                  r.odometry.size(), 2, [&](std::size_t i, int c) { return r.odometry[i].u[c]; }));
          d["landmark_observations"] = observations(r.landmark_observations);
          d["robot_observations"] = observations(r.robot_observations);
          d["groundtruth"] = py::dict(
              py::arg("t") =
                  arrayOf<double>(r.groundtruth.size(),
                                  0,
                                  [&](std::size_t i, int) { return r.groundtruth[i].time_s; }),
              py::arg("pose") = arrayOf<double>(r.groundtruth.size(), 3, [&](std::size_t i, int c) {
                return r.groundtruth[i].pose[c];
              }));
          d["unknown_barcode_rows"] =
              py::dict(py::arg("line") = arrayOf<std::int64_t>(
                           r.unknown_barcode_rows.size(),
                           0,
                           [&](std::size_t i, int) { return r.unknown_barcode_rows[i].line; }),
                       py::arg("barcode") =
                           arrayOf<int>(r.unknown_barcode_rows.size(), 0, [&](std::size_t i, int) {
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
