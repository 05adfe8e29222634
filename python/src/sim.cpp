// The simulators for Python: sylva's random number generator (the same streams as the C++
// examples, so that a seed gives the same run in both) and the planar loop world of
// range_bearing_slam. Results come out as numpy arrays.

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "sylva/motion/unicycle_2d.hpp"
#include "sylva/sim/planar_loop_world.hpp"
#include "sylva/sim/random.hpp"

#include "arrays.hpp"
#include "models.hpp"

namespace sylva_py {

namespace {

namespace sim = sylva::sim;

}  // namespace

void bindSim(py::module_& m) {
  py::class_<sim::Rng>(
      m,
      "Rng",
      "sylva's random number generator (std::mt19937_64 with its own uniform and normal draws, "
      "sylva/sim/random.hpp): the same seed gives the same numbers as in C++.")
      .def(py::init<std::uint64_t>(), py::arg("seed"))
      .def_property_readonly("seed", &sim::Rng::seed)
      .def("uniform01", &sim::Rng::uniform01, "Uniform in [0, 1) with 53 random bits.")
      .def("uniform", &sim::Rng::uniform, py::arg("lo"), py::arg("hi"), "Uniform in [lo, hi).")
      .def(
          "normal",
          [](sim::Rng& rng, double mean, double sigma) { return rng.normal(mean, sigma); },
          py::arg("mean") = 0.0,
          py::arg("sigma") = 1.0,
          "A normal sample N(mean, sigma^2).");
  m.def("derive_seed",
        &sim::deriveSeed,
        py::arg("seed"),
        py::arg("stream"),
        "The seed of stream `stream` derived from `seed` (run i of a study draws from "
        "derive_seed(seed, 1 + i)).");

  m.def(
      "unicycle_2d",
      [](const py::handle& x, const py::handle& u, double dt) {
        return toArray(sylva::Unicycle2D()(toVec<3>(x, "x"), toVec<2>(u, "u"), dt));
      },
      py::arg("x"),
      py::arg("u"),
      py::arg("dt"),
      "The unicycle motion (multisensor thesis eq. 2.12-2.14): pose x moved by control [v, omega] "
      "over dt.");

  py::class_<sim::LoopTrajectory2DOptions>(
      m, "LoopTrajectoryOptions", "The loop the robot drives and its odometry noise.")
      .def(py::init<>())
      .def_readwrite("perimeter_m", &sim::LoopTrajectory2DOptions::perimeter_m)
      .def_readwrite("aspect", &sim::LoopTrajectory2DOptions::aspect)
      .def_readwrite("corner_radius_m", &sim::LoopTrajectory2DOptions::corner_radius_m)
      .def_readwrite("speed_mps", &sim::LoopTrajectory2DOptions::speed_mps)
      .def_readwrite("dt_s", &sim::LoopTrajectory2DOptions::dt_s)
      .def_readwrite("sigma_v_mps", &sim::LoopTrajectory2DOptions::sigma_v_mps)
      .def_readwrite("sigma_omega_radps", &sim::LoopTrajectory2DOptions::sigma_omega_radps);
  py::class_<sim::LandmarkField2DOptions>(
      m, "LandmarkFieldOptions", "Point landmarks in a band along the loop.")
      .def(py::init<>())
      .def_readwrite("count", &sim::LandmarkField2DOptions::count)
      .def_readwrite("band_min_m", &sim::LandmarkField2DOptions::band_min_m)
      .def_readwrite("band_max_m", &sim::LandmarkField2DOptions::band_max_m)
      .def_readwrite("min_separation_m", &sim::LandmarkField2DOptions::min_separation_m)
      .def_readwrite("max_attempts_per_landmark",
                     &sim::LandmarkField2DOptions::max_attempts_per_landmark);
  py::class_<sim::RangeBearingSensor2DOptions>(
      m, "RangeBearingSensorOptions", "A forward-looking range-bearing sensor and its noise.")
      .def(py::init<>())
      .def_readwrite("max_range_m", &sim::RangeBearingSensor2DOptions::max_range_m)
      .def_readwrite("min_range_m", &sim::RangeBearingSensor2DOptions::min_range_m)
      .def_readwrite("fov_half_angle_rad", &sim::RangeBearingSensor2DOptions::fov_half_angle_rad)
      .def_readwrite("sigma_range_m", &sim::RangeBearingSensor2DOptions::sigma_range_m)
      .def_readwrite("sigma_bearing_rad", &sim::RangeBearingSensor2DOptions::sigma_bearing_rad);
  py::class_<sim::PlanarLoopWorldOptions>(
      m, "PlanarLoopWorldOptions", "The world of range_bearing_slam (defaults as there).")
      .def(py::init<>())
      .def_readwrite("trajectory", &sim::PlanarLoopWorldOptions::trajectory)
      .def_readwrite("landmarks", &sim::PlanarLoopWorldOptions::landmarks)
      .def_readwrite("sensor", &sim::PlanarLoopWorldOptions::sensor);

  py::class_<sim::PlanarLoopWorld>(
      m,
      "PlanarLoopWorld",
      "A robot on a rounded-rectangle loop with noisy odometry, point landmarks along it and a "
      "range-bearing sensor "
      "(sylva::sim::PlanarLoopWorld). The landmarks are drawn from derive_seed(seed, 0).")
      .def(py::init([](const sim::PlanarLoopWorldOptions& options, std::uint64_t seed) {
             return sim::makePlanarLoopWorld(options, seed);
           }),
           py::arg("options"),
           py::arg("seed"))
      .def_property_readonly(
          "landmarks",
          [](const sim::PlanarLoopWorld& w) {
            return arrayOf<double>(w.landmarks.size(), 2, [&](std::size_t i, int c) {
              return w.landmarks[i].position[c];
            });
          },
          "True landmark positions (n, 2).")
      .def_property_readonly(
          "landmark_ids",
          [](const sim::PlanarLoopWorld& w) {
            return arrayOf<sylva::Id>(
                w.landmarks.size(), 0, [&](std::size_t i, int) { return w.landmarks[i].id; });
          },
          "Their ids (n,).")
      .def_property_readonly("dt", [](const sim::PlanarLoopWorld& w) { return w.trajectory.dt(); })
      .def_property_readonly(
          "speed",
          [](const sim::PlanarLoopWorld& w) { return w.trajectory.speed(); },
          "The forward speed used (the loop's length is a whole number of steps).")
      .def_property_readonly(
          "steps_per_lap", [](const sim::PlanarLoopWorld& w) { return w.trajectory.stepsPerLap(); })
      .def_property_readonly(
          "start_pose",
          [](const sim::PlanarLoopWorld& w) { return toArray(w.trajectory.startPose()); })
      .def(
          "simulate",
          [](const sim::PlanarLoopWorld& w, int steps, sim::Rng& rng) {
            const auto truth = w.trajectory.simulate(steps, rng);
            const auto n = truth.size();
            py::dict out;
            out["time"] =
                arrayOf<double>(n, 0, [&](std::size_t k, int) { return truth[k].time_s; });
            out["true_pose"] =
                arrayOf<double>(n, 3, [&](std::size_t k, int c) { return truth[k].true_pose[c]; });
            out["true_control"] = arrayOf<double>(
                n, 2, [&](std::size_t k, int c) { return truth[k].true_control[c]; });
            out["odometry"] =
                arrayOf<double>(n, 2, [&](std::size_t k, int c) { return truth[k].odometry[c]; });
            return out;
          },
          py::arg("steps"),
          py::arg("rng"),
          "Drives `steps` steps from the start pose: a dict of arrays time (steps,), true_pose "
          "(steps, 3), "
          "true_control (steps, 2) and odometry (steps, 2), the control plus noise drawn from rng.")
      .def(
          "observe",
          [](const sim::PlanarLoopWorld& w, const py::handle& pose, sim::Rng& rng) {
            const auto readings = w.sensor.observe(toVec<3>(pose, "pose"), w.landmarks, rng);
            const auto n = readings.size();
            return py::make_tuple(
                arrayOf<double>(n, 2, [&](std::size_t i, int c) { return readings[i].z[c]; }),
                arrayOf<sylva::Id>(n, 0, [&](std::size_t i, int) { return readings[i].id; }));
          },
          py::arg("pose"),
          py::arg("rng"),
          "Noisy readings of the landmarks the sensor sees from the true pose: (Z (k, 2), ids "
          "(k,)).");
}

}  // namespace sylva_py
