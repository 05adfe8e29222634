// The consistency tools for Python: NEES and chi-square functions, and the Monte Carlo series
// of sylva/consistency/monte_carlo.hpp.

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "sylva/consistency/chi_square.hpp"
#include "sylva/consistency/monte_carlo.hpp"
#include "sylva/consistency/nees.hpp"

#include "arrays.hpp"
#include "models.hpp"

namespace sylva_py {

void bindConsistency(py::module_& m) {
  m.def(
      "nees",
      [](const py::handle& error, const py::handle& covariance) {
        const auto e = asDoubleArray(error, "error");
        if (e.ndim() != 1)
          sylva::fail(sylva::ErrorCode::kInvalidArgument,
                      "error: expected shape (n,), got " + shapeText(e));
        const auto P = asDoubleArray(covariance, "covariance");
        const auto n = e.shape(0);
        if (P.ndim() != 2 || P.shape(0) != n || P.shape(1) != n)
          sylva::fail(sylva::ErrorCode::kInvalidArgument,
                      "covariance: expected shape (" + std::to_string(n) + ", " +
                          std::to_string(n) + "), got " + shapeText(P));
        Eigen::VectorXd ev(n);
        Eigen::MatrixXd Pm(n, n);
        for (py::ssize_t i = 0; i < n; ++i) {
          ev[i] = e.at(i);
          for (py::ssize_t j = 0; j < n; ++j) Pm(i, j) = P.at(i, j);
        }
        return sylva::nees(ev, Pm);
      },
      py::arg("error"),
      py::arg("covariance"),
      "error^T covariance^-1 error (normalized estimation error squared).");
  m.def(
      "chi_square_quantile",
      [](double p, double dof) { return sylva::chiSquareQuantile(p, dof); },
      py::arg("p"),
      py::arg("dof"),
      "The p-quantile of the chi-square distribution with dof degrees of freedom.");
  m.def(
      "average_chi_square_bounds",
      [](int dof, int runs, double confidence) {
        return sylva::averageChiSquareBounds(dof, runs, confidence);
      },
      py::arg("dof"),
      py::arg("runs"),
      py::arg("confidence") = 0.95,
      "Two-sided bounds of the average of `runs` chi-square(dof) values (the NEES band of a Monte "
      "Carlo study).");

  py::class_<sylva::NeesSeries>(
      m,
      "NeesSeries",
      "A run-averaged chi-square statistic (NEES or NIS) per step of a Monte Carlo study "
      "(multisensor thesis eq. 2.44), with its chi-square band.")
      .def(py::init<int>(), py::arg("dof"))
      .def("add",
           &sylva::NeesSeries::add,
           py::arg("step"),
           py::arg("value"),
           "Records one run's value at step.")
      .def_property_readonly("dof", &sylva::NeesSeries::dof)
      .def_property_readonly("steps", &sylva::NeesSeries::steps)
      .def_property_readonly("runs", &sylva::NeesSeries::runs)
      .def(
          "averages",
          [](const sylva::NeesSeries& s) {
            const auto a = s.averages();
            return py::array_t<double>(static_cast<py::ssize_t>(a.size()), a.data());
          },
          "The run-averaged value at each step (NaN where nothing was recorded).")
      .def("mean", &sylva::NeesSeries::mean, "The mean over steps of the run-averaged value.")
      .def("bounds",
           &sylva::NeesSeries::bounds,
           py::arg("confidence") = 0.95,
           "The two-sided band of one step's run average.")
      .def("fraction_inside",
           &sylva::NeesSeries::fractionInside,
           py::arg("confidence") = 0.95,
           "The share of steps whose run average lies inside bounds(confidence).");
}

}  // namespace sylva_py
