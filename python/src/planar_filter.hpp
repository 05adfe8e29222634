#pragma once
// The planar filters, `Ekf<Robot, Point2>` for one robot each, bound with numpy in and out,
// and the SLAM layer's step for them (`slam::FrontEnd` with `RangeBearing`). One template,
// instantiated by one translation unit per robot (planar_*.cpp), so that the units compile
// side by side.

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "sylva/consistency/nees.hpp"
#include "sylva/filter/ekf.hpp"
#include "sylva/landmarks/point2.hpp"
#include "sylva/measurements/range_bearing.hpp"
#include "sylva/noise/gaussian.hpp"
#include "sylva/slam/front_end.hpp"
#include "sylva/slam/reach.hpp"

#include "arrays.hpp"
#include "models.hpp"
#include "python_model.hpp"

namespace sylva_py {

/// A noise covariance of size M from an array of shape (M, M); checked by sylva (symmetric,
/// positive definite).
template <int M>
sylva::Gaussian<M> toNoise(const py::handle& obj, const std::string& what) {
  return sylva::Gaussian<M>::covariance(toMat<M, M>(obj, what));
}

/// Calls f with the C++ measurement model behind a Python model object.
template <typename F>
py::object withMeasurement(const py::handle& model, F&& f) {
  if (py::isinstance<sylva::RangeBearing>(model))
    return f(model.cast<const sylva::RangeBearing&>());
  if (py::isinstance<MeasurementSpec>(model)) {
    const auto& spec = model.cast<const MeasurementSpec&>();
    switch (spec.dim) {
      case 1:
        return f(PythonMeasurement<1>{spec});
      case 2:
        return f(PythonMeasurement<2>{spec});
      case 3:
        return f(PythonMeasurement<3>{spec});
    }
  }
  sylva::fail(sylva::ErrorCode::kInvalidArgument,
              "expected a measurement model (sylva.RangeBearing or sylva.PythonModel), got a " +
                  std::string(py::str(py::type::of(model).attr("__name__"))));
}

/// Calls f with the C++ inverse model behind a Python inverse-model object.
template <typename F>
void withInverse(const py::handle& model, F&& f) {
  if (py::isinstance<sylva::InverseRangeBearing>(model))
    return f(model.cast<const sylva::InverseRangeBearing&>());
  if (py::isinstance<InverseSpec>(model)) {
    const auto& spec = model.cast<const InverseSpec&>();
    switch (spec.dim) {
      case 1:
        return f(PythonInverse<1>{spec});
      case 2:
        return f(PythonInverse<2>{spec});
      case 3:
        return f(PythonInverse<3>{spec});
    }
  }
  sylva::fail(
      sylva::ErrorCode::kInvalidArgument,
      "expected an inverse model (sylva.InverseRangeBearing or sylva.PythonInverseModel), got a " +
          std::string(py::str(py::type::of(model).attr("__name__"))));
}

inline sylva::Fusion toFusion(const std::string& fusion) {
  if (fusion == "batched") return sylva::Fusion::kBatched;
  if (fusion == "sequential") return sylva::Fusion::kSequential;
  sylva::fail(sylva::ErrorCode::kInvalidArgument,
              "fusion must be 'batched' or 'sequential', got '" + fusion + "'");
}

/// The SLAM step for one planar filter type with a range-bearing sensor.
template <typename Filter>
class PlanarFrontEnd {
 public:
  using Engine = sylva::slam::FrontEnd<Filter, sylva::RangeBearing, sylva::InverseRangeBearing>;

  PlanarFrontEnd(py::object filter,
                 const sylva::RangeBearing& sensor,
                 const sylva::slam::FrontEndOptions& options,
                 const std::optional<sylva::slam::RangeBearingReach>& reach)
      : filter_(std::move(filter)),
        engine_(sensor,
                sylva::InverseRangeBearing(sensor.mount()),
                options,
                reach ? typename Engine::Candidates(
                            sylva::slam::candidatesInReach<sylva::Point2>(sensor, *reach))
                      : typename Engine::Candidates()) {}

  /// The readings of one time: Z (n, 2), noise (2, 2) for all or (n, 2, 2), ids (n,) or None.
  sylva::slam::StepReport update(const py::handle& Z,
                                 const py::handle& noise,
                                 double time_s,
                                 const py::handle& ids) {
    readings_ = toReadings(Z, noise, ids);
    return engine_.update(filter(), readings_, time_s);
  }

  sylva::slam::StepReport step(const py::handle& u,
                               double dt,
                               const py::handle& process_noise,
                               const py::handle& Z,
                               const py::handle& noise,
                               double time_s,
                               const py::handle& ids) {
    const auto control = toVec<Filter::kControlDim>(u, "u");
    const auto q = toNoise<Filter::kNoiseDim>(process_noise, "process_noise");
    readings_ = toReadings(Z, noise, ids);
    return engine_.step(filter(), control, dt, q, readings_, time_s);
  }

  int sightings(sylva::Id id) const { return engine_.sightings(id); }
  int tentativeTracks() const { return engine_.tentativeTracks(); }
  const sylva::slam::FrontEndOptions& options() const { return engine_.options(); }
  const py::object& ekf() const { return filter_; }

 private:
  Filter& filter() { return filter_.cast<Filter&>(); }

  std::vector<typename Engine::ReadingType> toReadings(const py::handle& Z,
                                                       const py::handle& noise,
                                                       const py::handle& ids_obj) const {
    const auto z = toRows<2>(Z, "Z");
    std::vector<sylva::Gaussian<2>> noises;
    const auto n_arr = asDoubleArray(noise, "noise");
    if (n_arr.ndim() == 3) {
      if (n_arr.shape(0) != static_cast<py::ssize_t>(z.size()) || n_arr.shape(1) != 2 ||
          n_arr.shape(2) != 2)
        sylva::fail(sylva::ErrorCode::kInvalidArgument,
                    "noise: expected shape (2, 2) or (" + std::to_string(z.size()) +
                        ", 2, 2), got " + shapeText(n_arr));
      for (py::ssize_t i = 0; i < n_arr.shape(0); ++i) {
        sylva::Mat<2, 2> c;
        for (int r = 0; r < 2; ++r)
          for (int k = 0; k < 2; ++k) c(r, k) = n_arr.at(i, r, k);
        noises.push_back(sylva::Gaussian<2>::covariance(c));
      }
    } else {
      noises.assign(z.size(), toNoise<2>(noise, "noise"));
    }
    std::vector<sylva::Id> ids;
    if (!ids_obj.is_none()) {
      ids = toIds(ids_obj, "ids");
      if (ids.size() != z.size())
        sylva::fail(sylva::ErrorCode::kInvalidArgument,
                    "ids: " + std::to_string(ids.size()) + " ids for " + std::to_string(z.size()) +
                        " readings");
    }
    std::vector<typename Engine::ReadingType> out;
    out.reserve(z.size());
    for (std::size_t i = 0; i < z.size(); ++i)
      out.emplace_back(z[i],
                       noises[i],
                       std::nullopt,
                       ids.empty() ? std::nullopt : std::optional<sylva::Id>(ids[i]));
    return out;
  }

  py::object filter_;
  Engine engine_;
  std::vector<typename Engine::ReadingType> readings_;
};

/// Binds `Ekf<Robot, Point2>` as `name`, with `make_robot(kwargs)` building the robot, and
/// its front end as `name + "FrontEnd"`.
template <typename Robot, typename MakeRobot>
void bindPlanarFilter(py::module_& m,
                      const char* name,
                      const char* robot_doc,
                      MakeRobot make_robot) {
  using Filter = sylva::Ekf<Robot, sylva::Point2>;
  constexpr int kControl = Filter::kControlDim;
  constexpr int kNoise = Filter::kNoiseDim;
  const std::string cls_name = name;

  py::class_<Filter> cls(m, name, robot_doc);
  cls.def(
      py::init([make_robot](const py::handle& x0, const py::handle& P0, const py::kwargs& kwargs) {
        const auto x = toVec<3>(x0, "x0");
        const auto P = toMat<3, 3>(P0, "P0");
        return Filter(x, P, make_robot(kwargs));
      }),
      py::arg("x0"),
      py::arg("P0"),
      "A filter whose state is the robot pose x0 = [x, y, theta] with covariance P0 (3, 3), and no "
      "landmarks yet. Robot parameters, if the robot has any, are keyword arguments.");

  cls.def(
      "predict",
      [](Filter& f, const py::handle& u, double dt, const py::handle& noise) {
        const auto control = toVec<kControl>(u, "u");
        const auto q = toNoise<kNoise>(noise, "noise");
        f.predict(control, dt, q);
      },
      py::arg("u"),
      py::arg("dt"),
      py::arg("noise"),
      "Propagates the robot with control u over dt seconds; noise is the control noise "
      "covariance.");

  cls.def(
      "add",
      [](Filter& f,
         sylva::Id id,
         const py::handle& inverse,
         const py::handle& z,
         const py::handle& noise) {
        withInverse(inverse, [&](const auto& model) {
          constexpr int M = std::decay_t<decltype(model)>::kMeasurementDim;
          const auto zz = toVec<M>(z, "z");
          const auto r = toNoise<M>(noise, "noise");
          f.add(id, model, zz, r);
        });
      },
      py::arg("id"),
      py::arg("inverse_model"),
      py::arg("z"),
      py::arg("noise"),
      "Adds landmark id from its first measurement z through the inverse model.");

  cls.def(
      "update",
      [](Filter& f,
         const py::handle& model,
         sylva::Id id,
         const py::handle& z,
         const py::handle& noise) {
        return withMeasurement(model, [&](const auto& mdl) {
          constexpr int M = std::decay_t<decltype(mdl)>::kDim;
          const auto zz = toVec<M>(z, "z");
          const auto r = toNoise<M>(noise, "noise");
          const sylva::Innovation<M> innovation = f.update(mdl, id, zz, r);
          return py::cast(
              InnovationResult{toArray(innovation.nu), toArray(innovation.S), innovation.nis()});
        });
      },
      py::arg("model"),
      py::arg("id"),
      py::arg("z"),
      py::arg("noise"),
      "Fuses one measurement z of landmark id; returns the innovation at the prior.");

  cls.def(
      "update_many",
      [](Filter& f,
         const py::handle& model,
         const py::handle& ids_obj,
         const py::handle& Z,
         const py::handle& noise,
         const std::string& fusion) {
        withMeasurement(model, [&](const auto& mdl) {
          using Model = std::decay_t<decltype(mdl)>;
          constexpr int M = Model::kDim;
          const auto ids = toIds(ids_obj, "ids");
          const auto z = toRows<M>(Z, "Z");
          if (ids.size() != z.size())
            sylva::fail(sylva::ErrorCode::kInvalidArgument,
                        "ids: " + std::to_string(ids.size()) + " ids for " +
                            std::to_string(z.size()) + " measurements");
          const auto r = toNoise<M>(noise, "noise");
          std::vector<sylva::Observation<Model>> observations;
          observations.reserve(ids.size());
          for (std::size_t i = 0; i < ids.size(); ++i) observations.push_back({ids[i], z[i], r});
          f.update(mdl, observations, toFusion(fusion));
          return py::none();
        });
      },
      py::arg("model"),
      py::arg("ids"),
      py::arg("Z"),
      py::arg("noise"),
      py::arg("fusion") = "batched",
      "Fuses the measurements Z (n, m) of landmarks ids in one batched update (or one at a time).");

  cls.def_property(
      "linearization",
      &Filter::linearizationPoint,
      [](Filter& f, sylva::LinearizationPoint point) {
        if (point == sylva::LinearizationPoint::kIdeal)
          sylva::fail(sylva::ErrorCode::kInvalidArgument,
                      "the ideal linearization is not available from Python");
        f.setLinearizationPoint(point);
      },
      "Where the Jacobians are taken (sylva.Linearization; docs/filter.md). Set it before the "
      "first landmark.");
  cls.def("remove", &Filter::remove, py::arg("id"), "Removes landmark id from the state.");
  cls.def(
      "copy", [](const Filter& f) { return Filter(f); }, "An independent copy of the filter.");
  cls.def("__copy__", [](const Filter& f) { return Filter(f); });
  cls.def(
      "__deepcopy__", [](const Filter& f, const py::dict&) { return Filter(f); }, py::arg("memo"));
  cls.def("__len__", &Filter::landmarkCount);
  cls.def("__contains__", &Filter::contains, py::arg("id"));
  cls.def_property_readonly("dim", &Filter::dim, "Dimension of the state: 3 + 2 per landmark.");
  cls.def_property_readonly(
      "ids",
      [](const Filter& f) {
        std::vector<sylva::Id> ids;
        for (const auto& s : f.slots()) ids.push_back(s.id);
        return ids;
      },
      "Landmark ids in the order of their blocks in the state.");
  cls.def_property_readonly(
      "robot_mean",
      [](const Filter& f) { return toArray(f.robotMean()); },
      "The robot's mean [x, y, theta].");
  cls.def_property_readonly(
      "robot_covariance",
      [](const Filter& f) { return toArray(f.robotCovariance()); },
      "The robot's covariance (3, 3).");
  cls.def_property_readonly(
      "mean",
      [](const Filter& f) { return toArray(Eigen::VectorXd(f.mean())); },
      "The whole state mean (dim,): the pose, then each landmark in the order of ids.");
  cls.def_property_readonly(
      "covariance",
      [](const Filter& f) { return toArray(Eigen::MatrixXd(f.covariance())); },
      "The whole state covariance (dim, dim).");
  cls.def(
      "landmark_mean",
      [](const Filter& f, sylva::Id id) {
        return toArray(f.template landmarkMean<sylva::Point2>(id));
      },
      py::arg("id"),
      "The mean [x, y] of landmark id.");
  cls.def(
      "landmark_covariance",
      [](const Filter& f, sylva::Id id) {
        return toArray(f.template landmarkCovariance<sylva::Point2>(id));
      },
      py::arg("id"),
      "The covariance (2, 2) of landmark id.");
  cls.def(
      "robot_landmark_covariance",
      [](const Filter& f, sylva::Id id) {
        return toArray(f.template robotLandmarkCovariance<sylva::Point2>(id));
      },
      py::arg("id"),
      "The cross-covariance (3, 2) of the robot and landmark id.");
  cls.def(
      "robot_error",
      [](const Filter& f, const py::handle& x_true) {
        return toArray(Robot::difference(toVec<3>(x_true, "x_true"), f.robotMean()));
      },
      py::arg("x_true"),
      "The estimate's error against the true pose, [dx, dy, dtheta] with dtheta wrapped.");
  cls.def(
      "robot_nees",
      [](const Filter& f, const py::handle& x_true) {
        const sylva::Vec<3> error = Robot::difference(toVec<3>(x_true, "x_true"), f.robotMean());
        return sylva::nees(error, f.robotCovariance());
      },
      py::arg("x_true"),
      "The normalized estimation error squared of the pose against the true pose.");
  cls.def("__repr__", [cls_name](const Filter& f) {
    const auto x = f.robotMean();
    return "<sylva." + cls_name + " pose=(" + std::to_string(x[0]) + ", " + std::to_string(x[1]) +
           ", " + std::to_string(x[2]) + "), " + std::to_string(f.landmarkCount()) + " landmarks>";
  });

  using FE = PlanarFrontEnd<Filter>;
  const std::string fe_name = cls_name + "FrontEnd";
  py::class_<FE>(m,
                 fe_name.c_str(),
                 "The SLAM step of sylva.slam.FrontEnd for this filter type (see sylva.FrontEnd).")
      .def("update",
           &FE::update,
           py::arg("Z"),
           py::arg("noise"),
           py::arg("time"),
           py::arg("ids") = py::none(),
           "Associates, fuses and maps the readings Z (n, 2) of one time; returns the StepReport.")
      .def("step",
           &FE::step,
           py::arg("u"),
           py::arg("dt"),
           py::arg("process_noise"),
           py::arg("Z"),
           py::arg("noise"),
           py::arg("time"),
           py::arg("ids") = py::none(),
           "Predicts with u over dt, then update().")
      .def("sightings",
           &FE::sightings,
           py::arg("id"),
           "Readings landmark id has taken through this front end.")
      .def_property_readonly("tentative_tracks", &FE::tentativeTracks)
      .def_property_readonly("options", &FE::options)
      .def_property_readonly("ekf", &FE::ekf);
  cls.def(
      "_front_end",
      [](py::object self,
         const sylva::RangeBearing& sensor,
         const sylva::slam::FrontEndOptions& options,
         const std::optional<sylva::slam::RangeBearingReach>& reach) {
        self.cast<Filter&>();  // the type is checked by the binding
        return FE(self, sensor, options, reach);
      },
      py::arg("sensor"),
      py::arg("options"),
      py::arg("reach") = py::none());
}

}  // namespace sylva_py
