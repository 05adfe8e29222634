// JacobianRef: optional, writes through to matrices and to blocks of larger matrices.

#include <sylva/core/jacobian_ref.hpp>
#include <sylva/core/types.hpp>

#include "sylva_catch.hpp"

using namespace sylva;

namespace {
int fill(JacobianRef<2, 3> J) {
  if (!J) return 0;
  *J << 1, 2, 3, 4, 5, 6;
  return 1;
}
}  // namespace

TEST_CASE("JacobianRef is optional and writes through", "[core]") {
  CHECK(fill({}) == 0);
  CHECK(fill(skip) == 0);
  Mat<2, 3> J = Mat<2, 3>::Zero();
  CHECK(fill(J) == 1);
  CHECK(J == (Mat<2, 3>() << 1, 2, 3, 4, 5, 6).finished());
  // A block of a larger column-major matrix (outer stride 4).
  Eigen::Matrix<double, 4, 5> H = Eigen::Matrix<double, 4, 5>::Zero();
  CHECK(fill(H.block<2, 3>(1, 2)) == 1);
  CHECK(H.block<2, 3>(1, 2) == J);
  CHECK(H.leftCols<2>().isZero());
  CHECK(H.row(0).isZero());
  CHECK(H.row(3).isZero());
  Eigen::MatrixXd D = Eigen::MatrixXd::Zero(6, 6);
  auto block = D.block(2, 1, 2, 3);
  CHECK(fill(block) == 1);
  CHECK(D.block(2, 1, 2, 3) == J);
  CHECK(D.sum() == J.sum());
}
