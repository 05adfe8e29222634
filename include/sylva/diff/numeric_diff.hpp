#pragma once
/// @file
/// Numerical differentiation by central differences.
///
/// - `numericJacobian<Out, In>(f, x, difference)`: d f / d x at x, where `difference(a, b)`
///   is how two outputs are subtracted (plain `a - b`, or a model's angle-wrapping
///   residual). Step per coordinate: 1e-6 * max(1, |x_i|), close to the cube root of machine
///   epsilon that balances truncation and round-off for central differences.
/// - `NumericDiff<Model>`: gives a model with only `predict<double>` the analytic signature,
///   the way `AutoDiff<Model>` does, with numerically differentiated Jacobians.

#include <algorithm>
#include <cmath>
#include <type_traits>

#include "sylva/core/jacobian_ref.hpp"
#include "sylva/core/types.hpp"
#include "sylva/detail/model_traits.hpp"

namespace sylva {

inline constexpr double kNumericStep = 1e-6;

template <int Out, int In, typename Function, typename Difference>
Mat<Out, In> numericJacobian(Function&& f,
                             const Vec<In>& x,
                             Difference&& difference,
                             double relative_step = kNumericStep) {
  Mat<Out, In> J;
  for (int i = 0; i < In; ++i) {
    const double h = relative_step * std::max(1.0, std::abs(x[i]));
    Vec<In> plus = x;
    Vec<In> minus = x;
    plus[i] += h;
    minus[i] -= h;
    const Vec<Out> f_plus = f(plus);
    const Vec<Out> f_minus = f(minus);
    J.col(i) = difference(f_plus, f_minus) / (plus[i] - minus[i]);
  }
  return J;
}

/// Same, with plain subtraction of outputs.
template <int Out, int In, typename Function>
Mat<Out, In> numericJacobian(Function&& f, const Vec<In>& x, double relative_step = kNumericStep) {
  return numericJacobian<Out, In>(
      std::forward<Function>(f), x, [](const Vec<Out>& a, const Vec<Out>& b) { return Vec<Out>(a - b); },
      relative_step);
}

template <typename Model_>
struct NumericDiff : Model_ {
  using Model = Model_;
  using Model_::Model_;
  NumericDiff() = default;
  explicit NumericDiff(const Model_& model) : Model_(model) {}

  static constexpr int kRobotDim = Model_::Robot::kDim;
  static constexpr int kLandmarkDim = Model_::Landmark::kDim;
  static constexpr int kOutputDim = Model_::kDim;

  Vec<kOutputDim> operator()(const Vec<kRobotDim>& robot,
                             const Vec<kLandmarkDim>& landmark,
                             JacobianRef<kOutputDim, kRobotDim> J_z_x = {},
                             JacobianRef<kOutputDim, kLandmarkDim> J_z_l = {}) const {
    const Model_& model = *this;
    auto diff = [&](const Vec<kOutputDim>& a, const Vec<kOutputDim>& b) {
      return detail::residual(model, a, b);
    };
    if (J_z_x) {
      *J_z_x = numericJacobian<kOutputDim, kRobotDim>(
          [&](const Vec<kRobotDim>& x) { return model.template predict<double>(x, landmark); }, robot,
          diff);
    }
    if (J_z_l) {
      *J_z_l = numericJacobian<kOutputDim, kLandmarkDim>(
          [&](const Vec<kLandmarkDim>& l) { return model.template predict<double>(robot, l); },
          landmark, diff);
    }
    return model.template predict<double>(robot, landmark);
  }
};

}  // namespace sylva
