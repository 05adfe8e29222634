#pragma once
// Test helpers: forward-mode automatic differentiation (Eigen's AutoDiffScalar) of any
// Scalar-generic function of one stacked input vector, the comparison of an analytic Jacobian
// with it entry by entry, and that comparison for the three kinds of model: a measurement
// model (its predict<T>), an inverse model (initialize<T>) and a landmark conversion
// (convert<T>), each against the Jacobians its operator() returns.
//
// Both are exact derivatives, so they differ by round-off only. Entry (i, j) passes when
//
//   |analytic - automatic| <= kRelative |automatic| + kRoundoff eps S_i / max(1, |v_j|),
//   S_i = |f_i(v)| + sum_k |automatic_ik| |v_k|,
//
// the second term being the round-off of a derivative computed from terms of the size of
// output i's (S_i, as in sylva/testing/check_jacobians.hpp, but without the central
// differences' division by a step): it lets an entry that is zero, or the small difference
// of large terms, pass, while entries of any size are held to a relative bound.

#include "sylva_catch.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <type_traits>

#include <Eigen/Core>
#include <unsupported/Eigen/AutoDiff>

#include <sylva/core/types.hpp>

namespace sylva_test {

/// The dual number that differentiates with respect to a stacked input of `In` entries.
template <int In>
using StackedDual = Eigen::AutoDiffScalar<sylva::Vec<In>>;

/// d f / d v at v, and f(v) in `value` when given. `f` is a generic callable that maps a
/// Vec<In, T> to a Vec<Out, T> for T = StackedDual<In> (write it with `auto`).
template <int Out, int In, typename Function>
sylva::Mat<Out, In> autoDiffJacobian(const Function& f,
                                     const sylva::Vec<In>& v,
                                     sylva::Vec<Out>* value = nullptr) {
  using Dual = StackedDual<In>;
  sylva::Vec<In, Dual> v_dual;
  for (int k = 0; k < In; ++k) v_dual[k] = Dual(v[k], In, k);
  const sylva::Vec<Out, Dual> y = f(v_dual);
  sylva::Mat<Out, In> J;
  for (int i = 0; i < Out; ++i) {
    J.row(i) = y[i].derivatives().transpose();
    if (value) (*value)[i] = y[i].value();
  }
  return J;
}

struct AutoDiffComparison {
  bool ok = true;
  double worst = 0.0;  ///< the largest |analytic - automatic| / allowed (<= 1 passes)
  int row = -1;
  int col = -1;
  double analytic = 0.0;
  double automatic = 0.0;
  double allowed = 0.0;

  std::string message(const std::string& layout) const {
    std::ostringstream os;
    os << (ok ? "ok, closest to its bound" : "MISMATCH") << " at (" << row << ", " << col << ") of "
       << layout << ": analytic " << analytic << " vs autodiff " << automatic << ", |difference| "
       << std::abs(analytic - automatic) << (ok ? " <= " : " > ") << "allowed " << allowed;
    return os.str();
  }
};

inline constexpr double kAutoDiffRelative = 1e-10;
/// Two exact derivatives computed along different routes: each of a few dozen operations
/// errs by at most a few ulps of the terms it combines, which S_i bounds.
inline constexpr double kAutoDiffRoundoff = 64.0;

/// Compares `analytic` with `automatic`, both d f / d v at v, with value = f(v).
template <int Out, int In>
AutoDiffComparison compareWithAutoDiff(const sylva::Mat<Out, In>& analytic,
                                       const sylva::Mat<Out, In>& automatic,
                                       const sylva::Vec<In>& v,
                                       const sylva::Vec<Out>& value) {
  constexpr double eps = std::numeric_limits<double>::epsilon();
  const sylva::Vec<Out> scale = value.cwiseAbs() + automatic.cwiseAbs() * v.cwiseAbs();
  AutoDiffComparison c;
  for (int j = 0; j < In; ++j) {
    for (int i = 0; i < Out; ++i) {
      const double a = analytic(i, j);
      const double d = automatic(i, j);
      const double allowed = kAutoDiffRelative * std::abs(d) +
                             kAutoDiffRoundoff * eps * scale[i] / std::max(1.0, std::abs(v[j]));
      const double difference = std::abs(a - d);
      double ratio = allowed > 0.0 ? difference / allowed : (difference > 0.0 ? INFINITY : 0.0);
      if (!std::isfinite(a) || !std::isfinite(d) || !std::isfinite(scale[i])) ratio = INFINITY;
      if (c.row < 0 || ratio > c.worst) {
        c.worst = ratio;
        c.row = i;
        c.col = j;
        c.analytic = a;
        c.automatic = d;
        c.allowed = allowed;
      }
    }
  }
  c.ok = c.worst <= 1.0;
  return c;
}

/// CHECKs `analytic` against autodiff of `f` at v (see the file comment); `layout` names the
/// stacked columns for the failure message, e.g. "[J_l_x | J_l_z] (columns robot 0-2, z 3-4)".
/// Also CHECKs that f(v) equals `analytic_value`, the value of the model's own operator(), to
/// round-off (Eigen may sum a double vector's norm in another order than a dual one's): the
/// function differentiated is the one the filter evaluates.
template <int Out, int In, typename Function>
void checkAgainstAutoDiff(const std::string& layout,
                          const sylva::Mat<Out, In>& analytic,
                          const sylva::Vec<Out>& analytic_value,
                          const Function& f,
                          const sylva::Vec<In>& v) {
  sylva::Vec<Out> value;
  const sylva::Mat<Out, In> automatic = autoDiffJacobian<Out, In>(f, v, &value);
  const AutoDiffComparison c = compareWithAutoDiff<Out, In>(analytic, automatic, v, value);
  INFO(c.message(layout) << "\nanalytic\n" << analytic << "\nautodiff\n" << automatic);
  CHECK(c.ok);
  INFO("operator() " << analytic_value.transpose() << "\nScalar-generic function "
                     << value.transpose());
  const sylva::Vec<Out> scale = value.cwiseAbs() + automatic.cwiseAbs() * v.cwiseAbs();
  CHECK(((value - analytic_value).cwiseAbs().array() <=
         16.0 * std::numeric_limits<double>::epsilon() * scale.array())
            .all());
}

/// [J_a | J_b] of a function of two inputs against autodiff of `g(a, b)`, a generic callable
/// over Vec<A, T> and Vec<B, T>, at [a; b]; `value` is what the model's operator() returned.
/// The name says "[J_a | J_b] of Model (a columns 0-.., b from ..)".
template <int Out, int A, int B, typename Generic>
void checkTwoInputsAgainstAutoDiff(const std::string& blocks, const char* model, const char* a_name,
                                   const char* b_name, const sylva::Mat<Out, A>& J_a, const sylva::Mat<Out, B>& J_b,
                                   const sylva::Vec<Out>& value, const sylva::Vec<A>& a, const sylva::Vec<B>& b,
                                   const Generic& g) {
  sylva::Mat<Out, A + B> analytic;
  analytic << J_a, J_b;
  sylva::Vec<A + B> v;
  v << a, b;
  const auto f = [&](const auto& s) {
    using T = typename std::decay_t<decltype(s)>::Scalar;
    return g(sylva::Vec<A, T>(s.template head<A>()), sylva::Vec<B, T>(s.template tail<B>()));
  };
  checkAgainstAutoDiff<Out, A + B>(blocks + " of " + model + " (" + a_name + " columns 0-" + std::to_string(A - 1) +
                                       ", " + b_name + " from " + std::to_string(A) + ")",
                                   analytic, value, f, v);
}

/// A measurement model's [J_z_x | J_z_l] against autodiff of its predict<T> over [robot; landmark].
template <typename Model>
void checkMeasurementAgainstAutoDiff(const Model& model,
                                     const sylva::Vec<Model::Robot::kDim>& robot,
                                     const sylva::Vec<Model::Landmark::kDim>& landmark) {
  sylva::Mat<Model::kDim, Model::Robot::kDim> J_z_x;
  sylva::Mat<Model::kDim, Model::Landmark::kDim> J_z_l;
  const sylva::Vec<Model::kDim> z = model(robot, landmark, J_z_x, J_z_l);
  checkTwoInputsAgainstAutoDiff("[J_z_x | J_z_l]", Model::kName, "robot", "landmark", J_z_x, J_z_l, z, robot, landmark,
                                [&](const auto& x, const auto& l) { return model.predict(x, l); });
}

/// An inverse (initialization) model's [J_l_x | J_l_z] against autodiff of its
/// initialize<T> over [robot; z].
template <typename Inverse>
void checkInverseAgainstAutoDiff(const Inverse& inverse,
                                 const sylva::Vec<Inverse::Robot::kDim>& robot,
                                 const sylva::Vec<Inverse::kMeasurementDim>& z) {
  sylva::Mat<Inverse::Landmark::kDim, Inverse::Robot::kDim> J_l_x;
  sylva::Mat<Inverse::Landmark::kDim, Inverse::kMeasurementDim> J_l_z;
  const sylva::Vec<Inverse::Landmark::kDim> l = inverse(robot, z, J_l_x, J_l_z);
  checkTwoInputsAgainstAutoDiff("[J_l_x | J_l_z]", Inverse::kName, "robot", "z", J_l_x, J_l_z, l, robot, z,
                                [&](const auto& x, const auto& m) { return inverse.initialize(x, m); });
}

/// A landmark conversion's [J_to_x | J_to_l] against autodiff of its convert<T> over
/// [robot; landmark].
template <typename Conversion>
void checkConversionAgainstAutoDiff(const Conversion& conversion,
                                    const sylva::Vec<Conversion::Robot::kDim>& robot,
                                    const sylva::Vec<Conversion::From::kDim>& landmark) {
  sylva::Mat<Conversion::To::kDim, Conversion::Robot::kDim> J_x;
  sylva::Mat<Conversion::To::kDim, Conversion::From::kDim> J_l;
  const sylva::Vec<Conversion::To::kDim> converted = conversion(robot, landmark, J_x, J_l);
  checkTwoInputsAgainstAutoDiff("[J_to_x | J_to_l]", Conversion::kName, "robot", "landmark", J_x, J_l, converted,
                                robot, landmark, [&](const auto& x, const auto& l) { return conversion.convert(x, l); });
}

}  // namespace sylva_test
