// The quaternion helpers' derivatives (core/quaternion.hpp) against forward-mode automatic
// differentiation: rotateTransposedJacobian, d (R(q)^T v) / dq, which the camera models chain
// with the normalization's Jacobian, and the Log map rotationVectorFromQuaternion.

#include "sylva_catch.hpp"

#include <cmath>

#include <Eigen/Core>
#include <unsupported/Eigen/AutoDiff>

#include <sylva/core/quaternion.hpp>
#include <sylva/core/types.hpp>

// Own namespace: the tests of a folder are compiled as one unity translation unit.
namespace unity_core_quaternion {

using sylva::Mat;
using sylva::Vec;
using Dual = Eigen::AutoDiffScalar<Vec<4>>;

/// d (R(q)^T v) / dq by autodiff of rotationMatrix, at q.
Mat<3, 4> rotateTransposedAutoDiff(const Vec<4>& q, const Vec<3>& v) {
  Vec<4, Dual> qd;
  for (int i = 0; i < 4; ++i) qd[i] = Dual(q[i], 4, i);
  const Vec<3, Dual> rotated = sylva::rotationMatrix<Dual>(qd).transpose() * v.cast<Dual>();
  Mat<3, 4> J;
  for (int r = 0; r < 3; ++r) J.row(r) = rotated[r].derivatives().transpose();
  return J;
}

TEST_CASE("rotateTransposedJacobian equals autodiff on the tangent of the unit sphere",
          "[core][quaternion][autodiff]") {
  // The two extensions of R(q)^T v off the unit sphere differ only along q itself, which a
  // model that normalizes q removes with (I - q q^T) / |q|: on the tangent they must agree.
  const Vec<3> rotations[] = {Vec<3>::Zero(),
                              Vec<3>(0.3, -0.2, 0.9),
                              Vec<3>(0.0, 0.0, 3.14159),
                              Vec<3>(-2.0, 1.0, 0.5),
                              Vec<3>(1e-9, 0.0, -1e-9)};
  const Vec<3> vectors[] = {Vec<3>(1.0, 2.0, 3.0),
                            Vec<3>(0.0, 0.0, 1.0),
                            Vec<3>(-1e3, 5e2, 2e-3),
                            Vec<3>(1e-6, -1e-6, 0.0)};
  for (const Vec<3>& rotation : rotations) {
    for (const bool negate : {false, true}) {
      Vec<4> q = sylva::quaternionFromRotationVector<double>(rotation);
      if (negate) q = -q;
      for (const Vec<3>& v : vectors) {
        const Mat<4, 4> tangent = Mat<4, 4>::Identity() - q * q.transpose();
        const Mat<3, 4> analytic = sylva::rotateTransposedJacobian(q, v) * tangent;
        const Mat<3, 4> automatic = rotateTransposedAutoDiff(q, v) * tangent;
        INFO("q " << q.transpose() << ", v " << v.transpose() << "\nanalytic\n"
                  << analytic << "\nautodiff\n"
                  << automatic);
        // Entries are sums of products of |v| with quaternion entries of at most 1.
        CHECK((analytic - automatic).cwiseAbs().maxCoeff() <= 1e-14 * v.norm());
      }
    }
  }
}

TEST_CASE("rotationVectorFromQuaternion is differentiable at the identity and away from it",
          "[core][quaternion][autodiff]") {
  // Log(Exp(theta)) = theta, so d Log / d q times d Exp / d theta is the identity, at theta = 0
  // (the series branch, differentiated through s^2, not sqrt(s^2)) and away from it.
  using Dual3 = Eigen::AutoDiffScalar<Vec<3>>;
  for (const Vec<3>& theta : {Vec<3>(0.0, 0.0, 0.0),
                              Vec<3>(1e-10, -2e-10, 0.0),
                              Vec<3>(0.3, -0.2, 0.9),
                              Vec<3>(0.0, 3.0, 0.1)}) {
    Vec<3, Dual3> theta_d;
    for (int i = 0; i < 3; ++i) theta_d[i] = Dual3(theta[i], 3, i);
    const Vec<3, Dual3> back = sylva::rotationVectorFromQuaternion<Dual3>(
        sylva::quaternionFromRotationVector<Dual3>(theta_d));
    Mat<3, 3> J;
    for (int r = 0; r < 3; ++r) {
      J.row(r) = back[r].derivatives().transpose();
      CHECK(std::abs(back[r].value() - theta[r]) <= 1e-15 * (1.0 + theta.norm()));
    }
    INFO("theta " << theta.transpose() << "\nd Log(Exp(theta)) / d theta\n" << J);
    CHECK(J.allFinite());
    CHECK((J - Mat<3, 3>::Identity()).cwiseAbs().maxCoeff() <= 1e-14);
  }
}

}  // namespace unity_core_quaternion
