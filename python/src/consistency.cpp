// The consistency tools for Python: NEES and chi-square functions, and the Monte Carlo series
// of sylva/consistency/monte_carlo.hpp.

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "sylva/consistency/chi_square.hpp"
#include "sylva/consistency/monte_carlo.hpp"
#include "sylva/consistency/nees.hpp"
#include "sylva/consistency/paired_tests.hpp"

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
          [](const sylva::NeesSeries& s) { return toArray(s.averages()); },
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

  using Ensemble = sylva::NeesEnsemble;
  py::class_<Ensemble::Summary>(m, "NeesSummary", "What NeesEnsemble.summary() reports.")
      .def_readonly("mean", &Ensemble::Summary::mean, "mean over steps of the ensemble average")
      .def_readonly("median_run",
                    &Ensemble::Summary::median_run,
                    "median over runs of each run's time average")
      .def_readonly("lower", &Ensemble::Summary::lower)
      .def_readonly("upper", &Ensemble::Summary::upper)
      .def_readonly("fraction_inside", &Ensemble::Summary::fraction_inside)
      .def_readonly("runs", &Ensemble::Summary::runs)
      .def_readonly("dof", &Ensemble::Summary::dof);
  py::class_<Ensemble>(
      m,
      "NeesEnsemble",
      "NEES (or NIS) of each run of a Monte Carlo ensemble at each step; a diverged run may record "
      "inf, which the median over runs tolerates.")
      .def(py::init<int>(), py::arg("dof"))
      .def("add", &Ensemble::add, py::arg("run"), py::arg("step"), py::arg("value"))
      .def_property_readonly("dof", &Ensemble::dof)
      .def("step_averages", [](const Ensemble& e) { return toArray(e.stepAverages()); })
      .def("run_averages", [](const Ensemble& e) { return toArray(e.runAverages()); })
      .def("summary", &Ensemble::summary, py::arg("confidence") = 0.95);

  m.def("mcnemar_exact",
        &sylva::mcnemarExact,
        py::arg("a_only"),
        py::arg("b_only"),
        "Two-sided exact McNemar p-value of paired successes: a_only pairs where only A succeeded, "
        "b_only where only B "
        "did.");
  py::class_<sylva::SignedRankResult>(m, "SignedRankResult", "The result of wilcoxon_signed_rank.")
      .def_readonly("n", &sylva::SignedRankResult::n)
      .def_readonly("w_plus", &sylva::SignedRankResult::w_plus)
      .def_readonly("p_value", &sylva::SignedRankResult::p_value)
      .def_readonly("exact", &sylva::SignedRankResult::exact)
      .def_readonly("positive", &sylva::SignedRankResult::positive)
      .def_readonly("negative", &sylva::SignedRankResult::negative);
  m.def("wilcoxon_signed_rank",
        &sylva::wilcoxonSignedRank,
        py::arg("differences"),
        "Two-sided Wilcoxon signed-rank test of paired differences (zeros dropped).");
  m.def("wilson_interval",
        &sylva::wilsonInterval,
        py::arg("successes"),
        py::arg("trials"),
        py::arg("confidence") = 0.95,
        "Wilson score interval of a binomial proportion.");
}

}  // namespace sylva_py
