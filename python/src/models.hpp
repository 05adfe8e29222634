#pragma once
// Types shared by the binding units: the Python-side model objects and what an update returns.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include "python_model.hpp"

namespace sylva_py {

/// `sylva.PythonModel`: a measurement model written in Python.
struct MeasurementSpec : PythonModelSpec {};
/// `sylva.PythonInverseModel`: the landmark from one measurement, written in Python.
struct InverseSpec : PythonModelSpec {};

/// What `update` returns: the innovation nu, its covariance S and the NIS, at the prior.
struct InnovationResult {
  py::array_t<double> nu;
  py::array_t<double> S;
  double nis;
};

/// Each binding unit's entry point (module.cpp calls them in this order).
void bindCommon(py::module_& m);
void bindUnicycle(py::module_& m);
void bindOdometry(py::module_& m);
void bindAckermann(py::module_& m);
void bindSim(py::module_& m);
void bindConsistency(py::module_& m);
void bindDatasets(py::module_& m);
void bindEval(py::module_& m);
void bindMonocular(py::module_& m);

}  // namespace sylva_py
