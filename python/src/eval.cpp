// Evaluation for Python: similarity and rigid alignment, and the tree-width thesis' error
// metrics (sylva/eval).

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <vector>

#include "sylva/eval/map_errors.hpp"
#include "sylva/eval/rigid_2d.hpp"
#include "sylva/eval/similarity.hpp"

#include "arrays.hpp"
#include "models.hpp"

namespace sylva_py {

namespace {

namespace ev = sylva::eval;

/// Applies `f` (Vec<N> -> Vec<N>) to each row of an (n, N) array, or to one (N,) point.
template <int N, typename F>
py::array_t<double> applyToPoints(const py::handle& points, F&& f) {
  const auto a = asDoubleArray(points, "points");
  if (a.ndim() == 1) return toArray(f(toVec<N>(a, "points")));
  std::vector<sylva::Vec<N>> rows = toRows<N>(a, "points");
  for (auto& p : rows) p = f(p);
  return arrayOf<double>(rows.size(), N, [&](std::size_t i, int c) { return rows[i][c]; });
}

}  // namespace

void bindEval(py::module_& m) {
  py::class_<ev::Similarity3>(m, "Similarity3", "p -> scale * rotation * p + translation.")
      .def_readonly("scale", &ev::Similarity3::scale)
      .def_property_readonly("rotation",
                             [](const ev::Similarity3& T) { return toArray(T.rotation); })
      .def_property_readonly("translation",
                             [](const ev::Similarity3& T) { return toArray(T.translation); })
      .def(
          "__call__",
          [](const ev::Similarity3& T, const py::handle& points) {
            return applyToPoints<3>(points, [&](const sylva::Vec<3>& p) { return T(p); });
          },
          py::arg("points"),
          "The transform of one point (3,) or of each row of (n, 3).");
  m.def(
      "align_similarity",
      [](const py::handle& estimated, const py::handle& truth) {
        return ev::alignSimilarity(toRows<3>(estimated, "estimated"), toRows<3>(truth, "truth"));
      },
      py::arg("estimated"),
      py::arg("truth"),
      "The similarity minimizing sum |T(estimated_i) - truth_i|^2 over (n, 3) point arrays "
      "(tree-width thesis eq. 4.4, "
      "Umeyama's method).");

  py::class_<ev::Rigid2>(m, "Rigid2", "p -> rotation * p + translation in the plane.")
      .def_property_readonly("rotation", [](const ev::Rigid2& T) { return toArray(T.rotation); })
      .def_property_readonly("translation",
                             [](const ev::Rigid2& T) { return toArray(T.translation); })
      .def_property_readonly("angle", &ev::Rigid2::angle)
      .def(
          "__call__",
          [](const ev::Rigid2& T, const py::handle& points) {
            return applyToPoints<2>(points, [&](const sylva::Vec<2>& p) { return T(p); });
          },
          py::arg("points"),
          "The transform of one point (2,) or of each row of (n, 2).")
      .def(
          "pose",
          [](const ev::Rigid2& T, const py::handle& x) {
            return toArray(T.pose(toVec<3>(x, "x")));
          },
          py::arg("x"),
          "A pose [x, y, theta] moved by the transform.");
  m.def(
      "align_rigid_2d",
      [](const py::handle& estimated, const py::handle& truth) {
        return ev::alignRigid2(toRows<2>(estimated, "estimated"), toRows<2>(truth, "truth"));
      },
      py::arg("estimated"),
      py::arg("truth"),
      "The rotation and translation minimizing sum |T(estimated_i) - truth_i|^2 over (n, 2) point "
      "arrays.");

  m.def(
      "mean_squared_error",
      [](const ev::Similarity3& T, const py::handle& estimated, const py::handle& truth) {
        return ev::meanSquaredError(
            T, toRows<3>(estimated, "estimated"), toRows<3>(truth, "truth"));
      },
      py::arg("T"),
      py::arg("estimated"),
      py::arg("truth"),
      "1/N sum |T(estimated_i) - truth_i|^2: the landmark error e_l (tree-width thesis eq. 4.2) "
      "or, over camera "
      "positions, the trajectory error e_t (eq. 4.12). Mean squared, not RMS.");
  py::class_<ev::ConvergenceCriteria>(
      m,
      "ConvergenceCriteria",
      "A run converged when e_l < max_landmark_error and e_t < max_trajectory_error "
      "(tree-width thesis Sec. 4.2: 10 and 3).")
      .def(py::init<>())
      .def_readwrite("max_landmark_error", &ev::ConvergenceCriteria::max_landmark_error)
      .def_readwrite("max_trajectory_error", &ev::ConvergenceCriteria::max_trajectory_error)
      .def("converged",
           &ev::ConvergenceCriteria::converged,
           py::arg("landmark_error"),
           py::arg("trajectory_error"));
  m.def("negative_saturated_average",
        &ev::negativeSaturatedAverage,
        py::arg("errors"),
        py::arg("limit"),
        "1/n sum max(-limit, -e_i): the saturated average of tree-width thesis eq. 4.16-4.17 (0 is "
        "perfect).");
}

}  // namespace sylva_py
