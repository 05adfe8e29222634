#pragma once
/// @file
/// Consistency statistics of one run at one time step (multisensor thesis, "Consistency
/// Analysis"; Bar-Shalom, Li, Kirubarajan 2001, Sec. 5.4):
///
///   NEES   eps   = e^T P^-1 e                 e = x - x_hat            (2.43)
///   NIS    eps_v = nu^T S^-1 nu               nu = z - z_hat           (2.46)
///   NMEE   e_j / sqrt(P_jj) per component, averaged over runs             (2.45)
///
/// For a consistent linear-Gaussian filter NEES ~ chi-square(dim x) and NIS ~ chi-square(dim z).
/// A covariance that is not positive definite is reported as kNotPositiveDefinite.

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <cmath>

#include "sylva/core/error.hpp"
#include "sylva/core/types.hpp"

namespace sylva {

/// Normalized estimation error squared e^T P^-1 e (eq. 2.43). Works for fixed or dynamic sizes.
template <typename ErrorVector, typename CovarianceMatrix>
double nees(const Eigen::MatrixBase<ErrorVector>& error, const Eigen::MatrixBase<CovarianceMatrix>& covariance) {
  using Matrix = Eigen::Matrix<double, CovarianceMatrix::RowsAtCompileTime, CovarianceMatrix::ColsAtCompileTime>;
  if (error.rows() != covariance.rows() || covariance.rows() != covariance.cols())
    fail(ErrorCode::kInvalidArgument, "nees: error and covariance sizes do not match");
  if (!error.allFinite() || !covariance.allFinite())
    fail(ErrorCode::kNonFinite, "nees: error or covariance is not finite");
  const Eigen::LLT<Matrix> llt(covariance.derived());
  if (llt.info() != Eigen::Success)
    fail(ErrorCode::kNotPositiveDefinite, "nees: covariance is not positive definite");
  return error.dot(llt.solve(error.derived()));
}

/// Normalized innovation squared nu^T S^-1 nu (eq. 2.46): the same quadratic form.
template <typename InnovationVector, typename CovarianceMatrix>
double nis(const Eigen::MatrixBase<InnovationVector>& innovation, const Eigen::MatrixBase<CovarianceMatrix>& S) {
  return nees(innovation, S);
}

/// Per-component normalized error e_j / sqrt(P_jj), the summand of the NMEE (eq. 2.45).
template <typename ErrorVector, typename CovarianceMatrix>
Eigen::Matrix<double, ErrorVector::RowsAtCompileTime, 1> normalizedError(
    const Eigen::MatrixBase<ErrorVector>& error, const Eigen::MatrixBase<CovarianceMatrix>& covariance) {
  if (error.rows() != covariance.rows() || covariance.rows() != covariance.cols())
    fail(ErrorCode::kInvalidArgument, "normalizedError: error and covariance sizes do not match");
  const auto variances = covariance.diagonal();
  if (!(variances.array() > 0.0).all())
    fail(ErrorCode::kNotPositiveDefinite, "normalizedError: a variance is not positive");
  return error.cwiseQuotient(variances.cwiseSqrt());
}

}  // namespace sylva
