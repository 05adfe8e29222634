// What every filter of the module shares: sylva.Error, the enums and options of the SLAM
// layer, the step report and the measurement models.

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <string>

#include "sylva/core/error.hpp"
#include "sylva/filter/linearization_point.hpp"
#include "sylva/measurements/range_bearing.hpp"
#include "sylva/slam/front_end.hpp"
#include "sylva/slam/reach.hpp"

#include "arrays.hpp"
#include "models.hpp"

namespace sylva_py {

namespace {

/// sylva.Error, created in bindCommon; held for the module's lifetime.
PyObject* error_type = nullptr;

PythonModelSpec makeSpec(
    int dim, py::object function, py::object jacobians, std::vector<int> angles, const char* what) {
  if (dim < 1 || dim > 3)
    sylva::fail(sylva::ErrorCode::kInvalidArgument,
                std::string(what) + ": dim must be 1, 2 or 3, got " + std::to_string(dim));
  if (!PyCallable_Check(function.ptr()))
    sylva::fail(sylva::ErrorCode::kInvalidArgument,
                std::string(what) + ": the model function is not callable");
  if (!jacobians.is_none() && !PyCallable_Check(jacobians.ptr()))
    sylva::fail(sylva::ErrorCode::kInvalidArgument,
                std::string(what) + ": jacobians is neither None nor callable");
  for (const int a : angles)
    if (a < 0 || a >= dim)
      sylva::fail(
          sylva::ErrorCode::kInvalidArgument,
          std::string(what) + ": angle index " + std::to_string(a) + " is outside [0, dim)");
  PythonModelSpec spec;
  spec.dim = dim;
  spec.function = std::move(function);
  spec.jacobians = std::move(jacobians);
  spec.angles = std::move(angles);
  spec.name = what;
  return spec;
}

std::optional<sylva::Vec<2>> optionalMount(const py::handle& mount) {
  if (mount.is_none()) return std::nullopt;
  return toVec<2>(mount, "mount");
}

}  // namespace

void bindCommon(py::module_& m) {
  // ---------------------------------------------------------------- errors
  py::enum_<sylva::ErrorCode>(m, "ErrorCode", "What a sylva.Error is about (sylva::ErrorCode).")
      .value("NON_FINITE", sylva::ErrorCode::kNonFinite)
      .value("UNKNOWN_ID", sylva::ErrorCode::kUnknownId)
      .value("DUPLICATE_ID", sylva::ErrorCode::kDuplicateId)
      .value("WRONG_LANDMARK_TYPE", sylva::ErrorCode::kWrongLandmarkType)
      .value("NOT_POSITIVE_DEFINITE", sylva::ErrorCode::kNotPositiveDefinite)
      .value("NEGATIVE_TIME_STEP", sylva::ErrorCode::kNegativeTimeStep)
      .value("DEGENERATE_GEOMETRY", sylva::ErrorCode::kDegenerateGeometry)
      .value("INVALID_ARGUMENT", sylva::ErrorCode::kInvalidArgument)
      .value("MALFORMED_DATA", sylva::ErrorCode::kMalformedData)
      .value("OUT_OF_DOMAIN", sylva::ErrorCode::kOutOfDomain);

  error_type = PyErr_NewExceptionWithDoc(
      "sylva._sylva.Error",
      "Raised by every sylva operation on bad input. `code` is a sylva.ErrorCode, and str(e) names "
      "the problem. "
      "The filter it was raised from is unchanged. A subclass of ValueError.",
      PyExc_ValueError,
      nullptr);
  m.add_object("Error", py::handle(error_type));
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const sylva::Error& e) {
      py::object exc = py::reinterpret_borrow<py::object>(error_type)(py::str(e.what()));
      exc.attr("code") = py::cast(e.code());
      PyErr_SetObject(error_type, exc.ptr());
    }
  });

  // ---------------------------------------------------------------- models
  py::class_<sylva::RangeBearing>(
      m,
      "RangeBearing",
      "Range and bearing [r m, b rad] to a Point2 landmark (multisensor thesis eq. 2.16-2.17), "
      "from a sensor at `mount` [x, y] in the robot frame (default: the robot's origin).")
      .def(py::init([](const py::handle& mount) {
             const auto mt = optionalMount(mount);
             return mt ? sylva::RangeBearing(*mt) : sylva::RangeBearing();
           }),
           py::arg("mount") = py::none())
      .def_property_readonly("mount",
                             [](const sylva::RangeBearing& s) { return toArray(s.mount()); })
      .def_property_readonly_static("dim", [](const py::object&) { return 2; });
  py::class_<sylva::InverseRangeBearing>(
      m, "InverseRangeBearing", "A Point2 landmark from one range-bearing measurement (eq. 2.33).")
      .def(py::init([](const py::handle& mount) {
             const auto mt = optionalMount(mount);
             return mt ? sylva::InverseRangeBearing(*mt) : sylva::InverseRangeBearing();
           }),
           py::arg("mount") = py::none())
      .def_property_readonly(
          "mount", [](const sylva::InverseRangeBearing& s) { return toArray(s.mount()); });

  py::class_<MeasurementSpec>(m,
                              "PythonModel",
                              "A measurement model written in Python: z = h(robot, landmark) for a "
                              "planar pose [x, y, theta] and a Point2 "
                              "landmark [x, y], dim = 1, 2 or 3. jacobians(robot, landmark) "
                              "returns (J_z_x (dim, 3), J_z_l (dim, 2)); "
                              "without it the filter differentiates h numerically (central "
                              "differences). Components listed in angles are "
                              "wrapped to (-pi, pi] in the innovation.")
      .def(py::init([](int dim, py::object h, py::object jacobians, std::vector<int> angles) {
             return MeasurementSpec{makeSpec(
                 dim, std::move(h), std::move(jacobians), std::move(angles), "PythonModel")};
           }),
           py::arg("dim"),
           py::arg("h"),
           py::arg("jacobians") = py::none(),
           py::arg("angles") = std::vector<int>{})
      .def_property_readonly("dim", [](const MeasurementSpec& s) { return s.dim; })
      .def_property_readonly("h", [](const MeasurementSpec& s) { return s.function; })
      .def_property_readonly("jacobians", [](const MeasurementSpec& s) { return s.jacobians; })
      .def_property_readonly("angles", [](const MeasurementSpec& s) { return s.angles; });
  py::class_<InverseSpec>(
      m,
      "PythonInverseModel",
      "A landmark [x, y] from one measurement, written in Python: g(robot, z). jacobians(robot, z) "
      "returns "
      "(J_l_x (2, 3), J_l_z (2, dim)); without it the filter differentiates g numerically.")
      .def(py::init([](int dim, py::object g, py::object jacobians) {
             return InverseSpec{
                 makeSpec(dim, std::move(g), std::move(jacobians), {}, "PythonInverseModel")};
           }),
           py::arg("dim"),
           py::arg("g"),
           py::arg("jacobians") = py::none())
      .def_property_readonly("dim", [](const InverseSpec& s) { return s.dim; });

  py::enum_<sylva::LinearizationPoint>(
      m, "Linearization", "Where a filter takes its Jacobians (docs/filter.md).")
      .value("CURRENT_ESTIMATE", sylva::LinearizationPoint::kCurrentEstimate)
      .value("FIRST_ESTIMATES", sylva::LinearizationPoint::kFirstEstimates)
      .value("IDEAL", sylva::LinearizationPoint::kIdeal)
      .value("ITERATED", sylva::LinearizationPoint::kIterated)
      .value("INVARIANT", sylva::LinearizationPoint::kInvariant)
      .value("OBSERVABILITY_CONSTRAINED", sylva::LinearizationPoint::kObservabilityConstrained);

  py::class_<InnovationResult>(m, "Innovation", "The innovation of an update, at the prior.")
      .def_readonly("nu", &InnovationResult::nu, "z - h(x) (angles wrapped)")
      .def_readonly("S", &InnovationResult::S, "its covariance H P H^T + R")
      .def_readonly("nis", &InnovationResult::nis, "nu^T S^-1 nu");

  // ---------------------------------------------------------------- the SLAM layer's options and
  // report
  namespace slam = sylva::slam;
  py::enum_<slam::Association>(m, "Association", "How readings find their landmarks.")
      .value("KNOWN_IDS", slam::Association::kKnownIds)
      .value("NEAREST_NEIGHBOR", slam::Association::kNearestNeighbor)
      .value("JCBB", slam::Association::kJcbb);
  py::enum_<slam::NewLandmarks>(m, "NewLandmarks", "When an unpaired reading becomes a landmark.")
      .value("IMMEDIATE", slam::NewLandmarks::kImmediate)
      .value("TENTATIVE", slam::NewLandmarks::kTentative);
  py::enum_<sylva::Fusion>(
      m, "Fusion", "One stacked update of all paired readings, or one update per reading.")
      .value("BATCHED", sylva::Fusion::kBatched)
      .value("SEQUENTIAL", sylva::Fusion::kSequential);
  py::enum_<slam::Outcome>(m, "Outcome", "What happened to one reading in a step.")
      .value("PAIRED", slam::Outcome::kPaired)
      .value("ADDED", slam::Outcome::kAdded)
      .value("TENTATIVE", slam::Outcome::kTentative)
      .value("AMBIGUOUS", slam::Outcome::kAmbiguous)
      .value("GATED_OUT", slam::Outcome::kGatedOut)
      .value("THINNED", slam::Outcome::kThinned)
      .value("REPEATED", slam::Outcome::kRepeated)
      .value("REFUSED", slam::Outcome::kRefused);

  py::class_<slam::TentativeTracks>(m,
                                    "TentativeTracks",
                                    "NewLandmarks.TENTATIVE: a track fed in confirm_sightings "
                                    "steps, its readings within radius_m of each other, "
                                    "becomes a landmark; one not fed for timeout_s is dropped.")
      .def(py::init<>())
      .def_readwrite("confirm_sightings", &slam::TentativeTracks::confirm_sightings)
      .def_readwrite("radius_m", &slam::TentativeTracks::radius_m)
      .def_readwrite("timeout_s", &slam::TentativeTracks::timeout_s);
  py::class_<slam::UnconfirmedRemoval>(m,
                                       "UnconfirmedRemoval",
                                       "A landmark the front end started is removed when, within_s "
                                       "after it started, it has taken fewer than "
                                       "min_sightings readings (0: never).")
      .def(py::init<>())
      .def_readwrite("min_sightings", &slam::UnconfirmedRemoval::min_sightings)
      .def_readwrite("within_s", &slam::UnconfirmedRemoval::within_s);
  py::class_<slam::FrontEndOptions>(
      m, "FrontEndOptions", "Options of the SLAM step (sylva::slam::FrontEndOptions).")
      .def(py::init<>())
      .def_readwrite("association", &slam::FrontEndOptions::association)
      .def_readwrite("gate_probability", &slam::FrontEndOptions::gate_probability)
      .def_readwrite("new_landmark_probability", &slam::FrontEndOptions::new_landmark_probability)
      .def_readwrite("known_id_gate_probability", &slam::FrontEndOptions::known_id_gate_probability)
      .def_readwrite("report_nis", &slam::FrontEndOptions::report_nis)
      .def_readwrite("min_fusion_interval_s", &slam::FrontEndOptions::min_fusion_interval_s)
      .def_readwrite("fusion", &slam::FrontEndOptions::fusion)
      .def_readwrite("fallback_to_sequential", &slam::FrontEndOptions::fallback_to_sequential)
      .def_readwrite("new_landmarks", &slam::FrontEndOptions::new_landmarks)
      .def_readwrite("tentative", &slam::FrontEndOptions::tentative)
      .def_readwrite("unconfirmed", &slam::FrontEndOptions::unconfirmed)
      .def_readwrite("first_new_id", &slam::FrontEndOptions::first_new_id);
  py::class_<slam::RangeBearingReach>(
      m,
      "RangeBearingReach",
      "The part of the plane a range-bearing sensor sees: candidates of association.")
      .def(py::init([](double max_range_m, double half_fov_rad, double min_range_m) {
             const slam::RangeBearingReach reach{max_range_m, half_fov_rad, min_range_m};
             slam::checkReach(reach);
             return reach;
           }),
           py::arg("max_range_m") = std::numeric_limits<double>::infinity(),
           py::arg("half_fov_rad") = sylva::kPi,
           py::arg("min_range_m") = 0.0)
      .def_readonly("max_range_m", &slam::RangeBearingReach::max_range_m)
      .def_readonly("half_fov_rad", &slam::RangeBearingReach::half_fov_rad)
      .def_readonly("min_range_m", &slam::RangeBearingReach::min_range_m);

  py::class_<slam::ReadingResult>(m, "ReadingResult", "What happened to one reading.")
      .def_readonly("outcome", &slam::ReadingResult::outcome)
      .def_readonly(
          "landmark", &slam::ReadingResult::landmark, "the landmark it was paired with or started")
      .def_readonly("nis", &slam::ReadingResult::nis)
      .def_readonly("error", &slam::ReadingResult::error, "REFUSED: the sylva.ErrorCode")
      .def_readonly("why", &slam::ReadingResult::why, "REFUSED: the message")
      .def("__repr__", [](const slam::ReadingResult& r) {
        std::string s = std::string("<ReadingResult ") + slam::toString(r.outcome);
        if (r.landmark) s += " landmark=" + std::to_string(*r.landmark);
        if (!r.why.empty()) s += " why='" + r.why + "'";
        return s + ">";
      });
  py::class_<slam::StepReport>(m, "StepReport", "What one SLAM step did with each reading.")
      .def_readonly("readings",
                    &slam::StepReport::readings,
                    "one ReadingResult per reading, in the order given")
      .def_readonly("removed", &slam::StepReport::removed, "landmarks removed as unconfirmed")
      .def_readonly("candidates", &slam::StepReport::candidates)
      .def_readonly("tentative_tracks", &slam::StepReport::tentative_tracks)
      .def_readonly("batch_refused", &slam::StepReport::batch_refused)
      .def_property_readonly("seconds",
                             [](const slam::StepReport& r) {
                               py::dict d;
                               d["association"] = r.seconds.association;
                               d["fusion"] = r.seconds.fusion;
                               d["mapping"] = r.seconds.mapping;
                               d["total"] = r.seconds.total;
                               return d;
                             })
      .def("count", &slam::StepReport::count, py::arg("outcome"))
      .def_property_readonly("outcomes",
                             [](const slam::StepReport& r) {
                               std::vector<slam::Outcome> out;
                               for (const auto& x : r.readings) out.push_back(x.outcome);
                               return out;
                             })
      .def_property_readonly("landmarks", [](const slam::StepReport& r) {
        std::vector<std::optional<sylva::Id>> out;
        for (const auto& x : r.readings) out.push_back(x.landmark);
        return out;
      });
}

}  // namespace sylva_py
