#pragma once
/// @file
/// Framework-agnostic Jacobian checks for users' and sylva's own models: each compares the
/// analytic Jacobians a model returns with central differences and reports the entry closest
/// to (or furthest past) its bound by name, e.g.
/// "MISMATCH in J_z_x(1, 2): analytic -1 vs numeric -0.999 ...".
///
///   auto report = sylva::testing::checkMeasurementJacobians(RangeBearing{}, robot, landmark);
///   REQUIRE(report.ok);   // on failure, print report.message()
///
/// The bound is relative to each entry's own scale. An entry passes when
///
///   |analytic - numeric| <= tolerance * |numeric| + error estimate of numeric,
///
/// where the error estimate of the central difference D(h) = (f(x + h) - f(x - h)) / 2h has
/// two parts (see `kRoundoffFactor` for the derivation of the constants):
///
///   - truncation: |D(2h) - D(h)|. D(h) = f' + c h^2 + O(h^4), so D(2h) - D(h) = 3 c h^2 is
///     three times Richardson's estimate of D(h)'s truncation error (the margin covers the
///     next-order terms);
///   - round-off: kRoundoffFactor * eps * S_i / h_j, where S_i = |f_i| + sum_k |df_i/dx_k| |x_k|
///     over every input of the model is the size of the terms that make up output i: evaluating
///     f_i in floating point errs by a few eps times S_i, and the difference quotient divides
///     twice that error by 2 h_j. S_i also makes an exact zero entry pass against the numerical
///     noise of its row.
///
/// So an entry of size 1e-3 is held to the same relative tolerance as one of size 1, while a
/// numeric derivative that round-off or truncation leaves uncertain is not held to more
/// accuracy than it has. The default tolerance 1e-6 leaves room for the analytic Jacobian's
/// own round-off only: a 0.1% error fails at any scale the central differences resolve.

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>

#include "sylva/core/types.hpp"
#include "sylva/detail/model_traits.hpp"
#include "sylva/diff/evaluate.hpp"
#include "sylva/diff/numeric_diff.hpp"

namespace sylva::testing {

/// The round-off constant. Evaluating output f_i in floating point errs by |delta_i| <= n u S_i
/// to first order (u = eps / 2 the unit round-off): rounding the inputs moves f_i by at most
/// u sum_k |df_i/dx_k| |x_k|, the last operation adds u |f_i|, and each of the n roundings in
/// between adds at most one u of terms of that size. The central difference then errs by
/// |delta_i(x + h) - delta_i(x - h)| / 2 h_j <= n u S_i / h_j = (n / 2) eps S_i / h_j. A factor
/// 16 is n = 32 worst-case roundings, a few dozen operations from an input to an output
/// (errors that in practice add like a random walk, ~sqrt(n) u): every check in sylva's own
/// tests passes with a factor 64 times smaller, so 16 is a margin, not tuned to let them
/// through; and it is small enough that a 0.1% error still fails wherever S_i is of the size
/// of the entry's own terms (tests/diff/check_jacobians.test.cpp).
inline constexpr double kRoundoffFactor = 16.0;

struct JacobianReport {
  bool ok = true;
  /// The worst |analytic - numeric| / allowed over all entries compared: <= 1 passes.
  double max_error = 0.0;
  std::string block;  ///< e.g. "J_z_x"
  int row = -1;
  int col = -1;
  double analytic = 0.0;
  double numeric = 0.0;
  double estimate = 0.0;   ///< the error estimate of `numeric` (truncation + round-off)
  double allowed = 0.0;    ///< tolerance * |numeric| + estimate
  double tolerance = 0.0;  ///< the relative tolerance asked for

  std::string message() const {
    std::ostringstream os;
    if (row < 0) return "no Jacobian entries compared";
    const double difference = std::abs(analytic - numeric);
    os << (ok ? "ok, closest to its bound " : "MISMATCH in ") << block << "(" << row << ", " << col
       << "): analytic " << analytic << " vs numeric " << numeric << ", |difference| "
       << difference;
    if (numeric != 0.0) os << " (relative " << difference / std::abs(numeric) << ")";
    os << (ok ? " <= " : " > ") << "allowed " << allowed << " = " << tolerance
       << " x |numeric| + numeric error estimate " << estimate;
    return os.str();
  }

  /// Folds the comparison of one analytic/numeric pair into the report: entry (r, c) passes
  /// when |analytic - numeric| <= tol * |numeric| + estimate(r, c). `estimate` is the error
  /// of the numeric reference (zero for an exact reference).
  template <typename A, typename N, typename E>
  void compare(const std::string& name,
               const A& analytic_J,
               const N& numeric_J,
               const E& estimate_J,
               double tol) {
    tolerance = tol;
    for (int c = 0; c < analytic_J.cols(); ++c) {
      for (int r = 0; r < analytic_J.rows(); ++r) {
        const double a = analytic_J(r, c);
        const double n = numeric_J(r, c);
        const double e = estimate_J(r, c);
        const double bound = tol * std::abs(n) + e;
        const double difference = std::abs(a - n);
        double ratio = difference <= bound ? (bound > 0.0 ? difference / bound : 0.0)
                                           : (bound > 0.0 ? difference / bound : INFINITY);
        if (!std::isfinite(a) || !std::isfinite(n) || !std::isfinite(e)) ratio = INFINITY;
        if (row < 0 || ratio > max_error) {
          max_error = ratio;
          block = name;
          row = r;
          col = c;
          analytic = a;
          numeric = n;
          estimate = e;
          allowed = bound;
        }
      }
    }
    ok = max_error <= 1.0;
  }

  /// The same against an exact reference (no error estimate):
  /// |analytic - numeric| <= tol |numeric|.
  template <typename A, typename N>
  void compare(const std::string& name, const A& analytic_J, const N& numeric_J, double tol) {
    using Zero = Eigen::Matrix<double, A::RowsAtCompileTime, A::ColsAtCompileTime>;
    compare(name, analytic_J, numeric_J, Zero::Zero(analytic_J.rows(), analytic_J.cols()), tol);
  }
};

}  // namespace sylva::testing

namespace sylva::detail {

/// Central differences of one Jacobian block with what its error estimate needs.
template <int Out, int In>
struct CentralDifferences {
  Mat<Out, In> value;       ///< D(h), h_j = kNumericStep * max(1, |x_j|) (numericJacobian's step)
  Mat<Out, In> truncation;  ///< |D(2h) - D(h)|
  Vec<In> step;             ///< h_j
  Vec<Out> terms;           ///< sum_j |D(h)_ij| |x_j|: this input's share of S_i
};

template <int Out, int In, typename Function, typename Difference>
CentralDifferences<Out, In> centralDifferences(const Function& f,
                                               const Vec<In>& x,
                                               const Difference& difference) {
  CentralDifferences<Out, In> d;
  d.value = numericJacobian<Out, In>(f, x, difference, kNumericStep);
  const Mat<Out, In> wide = numericJacobian<Out, In>(f, x, difference, 2.0 * kNumericStep);
  d.truncation = (wide - d.value).cwiseAbs();
  for (int j = 0; j < In; ++j) d.step[j] = kNumericStep * std::max(1.0, std::abs(x[j]));
  d.terms = d.value.cwiseAbs() * x.cwiseAbs();
  return d;
}

/// The error estimate of each entry of d.value: truncation + kRoundoffFactor eps S_i / h_j,
/// with `scale` = S_i = |f_i| + the `terms` of every input block of the model.
template <int Out, int In>
Mat<Out, In> numericErrorEstimate(const CentralDifferences<Out, In>& d, const Vec<Out>& scale) {
  constexpr double eps = std::numeric_limits<double>::epsilon();
  Mat<Out, In> e;
  for (int j = 0; j < In; ++j)
    e.col(j) = d.truncation.col(j) + (testing::kRoundoffFactor * eps / d.step[j]) * scale;
  return e;
}

}  // namespace sylva::detail

namespace sylva::testing {

/// Measurement model: J_z_x and J_z_l against central differences of `predict<double>`
/// (outputs subtracted with the model's residual, so a bearing's wrap does not matter).
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
  const Vec<M> z = detail::evaluate(model, robot, landmark, J_z_x, J_z_l);
  auto residual = [&](const Vec<M>& a, const Vec<M>& b) {
    return Vec<M>(detail::residual(model, a, b));
  };
  const auto N_x = detail::centralDifferences<M, R>(
      [&](const Vec<R>& x) { return Vec<M>(model.template predict<double>(x, landmark)); },
      robot,
      residual);
  const auto N_l = detail::centralDifferences<M, L>(
      [&](const Vec<L>& l) { return Vec<M>(model.template predict<double>(robot, l)); },
      landmark,
      residual);
  const Vec<M> scale = z.cwiseAbs() + N_x.terms + N_l.terms;
  JacobianReport report;
  report.compare("J_z_x", J_z_x, N_x.value, detail::numericErrorEstimate(N_x, scale), tolerance);
  report.compare("J_z_l", J_z_l, N_l.value, detail::numericErrorEstimate(N_l, scale), tolerance);
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
  const Vec<L> l = inverse(robot, z, J_l_x, J_l_z);
  auto minus = [](const Vec<L>& a, const Vec<L>& b) { return Vec<L>(a - b); };
  const auto N_x = detail::centralDifferences<L, R>(
      [&](const Vec<R>& x) { return Vec<L>(inverse(x, z)); }, robot, minus);
  const auto N_z = detail::centralDifferences<L, Z>(
      [&](const Vec<Z>& zz) { return Vec<L>(inverse(robot, zz)); }, z, minus);
  const Vec<L> scale = l.cwiseAbs() + N_x.terms + N_z.terms;
  JacobianReport report;
  report.compare("J_l_x", J_l_x, N_x.value, detail::numericErrorEstimate(N_x, scale), tolerance);
  report.compare("J_l_z", J_l_z, N_z.value, detail::numericErrorEstimate(N_z, scale), tolerance);
  return report;
}

/// Motion model: J_x and J_n (w.r.t. the noise input), against central differences of the
/// model's `propagate<double>(x, u, n, dt)` at n = 0; and the mean prediction operator()
/// against propagate at n = 0 (block "f - propagate", allowed tolerance * |f_i| plus the
/// round-off term of the file comment), so that the Jacobians checked are those of the
/// function the filter runs.
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
  const Vec<D> propagated = motion.template propagate<double>(x, u, zero, dt);
  const auto N_x = detail::centralDifferences<D, D>(
      [&](const Vec<D>& xx) { return Vec<D>(motion.template propagate<double>(xx, u, zero, dt)); },
      x,
      diff);
  const auto N_n = detail::centralDifferences<D, N>(
      [&](const Vec<N>& nn) { return Vec<D>(motion.template propagate<double>(x, u, nn, dt)); },
      zero,
      diff);
  const Vec<D> scale = propagated.cwiseAbs() + N_x.terms + N_n.terms;
  JacobianReport report;
  report.compare("J_x", J_x, N_x.value, detail::numericErrorEstimate(N_x, scale), tolerance);
  report.compare("J_n", J_n, N_n.value, detail::numericErrorEstimate(N_n, scale), tolerance);
  // Two evaluations of the same function differ by round-off only: the round-off term without
  // the division by a step, and the relative tolerance on the value itself.
  const Vec<D> mean = motion(x, u, dt);
  const Vec<D> agreement = tolerance * propagated.cwiseAbs() +
                           (kRoundoffFactor * std::numeric_limits<double>::epsilon()) * scale;
  report.compare("f - propagate", diff(mean, propagated), Vec<D>::Zero(), agreement, tolerance);
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
  const Vec<T> to = conversion(robot, landmark, J_x, J_l);
  auto minus = [](const Vec<T>& a, const Vec<T>& b) { return Vec<T>(a - b); };
  const auto N_x = detail::centralDifferences<T, R>(
      [&](const Vec<R>& x) { return Vec<T>(conversion(x, landmark)); }, robot, minus);
  const auto N_l = detail::centralDifferences<T, F>(
      [&](const Vec<F>& l) { return Vec<T>(conversion(robot, l)); }, landmark, minus);
  const Vec<T> scale = to.cwiseAbs() + N_x.terms + N_l.terms;
  JacobianReport report;
  report.compare("J_to_x", J_x, N_x.value, detail::numericErrorEstimate(N_x, scale), tolerance);
  report.compare("J_to_l", J_l, N_l.value, detail::numericErrorEstimate(N_l, scale), tolerance);
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
  const Vec<T> to = conversion(robot, landmark, z, J_x, J_l, J_z);
  auto minus = [](const Vec<T>& a, const Vec<T>& b) { return Vec<T>(a - b); };
  const auto N_x = detail::centralDifferences<T, R>(
      [&](const Vec<R>& x) { return Vec<T>(conversion(x, landmark, z)); }, robot, minus);
  const auto N_l = detail::centralDifferences<T, F>(
      [&](const Vec<F>& l) { return Vec<T>(conversion(robot, l, z)); }, landmark, minus);
  const auto N_z = detail::centralDifferences<T, Z>(
      [&](const Vec<Z>& zz) { return Vec<T>(conversion(robot, landmark, zz)); }, z, minus);
  const Vec<T> scale = to.cwiseAbs() + N_x.terms + N_l.terms + N_z.terms;
  JacobianReport report;
  report.compare("J_to_x", J_x, N_x.value, detail::numericErrorEstimate(N_x, scale), tolerance);
  report.compare("J_to_l", J_l, N_l.value, detail::numericErrorEstimate(N_l, scale), tolerance);
  report.compare("J_to_z", J_z, N_z.value, detail::numericErrorEstimate(N_z, scale), tolerance);
  return report;
}

}  // namespace sylva::testing
