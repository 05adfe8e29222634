// The extension module sylva._sylva; the package sylva (python/sylva/__init__.py) re-exports it.
#include <pybind11/pybind11.h>

#include <Eigen/Core>

#include "models.hpp"

namespace py = pybind11;

PYBIND11_MODULE(_sylva, m) {
  m.doc() = "sylva's C++ filters, models and tools (see docs/python.md).";
  py::dict build;
#if defined(__clang__)
  build["compiler"] = "clang++ " __clang_version__;
#elif defined(__GNUC__)
  build["compiler"] = "g++ " __VERSION__;
#else
  build["compiler"] = "unknown";
#endif
#ifdef __OPTIMIZE__
  build["optimized"] = true;
#else
  build["optimized"] = false;
#endif
  build["simd"] = Eigen::SimdInstructionSetsInUse();
  m.attr("build_info") = build;
  sylva_py::bindCommon(m);
  sylva_py::bindUnicycle(m);
  sylva_py::bindOdometry(m);
  sylva_py::bindAckermann(m);
  sylva_py::bindSim(m);
  sylva_py::bindConsistency(m);
  sylva_py::bindDatasets(m);
  sylva_py::bindEval(m);
  sylva_py::bindMonocular(m);
}
