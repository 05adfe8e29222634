// The extension module sylva._sylva; the package sylva (python/sylva/__init__.py) re-exports it.
#include <pybind11/pybind11.h>

#include "models.hpp"

PYBIND11_MODULE(_sylva, m) {
  m.doc() = "sylva's C++ filters, models and tools (see docs/python.md).";
  sylva_py::bindCommon(m);
  sylva_py::bindUnicycle(m);
  sylva_py::bindOdometry(m);
  sylva_py::bindAckermann(m);
  sylva_py::bindSim(m);
  sylva_py::bindConsistency(m);
  sylva_py::bindDatasets(m);
  sylva_py::bindEval(m);
}
