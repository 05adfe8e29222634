#pragma once
// The prototype path: a measurement model written in Python that runs through the C++
// filter. `PythonMeasurement<M>` has the analytic signature the filter looks for
// (include/sylva/detail/model_traits.hpp): it calls the Python h(robot, landmark), and either
// the user's Jacobians or central differences of h (sylva::numericJacobian, step 1e-6
// relative). `PythonInverse<M>` does the same for the landmark's initialization g(robot, z).
// Both observe a planar pose [x, y, theta] and a `Point2` landmark. Components listed in
// `angles` are wrapped to (-pi, pi] in the innovation and in the numerical differences.

#include <pybind11/pybind11.h>

#include <array>
#include <string>
#include <utility>

#include "sylva/core/angles.hpp"
#include "sylva/core/jacobian_ref.hpp"
#include "sylva/diff/numeric_diff.hpp"
#include "sylva/landmarks/point2.hpp"
#include "sylva/motion/pose_2d.hpp"

#include "arrays.hpp"

namespace sylva_py {

/// What a Python model is, apart from its dimension (the Python-side object `sylva.PythonModel`).
struct PythonModelSpec {
  int dim = 0;
  py::object function;   ///< h(robot, landmark) -> z, or g(robot, z) -> landmark
  py::object jacobians;  ///< None, or (robot, x) -> (J_robot, J_x)
  std::vector<int> angles;
  std::string name;
};

namespace detail {

template <int M>
sylva::Vec<M> wrapAngles(sylva::Vec<M> v, const std::vector<int>& angles) {
  for (const int i : angles) v[i] = sylva::wrapAngle(v[i]);
  return v;
}

/// Calls `spec.function(a, b)` and converts its result to a Vec<Out>.
template <int Out, int A, int B>
sylva::Vec<Out> call(const PythonModelSpec& spec, const sylva::Vec<A>& a, const sylva::Vec<B>& b) {
  const py::object result = spec.function(toArray(a), toArray(b));
  return toVec<Out>(result, spec.name + ": the result of the Python function");
}

/// Fills J_a (Out x A) and J_b (Out x B) from the Python Jacobians, or numerically.
template <int Out, int A, int B>
void jacobians(const PythonModelSpec& spec,
               const sylva::Vec<A>& a,
               const sylva::Vec<B>& b,
               sylva::JacobianRef<Out, A> J_a,
               sylva::JacobianRef<Out, B> J_b) {
  if (!J_a && !J_b) return;
  if (!spec.jacobians.is_none()) {
    const py::object result = spec.jacobians(toArray(a), toArray(b));
    py::tuple pair;
    if (py::isinstance<py::tuple>(result) || py::isinstance<py::list>(result))
      pair = py::tuple(result);
    if (pair.size() != 2)
      sylva::fail(
          sylva::ErrorCode::kInvalidArgument,
          spec.name + ": the Jacobian function must return a pair of arrays (J_robot, J_other)");
    if (J_a) *J_a = toMat<Out, A>(pair[0], spec.name + ": the robot Jacobian");
    if (J_b) *J_b = toMat<Out, B>(pair[1], spec.name + ": the second Jacobian");
    return;
  }
  const auto difference = [&](const sylva::Vec<Out>& p, const sylva::Vec<Out>& q) {
    return wrapAngles<Out>(p - q, spec.angles);
  };
  if (J_a)
    *J_a = sylva::numericJacobian<Out, A>(
        [&](const sylva::Vec<A>& x) { return call<Out, A, B>(spec, x, b); }, a, difference);
  if (J_b)
    *J_b = sylva::numericJacobian<Out, B>(
        [&](const sylva::Vec<B>& x) { return call<Out, A, B>(spec, a, x); }, b, difference);
}

}  // namespace detail

/// z = h(robot, landmark) of a Python function, M = 1, 2 or 3.
template <int M>
struct PythonMeasurement {
  using Robot = sylva::Pose2D;
  using Landmark = sylva::Point2;
  static constexpr int kDim = M;
  static constexpr const char* kName = "PythonModel";

  PythonModelSpec spec;

  sylva::Vec<M> operator()(const sylva::Vec<3>& robot,
                           const sylva::Vec<2>& landmark,
                           sylva::JacobianRef<M, 3> J_z_x = {},
                           sylva::JacobianRef<M, 2> J_z_l = {}) const {
    const sylva::Vec<M> z = detail::call<M, 3, 2>(spec, robot, landmark);
    detail::jacobians<M, 3, 2>(spec, robot, landmark, J_z_x, J_z_l);
    return z;
  }

  sylva::Vec<M> residual(const sylva::Vec<M>& z, const sylva::Vec<M>& z_hat) const {
    return detail::wrapAngles<M>(z - z_hat, spec.angles);
  }
};

/// landmark = g(robot, z) of a Python function, for `add`.
template <int M>
struct PythonInverse {
  using Robot = sylva::Pose2D;
  using Landmark = sylva::Point2;
  static constexpr int kMeasurementDim = M;
  static constexpr const char* kName = "PythonInverseModel";

  PythonModelSpec spec;

  sylva::Vec<2> operator()(const sylva::Vec<3>& robot,
                           const sylva::Vec<M>& z,
                           sylva::JacobianRef<2, 3> J_l_x = {},
                           sylva::JacobianRef<2, M> J_l_z = {}) const {
    const sylva::Vec<2> l = detail::call<2, 3, M>(spec, robot, z);
    PythonModelSpec plain = spec;
    plain.angles.clear();  // the landmark [x, y] has no angle
    detail::jacobians<2, 3, M>(plain, robot, z, J_l_x, J_l_z);
    return l;
  }
};

}  // namespace sylva_py
