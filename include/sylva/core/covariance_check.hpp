#pragma once
/// @file
/// `detail::checkCovarianceMatrix`: whether a matrix can serve as a covariance (finite,
/// symmetric, positive definite or semi-definite), for the checks that `Gaussian` and the
/// filter's constructor make of what they are given.
///
/// One function serves every size: a template on the size would compile Eigen's Cholesky
/// factorization again for each (docs/build-time.md), for a check that runs once per noise or
/// filter that is built. It factors in place through the same
/// `Eigen::LLT<Eigen::Ref<Eigen::MatrixXd>>` as the filter's batched update, so a program
/// that updates compiles it once, and up to 16 x 16 it works on the stack: building a noise
/// allocates nothing. It is still a template, with its argument's type deferred
/// (core/deferred.hpp), so that a translation unit that includes the header but never calls
/// it compiles none of it (as a plain inline function it did, about 2 s of g++ -O2 in every
/// unit that includes the filter).

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "sylva/core/deferred.hpp"
#include "sylva/core/error.hpp"

namespace sylva::detail {

enum class Definiteness {
  kPositive,      ///< every eigenvalue > 0 (a noise covariance: it is inverted)
  kPositiveSemi,  ///< no eigenvalue below -1e-12 of the largest entry (a prior)
};

/// Throws `sylva::Error` naming `what` unless `P` is finite (kNonFinite), symmetric to 1e-9 of
/// its largest entry (kInvalidArgument; of max(1, largest entry) for kPositiveSemi) and of the
/// given definiteness (kNotPositiveDefinite). The messages read "<what> is not finite", "...
/// is not symmetric", "... is not positive definite" or "... is not positive semi-definite".
template <typename Tag = void>
void checkCovarianceMatrix(const Eigen::Ref<const Deferred<Eigen::MatrixXd, Tag>>& P, Definiteness definiteness,
                           const char* what) {
  using WorkMatrix = Deferred<Eigen::MatrixXd, Tag>;
  if (!P.allFinite()) fail(ErrorCode::kNonFinite, std::string(what) + " is not finite");
  const bool semi = definiteness == Definiteness::kPositiveSemi;
  const double largest = P.size() > 0 ? P.cwiseAbs().maxCoeff() : 0.0;
  const double scale = semi ? std::max(1.0, largest) : largest;
  const Eigen::Index n = P.rows();
  for (Eigen::Index j = 0; j < n; ++j)
    for (Eigen::Index i = j + 1; i < n; ++i)
      if (!(std::abs(P(i, j) - P(j, i)) <= 1e-9 * scale))
        fail(ErrorCode::kInvalidArgument, std::string(what) + " is not symmetric");
  // The symmetric part, factored in place: on the stack up to 16 x 16.
  constexpr Eigen::Index kOnStack = 16;
  double stack[kOnStack * kOnStack];
  std::vector<double> heap;
  double* data = stack;
  if (n > kOnStack) {
    heap.resize(static_cast<std::size_t>(n * n));
    data = heap.data();
  }
  Eigen::Map<WorkMatrix> A(data, n, n);
  A = 0.5 * (P + P.transpose());
  // Positive semi-definite: no eigenvalue below -tol (tol = 1e-12 of the scale) exactly when
  // A + tol I is positive definite, which a Cholesky factorization decides: its backward
  // error, about n eps |A|, is far below tol, so round-off cannot turn the verdict.
  if (semi) A.diagonal().array() += 1e-12 * scale;
  const Eigen::LLT<Eigen::Ref<WorkMatrix>> llt(A);
  if (llt.info() != Eigen::Success)
    fail(ErrorCode::kNotPositiveDefinite,
         std::string(what) + (semi ? " is not positive semi-definite" : " is not positive definite"));
}

}  // namespace sylva::detail
