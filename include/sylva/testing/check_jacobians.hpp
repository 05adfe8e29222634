#pragma once
/// @file
/// Framework-agnostic Jacobian checks for users' and sylva's own models: each compares the
/// analytic Jacobians a model returns with central differences and reports the worst entry
/// by name, e.g. "J_z_x(1, 2): analytic -1 vs numeric -0.999 (error 1e-3)".
///
///   auto report = sylva::testing::checkMeasurementJacobians(RangeBearing{}, robot, landmark);
///   REQUIRE(report.ok);   // on failure, print report.message()
///
/// The error of an entry is |analytic - numeric| / max(1, |numeric|).

#include <cmath>
#include <sstream>
#include <string>

#include "sylva/core/types.hpp"
#include "sylva/detail/model_traits.hpp"
#include "sylva/diff/numeric_diff.hpp"

namespace sylva::testing {

struct JacobianReport {
  bool ok = true;
  double max_error = 0.0;
  std::string block;  ///< e.g. "J_z_x"
  int row = -1;
  int col = -1;
  double analytic = 0.0;
  double numeric = 0.0;
  double tolerance = 0.0;

  std::string message() const {
    std::ostringstream os;
    if (row < 0) return "no Jacobian entries compared";
    os << (ok ? "ok, worst " : "MISMATCH in ") << block << "(" << row << ", " << col
       << "): analytic " << analytic << " vs numeric " << numeric << " (error " << max_error
       << ", tolerance " << tolerance << ")";
    return os.str();
  }

  /// Folds the comparison of one analytic/numeric pair into the report.
  template <typename A, typename N>
  void compare(const std::string& name, const A& analytic_J, const N& numeric_J, double tol) {
    tolerance = tol;
    for (int c = 0; c < analytic_J.cols(); ++c) {
      for (int r = 0; r < analytic_J.rows(); ++r) {
        const double a = analytic_J(r, c);
        const double n = numeric_J(r, c);
        double e = std::abs(a - n) / std::max(1.0, std::abs(n));
        if (!std::isfinite(a) || !std::isfinite(n)) e = INFINITY;
        if (row < 0 || e > max_error || !(e == e)) {
          max_error = e;
          block = name;
          row = r;
          col = c;
          analytic = a;
          numeric = n;
        }
      }
    }
    ok = max_error <= tol;
  }
};

/// Measurement model: J_z_x and J_z_l against central differences of `predict<double>`.
template <typename Model>
JacobianReport checkMeasurementJacobians(const Model& model,
                                         const Vec<Model::Robot::kDim>& robot,
                                         const Vec<Model::Landmark::kDim>& landmark,
                                         double tolerance = 1e-6) {
  constexpr int M = Model::kDim;
  constexpr int R = Model::Robot::kDim;
  constexpr int L = Model::Landmark::kDim;
  Mat<M, R> J_z_x;
  Mat<M, L> J_z_l;
  detail::evaluate(model, robot, landmark, J_z_x, J_z_l);
  const NumericDiff<Model> numeric(model);
  Mat<M, R> N_z_x;
  Mat<M, L> N_z_l;
  numeric(robot, landmark, N_z_x, N_z_l);
  JacobianReport report;
  report.compare("J_z_x", J_z_x, N_z_x, tolerance);
  const JacobianReport robot_part = report;
  report.compare("J_z_l", J_z_l, N_z_l, tolerance);
  report.ok = report.ok && robot_part.ok;
  return report;
}

/// Inverse (initialization) model: J_l_x and J_l_z.
template <typename Inverse>
JacobianReport checkInverseJacobians(const Inverse& inverse,
                                     const Vec<Inverse::Robot::kDim>& robot,
                                     const Vec<Inverse::kMeasurementDim>& z,
                                     double tolerance = 1e-6) {
  constexpr int L = Inverse::Landmark::kDim;
  constexpr int R = Inverse::Robot::kDim;
  constexpr int Z = Inverse::kMeasurementDim;
  Mat<L, R> J_l_x;
  Mat<L, Z> J_l_z;
  inverse(robot, z, J_l_x, J_l_z);
  const Mat<L, R> N_l_x =
      numericJacobian<L, R>([&](const Vec<R>& x) { return Vec<L>(inverse(x, z)); }, robot);
  const Mat<L, Z> N_l_z =
      numericJacobian<L, Z>([&](const Vec<Z>& zz) { return Vec<L>(inverse(robot, zz)); }, z);
  JacobianReport report;
  report.compare("J_l_x", J_l_x, N_l_x, tolerance);
  const bool first_ok = report.ok;
  report.compare("J_l_z", J_l_z, N_l_z, tolerance);
  report.ok = report.ok && first_ok;
  return report;
}

/// Motion model: J_x and J_n (w.r.t. the noise input), against central differences of the
/// model's `propagate<double>(x, u, n, dt)` at n = 0; and the mean prediction operator()
/// against propagate at n = 0 (block "f - propagate"), so that the Jacobians checked are those
/// of the function the filter runs.
template <typename Motion>
JacobianReport checkMotionJacobians(const Motion& motion,
                                    const Vec<Motion::kDim>& x,
                                    const Vec<Motion::kControlDim>& u,
                                    double dt,
                                    double tolerance = 1e-6) {
  constexpr int D = Motion::kDim;
  constexpr int N = Motion::kNoiseDim;
  Mat<D, D> J_x;
  Mat<D, N> J_n;
  motion(x, u, dt, J_x, J_n);
  auto diff = [](const Vec<D>& a, const Vec<D>& b) { return Vec<D>(Motion::difference(a, b)); };
  const Vec<N> zero = Vec<N>::Zero();
  const Mat<D, D> N_x = numericJacobian<D, D>(
      [&](const Vec<D>& xx) { return Vec<D>(motion.template propagate<double>(xx, u, zero, dt)); }, x, diff);
  const Mat<D, N> N_n = numericJacobian<D, N>(
      [&](const Vec<N>& nn) { return Vec<D>(motion.template propagate<double>(x, u, nn, dt)); }, zero, diff);
  JacobianReport report;
  report.compare("J_x", J_x, N_x, tolerance);
  report.compare("J_n", J_n, N_n, tolerance);
  const Vec<D> mean = motion(x, u, dt);
  report.compare("f - propagate", diff(mean, Vec<D>(motion.template propagate<double>(x, u, zero, dt))), Vec<D>::Zero(),
                 tolerance);
  return report;
}

/// Landmark conversion (reparametrization): J_to_x and J_to_l.
template <typename Conversion, int R>
JacobianReport checkConversionJacobians(const Conversion& conversion,
                                        const Vec<R>& robot,
                                        const Vec<Conversion::From::kDim>& landmark,
                                        double tolerance = 1e-6) {
  constexpr int F = Conversion::From::kDim;
  constexpr int T = Conversion::To::kDim;
  Mat<T, R> J_x;
  Mat<T, F> J_l;
  conversion(robot, landmark, J_x, J_l);
  const Mat<T, R> N_x = numericJacobian<T, R>(
      [&](const Vec<R>& x) { return Vec<T>(conversion(x, landmark)); }, robot);
  const Mat<T, F> N_l = numericJacobian<T, F>(
      [&](const Vec<F>& l) { return Vec<T>(conversion(robot, l)); }, landmark);
  JacobianReport report;
  report.compare("J_to_x", J_x, N_x, tolerance);
  const bool first_ok = report.ok;
  report.compare("J_to_l", J_l, N_l, tolerance);
  report.ok = report.ok && first_ok;
  return report;
}

/// The same for a conversion that also takes a measurement z (`InverseTreeWidth`):
/// J_to_x, J_to_l and J_to_z against central differences.
template <typename Conversion, int R>
JacobianReport checkMeasuredConversionJacobians(const Conversion& conversion,
                                                const Vec<R>& robot,
                                                const Vec<Conversion::From::kDim>& landmark,
                                                const Vec<Conversion::kMeasurementDim>& z,
                                                double tolerance = 1e-6) {
  constexpr int F = Conversion::From::kDim;
  constexpr int T = Conversion::To::kDim;
  constexpr int Z = Conversion::kMeasurementDim;
  Mat<T, R> J_x;
  Mat<T, F> J_l;
  Mat<T, Z> J_z;
  conversion(robot, landmark, z, J_x, J_l, J_z);
  const Mat<T, R> N_x = numericJacobian<T, R>(
      [&](const Vec<R>& x) { return Vec<T>(conversion(x, landmark, z)); }, robot);
  const Mat<T, F> N_l = numericJacobian<T, F>(
      [&](const Vec<F>& l) { return Vec<T>(conversion(robot, l, z)); }, landmark);
  const Mat<T, Z> N_z = numericJacobian<T, Z>(
      [&](const Vec<Z>& zz) { return Vec<T>(conversion(robot, landmark, zz)); }, z);
  JacobianReport report;
  report.compare("J_to_x", J_x, N_x, tolerance);
  bool ok = report.ok;
  report.compare("J_to_l", J_l, N_l, tolerance);
  ok = ok && report.ok;
  report.compare("J_to_z", J_z, N_z, tolerance);
  report.ok = report.ok && ok;
  return report;
}

}  // namespace sylva::testing
