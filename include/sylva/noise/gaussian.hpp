#pragma once
/// @file
/// `Gaussian<N>`: zero-mean Gaussian noise of dimension N, built only through named
/// constructors that say what the numbers are (standard deviations, variances or a full
/// covariance). Construction validates: every entry finite, covariance symmetric and
/// positive definite. Invalid input throws `sylva::Error` naming the problem.

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <cmath>
#include <sstream>

#include "sylva/core/covariance_check.hpp"
#include "sylva/core/error.hpp"
#include "sylva/core/types.hpp"

namespace sylva {

template <int N>
class Gaussian {
 public:
  static constexpr int kDim = N;
  using Covariance = Mat<N, N>;

  /// Independent components with the given standard deviations (same units as the
  /// quantity, e.g. metres and radians).
  static Gaussian sigmas(const Vec<N>& sigma) {
    for (int i = 0; i < N; ++i) {
      if (!std::isfinite(sigma[i]) || !(sigma[i] > 0.0)) {
        std::ostringstream os;
        os << "Gaussian::sigmas: sigma[" << i << "] = " << sigma[i]
           << " must be finite and > 0";
        fail(std::isfinite(sigma[i]) ? ErrorCode::kNotPositiveDefinite : ErrorCode::kNonFinite,
             os.str());
      }
    }
    const Vec<N> variance = sigma.array().square().matrix();
    if (!variance.allFinite() || !(variance.minCoeff() > 0.0))
      fail(ErrorCode::kNotPositiveDefinite,
           "Gaussian::sigmas: a variance under- or overflows double precision");
    return Gaussian(Covariance(variance.asDiagonal()));
  }

  /// Independent components with the given variances (units squared).
  static Gaussian variances(const Vec<N>& variance) {
    for (int i = 0; i < N; ++i) {
      if (!std::isfinite(variance[i]) || !(variance[i] > 0.0)) {
        std::ostringstream os;
        os << "Gaussian::variances: variance[" << i << "] = " << variance[i] << " must be finite and > 0";
        fail(std::isfinite(variance[i]) ? ErrorCode::kNotPositiveDefinite : ErrorCode::kNonFinite, os.str());
      }
    }
    return sigmas(variance.array().sqrt().matrix().eval());
  }

  /// A full covariance matrix; must be symmetric (to 1e-9 relative) and positive definite.
  static Gaussian covariance(const Covariance& cov) {
    detail::checkCovarianceMatrix(cov, detail::Definiteness::kPositive, "Gaussian::covariance: matrix");
    return Gaussian(Covariance(0.5 * (cov + cov.transpose())));
  }

  const Covariance& covariance() const { return covariance_; }

  /// A sample of this noise, drawn with `normal()` returning independent N(0, 1) values.
  template <typename StandardNormal>
  Vec<N> sample(StandardNormal&& normal) const {
    Vec<N> white;
    for (int i = 0; i < N; ++i) white[i] = normal();
    return Eigen::LLT<Covariance>(covariance_).matrixL() * white;
  }

 private:
  explicit Gaussian(const Covariance& cov) : covariance_(cov) {}
  Covariance covariance_;
};

}  // namespace sylva
