// detail::checkCovarianceMatrix, the one check behind Gaussian::covariance and the filter's
// prior: its verdicts and messages, on the stack (n <= 16) and on the heap (n > 16) alike.

#include <Eigen/Core>
#include <Eigen/QR>
#include <limits>
#include <string>

#include <sylva/core/covariance_check.hpp>

#include "error_helpers.hpp"
#include "sylva_catch.hpp"

namespace covariance_check_test {

using sylva::ErrorCode;
using sylva::detail::checkCovarianceMatrix;
using sylva::detail::Definiteness;

// A symmetric matrix with the given eigenvalues, in a rotated basis (so that no entry shows
// the verdict by itself).
Eigen::MatrixXd withEigenvalues(const Eigen::VectorXd& lambda) {
  const Eigen::Index n = lambda.size();
  Eigen::MatrixXd A(n, n);
  for (Eigen::Index j = 0; j < n; ++j)
    for (Eigen::Index i = 0; i < n; ++i) A(i, j) = 1.0 / (1.0 + static_cast<double>(i + 2 * j)) + (i == j ? 1.0 : 0.0);
  const Eigen::MatrixXd Q = A.householderQr().householderQ();
  Eigen::MatrixXd P = Q * lambda.asDiagonal() * Q.transpose();
  return 0.5 * (P + P.transpose());
}

// The message of the refusal without the error code's prefix ("" when accepted).
std::string messageOf(const Eigen::MatrixXd& P, Definiteness d) {
  try {
    checkCovarianceMatrix(P, d, "the matrix");
  } catch (const sylva::Error& e) {
    const std::string what = e.what();
    const std::size_t at = what.find("the matrix");
    return at == std::string::npos ? what : what.substr(at);
  }
  return "";
}

}  // namespace covariance_check_test

TEST_CASE("checkCovarianceMatrix decides definiteness alike on the stack and on the heap", "[core]") {
  using namespace covariance_check_test;
  for (const int n : {1, 3, 16, 17, 40}) {
    CAPTURE(n);
    Eigen::VectorXd lambda = Eigen::VectorXd::LinSpaced(n, 0.5, 4.0);
    CHECK(messageOf(withEigenvalues(lambda), Definiteness::kPositive).empty());
    CHECK(messageOf(withEigenvalues(lambda), Definiteness::kPositiveSemi).empty());
    // A zero eigenvalue (in a rotated basis, so only up to round-off): a valid prior.
    lambda[0] = 0.0;
    CHECK(messageOf(withEigenvalues(lambda), Definiteness::kPositiveSemi).empty());
    // An exact zero on the diagonal: a valid prior, not a noise, which is inverted.
    Eigen::MatrixXd singular = Eigen::MatrixXd::Identity(n, n);
    singular(n - 1, n - 1) = 0.0;
    CHECK(messageOf(singular, Definiteness::kPositiveSemi).empty());
    CHECK(messageOf(singular, Definiteness::kPositive) == "the matrix is not positive definite");
    // A clearly negative eigenvalue: neither.
    lambda[0] = -1e-3;
    CHECK(messageOf(withEigenvalues(lambda), Definiteness::kPositiveSemi) == "the matrix is not positive semi-definite");
    CHECK(sylva_test::throwsCode([&] { checkCovarianceMatrix(withEigenvalues(lambda), Definiteness::kPositive, "P"); },
                                 ErrorCode::kNotPositiveDefinite));
  }
}

TEST_CASE("checkCovarianceMatrix refuses non-finite and asymmetric matrices first", "[core]") {
  using namespace covariance_check_test;
  for (const int n : {2, 20}) {
    CAPTURE(n);
    Eigen::MatrixXd P = Eigen::MatrixXd::Identity(n, n);
    P(n - 1, 0) = std::numeric_limits<double>::quiet_NaN();
    CHECK(messageOf(P, Definiteness::kPositiveSemi) == "the matrix is not finite");
    CHECK(sylva_test::throwsCode([&] { checkCovarianceMatrix(P, Definiteness::kPositive, "P"); }, ErrorCode::kNonFinite));
    P(n - 1, 0) = 1e-6;  // (0, n - 1) stays 0: asymmetric by far more than 1e-9 of the scale
    CHECK(messageOf(P, Definiteness::kPositive) == "the matrix is not symmetric");
    CHECK(sylva_test::throwsCode([&] { checkCovarianceMatrix(P, Definiteness::kPositiveSemi, "P"); },
                                 ErrorCode::kInvalidArgument));
    P(0, n - 1) = 1e-6 + 1e-16;  // within round-off: accepted, and the symmetric part is used
    CHECK(messageOf(P, Definiteness::kPositive).empty());
  }
}
