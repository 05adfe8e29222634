// InverseDepth: the point it encodes, the conversion to Point3 and its Jacobian, the
// linearity index, and the conversion inside the filter against the dense reference.

#include <sylva/filter/ekf.hpp>
#include <sylva/landmarks/inverse_depth.hpp>
#include <sylva/motion/constant_velocity_3d.hpp>
#include <sylva/testing/check_jacobians.hpp>
#include <sylva/testing/dense_reference_ekf.hpp>

#include "sylva_catch.hpp"

#include <cmath>

#include "error_helpers.hpp"

using namespace sylva;
using ToPoint3 = InverseDepthToPoint3<ConstantVelocity3D>;

namespace {
Vec<6> inverseDepth(const Vec<3>& anchor, double theta, double phi, double rho) {
  Vec<6> l;
  l << anchor, theta, phi, rho;
  return l;
}
Vec<13> camera(const Vec<3>& r) {
  Vec<13> x = Vec<13>::Zero();
  x.head<3>() = r;
  x[3] = 1.0;
  return x;
}

// Puts an inverse-depth point with a full covariance into a filter: an inverse model that
// copies a 6-vector "measurement" anchored at the camera position.
struct CopyInit {
  using Robot = ConstantVelocity3D;
  using Landmark = InverseDepth;
  static constexpr int kMeasurementDim = 6;
  static constexpr const char* kName = "CopyInit";
  Vec<6> operator()(const Vec<13>& x, const Vec<6>& z, JacobianRef<6, 13> J_l_x = {}, JacobianRef<6, 6> J_l_z = {}) const {
    if (J_l_x) {
      (*J_l_x).setZero();
      (*J_l_x).leftCols<3>().topRows<3>().setIdentity();
    }
    if (J_l_z) (*J_l_z).setIdentity();
    Vec<6> l = z;
    l.head<3>() += x.head<3>();
    return l;
  }
};
}  // namespace

TEST_CASE("the inverse-depth direction follows the world axes", "[landmarks]") {
  CHECK((InverseDepth::direction(0.0, 0.0) - Vec<3>(1, 0, 0)).norm() < 1e-15);
  CHECK((InverseDepth::direction(kPi / 2, 0.0) - Vec<3>(0, 1, 0)).norm() < 1e-15);
  CHECK((InverseDepth::direction(0.3, kPi / 2) - Vec<3>(0, 0, 1)).norm() < 1e-15);
  const Vec<6> l = inverseDepth(Vec<3>(1, 2, 3), 0.4, -0.2, 0.25);
  CHECK((InverseDepth::point(l) - (Vec<3>(1, 2, 3) + 4.0 * InverseDepth::direction(0.4, -0.2))).norm() < 1e-14);
  CHECK((ToPoint3{}(camera(Vec<3>::Zero()), l) - InverseDepth::point(l)).norm() < 1e-14);
}

TEST_CASE("InverseDepthToPoint3 Jacobians match numerical differentiation", "[landmarks][jacobian]") {
  const Vec<6> cases[] = {
      inverseDepth(Vec<3>(1, 2, 3), 0.4, -0.2, 0.25),      // ordinary, 4 m
      inverseDepth(Vec<3>(0, 0, 0), kPi - 1e-6, 0.0, 1.0),  // azimuth at the seam
      inverseDepth(Vec<3>(5, -5, 1), -1.0, 1.5, 0.5),       // looking almost straight up
      inverseDepth(Vec<3>(0, 0, 0), 0.2, 0.1, 0.002),       // 500 m away
      inverseDepth(Vec<3>(0, 0, 0), 0.2, 0.1, 20.0),        // 5 cm away
  };
  for (const Vec<6>& l : cases) {
    INFO("l = " << l.transpose());
    // Far points: derivatives w.r.t. rho are ~1/rho^2, so the comparison is relative.
    const auto report = testing::checkConversionJacobians(ToPoint3{}, camera(Vec<3>(1, 1, 1)), l, 1e-6);
    INFO(report.message());
    CHECK(report.ok);
  }
}

TEST_CASE("the conversion rejects an inverse depth at infinity", "[landmarks][errors]") {
  using Catch::Matchers::Contains;
  CHECK_THROWS_WITH(ToPoint3{}(camera(Vec<3>::Zero()), inverseDepth(Vec<3>::Zero(), 0, 0, 0.0)),
                    Contains("not usable for a Euclidean point"));
  // A negative inverse depth (the point behind its anchor) is refused too, before any output.
  Mat<3, 6> J = Mat<3, 6>::Constant(7.0);
  CHECK_THROWS_WITH(ToPoint3{}(camera(Vec<3>::Zero()), inverseDepth(Vec<3>::Zero(), 0, 0, -0.5), {}, J),
                    Contains("must be > 0"));
  CHECK(J == Mat<3, 6>::Constant(7.0));
  // NaN anywhere (here the azimuth, with a usable rho) is reported as non-finite input.
  Vec<6> nan_azimuth = inverseDepth(Vec<3>::Zero(), 0, 0, 0.5);
  nan_azimuth[3] = NAN;
  CHECK_THROWS_WITH(ToPoint3{}(camera(Vec<3>::Zero()), nan_azimuth, {}, J), Contains("not finite"));
  CHECK(sylva_test::throwsCode([&] { ToPoint3{}(camera(Vec<3>::Zero()), nan_azimuth); }, ErrorCode::kNonFinite));
  CHECK(J == Mat<3, 6>::Constant(7.0));
  CHECK_THROWS_WITH(inverseDepthLinearityIndex(Vec<3>::Zero(), inverseDepth(Vec<3>::Zero(), 0, 0, -1.0), 0.1),
                    Contains("must be > 0"));
}

TEST_CASE("the linearity index falls as the point is seen with more parallax", "[landmarks]") {
  // A point 10 m ahead of its anchor along x, rho = 0.1 +- 0.02.
  const Vec<6> l = inverseDepth(Vec<3>::Zero(), 0.0, 0.0, 0.1);
  // Seen from the anchor itself: cos a = 1, d = 10, sigma_d = 0.02 / 0.01 = 2 -> L = 0.8.
  CHECK(inverseDepthLinearityIndex(Vec<3>::Zero(), l, 0.02) == Approx(0.8));
  // Seen from the side (camera at (10, 10, 0)): the rays are perpendicular, L = 0.
  CHECK(inverseDepthLinearityIndex(Vec<3>(10, 10, 0), l, 0.02) == Approx(0.0).margin(1e-15));
  // A well-known depth (sigma_rho 0.001): L = 0.04 < 0.1, ready for XYZ.
  CHECK(inverseDepthLinearityIndex(Vec<3>::Zero(), l, 0.001) == Approx(0.04));
}

TEST_CASE("reparametrizing inverse depth to XYZ in the filter equals the dense reference", "[landmarks][filter]") {
  Mat<13, 13> P0 = Mat<13, 13>::Identity() * 1e-4;
  Ekf<ConstantVelocity3D, InverseDepth, Point3> ekf(camera(Vec<3>(0.5, 0, 1)), P0);
  testing::DenseReferenceEkf<ConstantVelocity3D> ref{ConstantVelocity3D{}, camera(Vec<3>(0.5, 0, 1)), P0};
  Mat<6, 6> R = Mat<6, 6>::Identity() * 1e-3;
  R(5, 5) = 1e-4;
  R(3, 4) = R(4, 3) = 2e-4;
  const Vec<6> z = inverseDepth(Vec<3>::Zero(), 0.3, 0.1, 0.2);
  ekf.add(1, CopyInit{}, z, Gaussian<6>::covariance(R));
  ref.add(CopyInit{}, z, R);
  ekf.add(2, CopyInit{}, inverseDepth(Vec<3>::Zero(), -0.3, 0.0, 0.5), Gaussian<6>::covariance(R));
  ref.add(CopyInit{}, inverseDepth(Vec<3>::Zero(), -0.3, 0.0, 0.5), R);
  const int offset = ekf.slot(1).offset;
  ekf.reparametrize(1, ToPoint3{});
  ref.reparametrize(offset, ToPoint3{});
  CHECK(ekf.holds<Point3>(1));
  CHECK((ekf.mean() - ref.x).cwiseAbs().maxCoeff() < 1e-12);
  CHECK((ekf.covariance() - ref.P).cwiseAbs().maxCoeff() < 1e-12);
}
