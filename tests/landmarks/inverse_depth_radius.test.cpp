// InverseDepthRadius (IDR): its declarations (normalize and the kappa > 0 domain, as the
// filter detects them), the conversion to TreeXYZR against InverseDepth's point and
// kappa / rho, its Jacobians against central differences at ordinary and awkward geometry,
// rejected input (nothing written), the linearity index, and the conversion inside the
// filter against the dense reference EKF.

#include "sylva_catch.hpp"

#include <cmath>
#include <limits>
#include <string>
#include <type_traits>

#include <sylva/detail/model_traits.hpp>
#include <sylva/filter/ekf.hpp>
#include <sylva/landmarks/inverse_depth.hpp>
#include <sylva/landmarks/inverse_depth_radius.hpp>
#include <sylva/landmarks/tree_xyzr.hpp>
#include <sylva/motion/constant_velocity_3d.hpp>
#include <sylva/testing/check_jacobians.hpp>
#include <sylva/testing/dense_reference_ekf.hpp>

#include "copy_init.hpp"
#include "error_helpers.hpp"

// Own namespace: the tests of a folder are compiled as one unity translation unit.
namespace unity_landmarks_inverse_depth_radius {

using namespace sylva;
using sylva_test::throwsCode;
using ToTree = InverseDepthRadiusToTree<ConstantVelocity3D>;

namespace {

Vec<7> idr(const Vec<3>& anchor, double theta, double phi, double rho, double kappa) {
  Vec<7> l;
  l << anchor, theta, phi, rho, kappa;
  return l;
}

Vec<13> cameraAt(const Vec<3>& position) {
  Vec<13> x = Vec<13>::Zero();
  x.head<3>() = position;
  x[3] = 1.0;
  x.segment<3>(7) = Vec<3>(0.2, -0.1, 0.0);
  return x;
}

// Puts an IDR tree with a full covariance into a filter, its anchor relative to the camera.
using CopyInitIdr = sylva_test::CopyInit<ConstantVelocity3D, InverseDepthRadius, true>;

}  // namespace

TEST_CASE("InverseDepthRadius declares its dimension, normalize and domain", "[landmarks][idr]") {
  STATIC_REQUIRE(InverseDepthRadius::kDim == 7);
  STATIC_REQUIRE(std::is_same_v<InverseDepthRadius::Mean, Vec<7>>);
  STATIC_REQUIRE(std::is_same_v<ToTree::From, InverseDepthRadius>);
  STATIC_REQUIRE(std::is_same_v<ToTree::To, TreeXYZR>);
  // The filter finds both (detail::normalize and the posterior domain check use these).
  STATIC_REQUIRE(detail::HasNormalize<InverseDepthRadius>::value);
  STATIC_REQUIRE(detail::HasDomain<InverseDepthRadius>::value);
  CHECK(std::string(InverseDepthRadius::kName) == "InverseDepthRadius");
  CHECK(std::string(ToTree::kName) == "InverseDepthRadiusToTree");
}

TEST_CASE("InverseDepthRadius::normalize wraps the azimuth only", "[landmarks][idr]") {
  for (const double theta : {0.3, 3.0 * kPi / 2.0, -7.0, kPi + 1e-9, 25.0}) {
    Vec<7> l = idr(Vec<3>(1, 2, 3), theta, 0.4, 0.2, 0.05);
    const Vec<7> before = l;
    InverseDepthRadius::normalize(l);
    INFO("theta " << theta << " -> " << l[3]);
    CHECK(l[3] > -kPi);
    CHECK(l[3] <= kPi);
    CHECK(std::remainder(l[3] - theta, 2.0 * kPi) == Approx(0.0).margin(1e-12));
    CHECK(l.head<3>() == before.head<3>());
    CHECK(l.tail<3>() == before.tail<3>());
  }
  Vec<7> l = idr(Vec<3>::Zero(), 3.0 * kPi / 2.0, 0.0, 0.1, 0.01);
  InverseDepthRadius::normalize(l);
  CHECK(l[3] == Approx(-kPi / 2.0).epsilon(1e-15));
}

TEST_CASE("InverseDepthRadius::domainViolation is kappa > 0", "[landmarks][idr]") {
  CHECK(InverseDepthRadius::domainViolation(idr(Vec<3>::Zero(), 0, 0, 0.1, 0.02)) == nullptr);
  CHECK(InverseDepthRadius::domainViolation(idr(Vec<3>::Zero(), 0, 0, 1e-9, 1e-12)) == nullptr);
  // rho <= 0 is inside the domain (a far tree's estimate crosses zero while it settles).
  CHECK(InverseDepthRadius::domainViolation(idr(Vec<3>::Zero(), 0, 0, 0.0, 0.02)) == nullptr);
  CHECK(InverseDepthRadius::domainViolation(idr(Vec<3>::Zero(), 0, 0, -0.1, 0.02)) == nullptr);
  for (const double kappa : {0.0, -0.01, std::numeric_limits<double>::quiet_NaN()}) {
    const char* why = InverseDepthRadius::domainViolation(idr(Vec<3>::Zero(), 0, 0, 0.1, kappa));
    INFO("kappa " << kappa);
    REQUIRE(why != nullptr);
    CHECK(std::string(why).find("kappa") != std::string::npos);
  }
}

TEST_CASE("InverseDepthRadiusToTree gives InverseDepth's point and the radius kappa / rho",
          "[landmarks][idr]") {
  const Vec<7> cases[] = {
      idr(Vec<3>(1, 2, 3), 0.4, -0.2, 0.25, 0.05),
      idr(Vec<3>(-3, 0.5, 1.5), kPi - 1e-6, 0.1, 1.0 / 12.0, 0.3 / 12.0),
      idr(Vec<3>(100, -40, 2), -2.0, -0.05, 0.002, 0.5 * 0.002),
  };
  for (const Vec<7>& l : cases) {
    INFO("l = " << l.transpose());
    Mat<4, 13> J_x = Mat<4, 13>::Constant(7.0);
    const Vec<4> tree = ToTree{}(cameraAt(Vec<3>(4, -1, 1)), l, J_x);
    const Vec<3> point = InverseDepth::point<double>(Vec<6>(l.head<6>()));
    CHECK((tree.head<3>() - point).norm() <= 1e-14 * point.norm());
    CHECK(tree[3] == Approx(l[6] / l[5]).epsilon(1e-15));
    CHECK(J_x.isZero(0.0));  // the robot does not enter
    // ... so another camera gives the same tree.
    CHECK(ToTree{}(cameraAt(Vec<3>(-50, 20, 3)), l) == tree);
  }
}

TEST_CASE("InverseDepthRadiusToTree Jacobians match numerical differentiation",
          "[landmarks][idr][jacobian]") {
  struct Case {
    const char* name;
    Vec<7> l;
  };
  const Case cases[] = {
      {"ordinary, 4 m", idr(Vec<3>(1, 2, 3), 0.4, -0.2, 0.25, 0.3 * 0.25)},
      {"azimuth at the seam (just below pi)", idr(Vec<3>(0, 0, 0), kPi - 1e-6, 0.0, 1.0, 0.2)},
      {"azimuth at the seam (just above -pi)", idr(Vec<3>(0, 0, 0), -kPi + 1e-6, 0.3, 0.5, 0.1)},
      {"looking almost straight up", idr(Vec<3>(5, -5, 1), -1.0, 1.5, 0.5, 0.05)},
      {"looking almost straight down", idr(Vec<3>(5, -5, 1), 2.0, -1.55, 0.5, 0.05)},
      {"500 m away", idr(Vec<3>(0, 0, 0), 0.2, 0.1, 0.002, 0.4 * 0.002)},
      {"5 cm away", idr(Vec<3>(0, 0, 0), 0.2, 0.1, 20.0, 0.02 * 20.0)},
      {"anchor far from the origin", idr(Vec<3>(800, -600, 40), 1.2, -0.1, 0.1, 0.03)},
  };
  for (const Case& c : cases) {
    INFO(c.name << ": l = " << c.l.transpose());
    // Far trees: derivatives w.r.t. rho are ~1/rho^2, so the comparison is relative.
    const auto report =
        testing::checkConversionJacobians(ToTree{}, cameraAt(Vec<3>(1, 1, 1)), c.l, 1e-6);
    INFO(report.message());
    CHECK(report.ok);
  }
}

TEST_CASE(
    "InverseDepthRadiusToTree rejects a tree at infinity, behind its anchor, of "
    "non-positive size or non-finite, before writing anything",
    "[landmarks][idr][errors]") {
  using Catch::Matchers::Contains;
  const Vec<13> x = cameraAt(Vec<3>::Zero());
  Mat<4, 13> J_x = Mat<4, 13>::Constant(7.0);
  Mat<4, 7> J_l = Mat<4, 7>::Constant(7.0);
  auto untouched = [&] {
    return J_x == Mat<4, 13>::Constant(7.0) && J_l == Mat<4, 7>::Constant(7.0);
  };

  const Vec<7> at_infinity = idr(Vec<3>::Zero(), 0.1, 0.0, 0.0, 0.02);
  CHECK_THROWS_WITH(ToTree{}(x, at_infinity, J_x, J_l), Contains("not usable for an XYZ-R tree"));
  CHECK(throwsCode([&] { ToTree{}(x, at_infinity, J_x, J_l); }, ErrorCode::kDegenerateGeometry));
  CHECK(untouched());

  const Vec<7> behind = idr(Vec<3>::Zero(), 0.1, 0.0, -0.5, 0.02);
  CHECK_THROWS_WITH(ToTree{}(x, behind, J_x, J_l), Contains("must be > 0"));
  CHECK(throwsCode([&] { ToTree{}(x, behind, J_x, J_l); }, ErrorCode::kDegenerateGeometry));
  CHECK(untouched());

  for (const double kappa : {0.0, -0.02}) {
    const Vec<7> l = idr(Vec<3>::Zero(), 0.1, 0.0, 0.2, kappa);
    INFO("kappa " << kappa);
    CHECK_THROWS_WITH(ToTree{}(x, l, J_x, J_l), Contains("kappa"));
    CHECK(throwsCode([&] { ToTree{}(x, l, J_x, J_l); }, ErrorCode::kDegenerateGeometry));
    CHECK(untouched());
  }

  for (int i = 0; i < 7; ++i) {
    for (const double bad :
         {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
      Vec<7> l = idr(Vec<3>(1, 2, 3), 0.1, 0.0, 0.2, 0.05);
      l[i] = bad;
      INFO("entry " << i << " = " << bad);
      CHECK_THROWS_WITH(ToTree{}(x, l, J_x, J_l),
                        Contains("InverseDepthRadiusToTree: the landmark is not finite"));
      CHECK(throwsCode([&] { ToTree{}(x, l, J_x, J_l); }, ErrorCode::kNonFinite));
      CHECK(untouched());
    }
  }
}

TEST_CASE("inverseDepthRadiusLinearityIndex is the inverse-depth index of the base centre",
          "[landmarks][idr]") {
  // A tree 10 m ahead of its anchor along x, rho = 0.1 +- 0.02 (see inverse_depth.test.cpp).
  for (const double kappa : {1e-3, 0.03, 0.5}) {
    const Vec<7> l = idr(Vec<3>::Zero(), 0.0, 0.0, 0.1, kappa);
    CHECK(inverseDepthRadiusLinearityIndex(Vec<3>::Zero(), l, 0.02) == Approx(0.8));
    CHECK(inverseDepthRadiusLinearityIndex(Vec<3>(10, 10, 0), l, 0.02) ==
          Approx(0.0).margin(1e-15));
    CHECK(inverseDepthRadiusLinearityIndex(Vec<3>::Zero(), l, 0.001) == Approx(0.04));
    const Vec<7> other = idr(Vec<3>(1, -2, 0.5), 0.7, -0.1, 0.07, kappa);
    CHECK(inverseDepthRadiusLinearityIndex(Vec<3>(3, 1, 1), other, 0.01) ==
          inverseDepthLinearityIndex(Vec<3>(3, 1, 1), Vec<6>(other.head<6>()), 0.01));
  }
  CHECK(throwsCode(
      [] {
        inverseDepthRadiusLinearityIndex(Vec<3>::Zero(), idr(Vec<3>::Zero(), 0, 0, -1.0, 0.1), 0.1);
      },
      ErrorCode::kDegenerateGeometry));
  CHECK(throwsCode(
      [] {
        inverseDepthRadiusLinearityIndex(Vec<3>::Zero(), idr(Vec<3>::Zero(), 0, 0, 0.1, 0.1), NAN);
      },
      ErrorCode::kNonFinite));
}

TEST_CASE("the filter normalizes IDR trees and refuses a non-positive kappa",
          "[landmarks][idr][filter]") {
  const Mat<13, 13> P0 = Mat<13, 13>::Identity() * 1e-4;
  Ekf<ConstantVelocity3D, InverseDepthRadius, TreeXYZR> ekf(cameraAt(Vec<3>(0.5, 0, 1)), P0);
  const Gaussian<7> noise = Gaussian<7>::covariance(Mat<7, 7>::Identity() * 1e-4);
  // An azimuth outside (-pi, pi] is wrapped when the landmark enters the state.
  ekf.add(1, CopyInitIdr{}, idr(Vec<3>::Zero(), 3.0 * kPi / 2.0, 0.1, 0.2, 0.05), noise);
  CHECK(ekf.landmarkMean<InverseDepthRadius>(1)[3] == Approx(-kPi / 2.0).epsilon(1e-15));
  // kappa <= 0 is outside the domain.
  CHECK(
      throwsCode([&] { ekf.add(2, CopyInitIdr{}, idr(Vec<3>::Zero(), 0.1, 0.1, 0.2, 0.0), noise); },
                 ErrorCode::kOutOfDomain));
  CHECK_FALSE(ekf.contains(2));
}

TEST_CASE("reparametrizing IDR to XYZ-R in the filter equals the dense reference",
          "[landmarks][idr][filter]") {
  const Mat<13, 13> P0 = Mat<13, 13>::Identity() * 1e-4;
  Ekf<ConstantVelocity3D, InverseDepthRadius, TreeXYZR> ekf(cameraAt(Vec<3>(0.5, 0, 1)), P0);
  testing::DenseReferenceEkf<ConstantVelocity3D> ref{
      ConstantVelocity3D{}, cameraAt(Vec<3>(0.5, 0, 1)), P0};
  Mat<7, 7> R = Mat<7, 7>::Identity() * 1e-3;
  R(5, 5) = 1e-4;
  R(6, 6) = 1e-6;
  R(3, 4) = R(4, 3) = 2e-4;
  R(5, 6) = R(6, 5) = 5e-6;  // kappa and rho correlated
  const Vec<7> z1 = idr(Vec<3>::Zero(), 0.3, 0.1, 0.2, 0.06);
  const Vec<7> z2 = idr(Vec<3>::Zero(), -0.3, 0.0, 0.5, 0.1);
  ekf.add(1, CopyInitIdr{}, z1, Gaussian<7>::covariance(R));
  ref.add(CopyInitIdr{}, z1, R);
  ekf.add(2, CopyInitIdr{}, z2, Gaussian<7>::covariance(R));
  ref.add(CopyInitIdr{}, z2, R);
  const int offset = ekf.slot(1).offset;
  const Vec<7> l = ekf.landmarkMean<InverseDepthRadius>(1);
  ekf.reparametrize(1, ToTree{});
  ref.reparametrize(offset, ToTree{});
  REQUIRE(ekf.holds<TreeXYZR>(1));
  CHECK((ekf.landmarkMean<TreeXYZR>(1) - ToTree{}(ekf.robotMean(), l)).norm() < 1e-14);
  CHECK(ekf.landmarkMean<TreeXYZR>(1)[3] == Approx(0.06 / 0.2).epsilon(1e-14));
  CHECK((ekf.mean() - ref.x).cwiseAbs().maxCoeff() < 1e-12);
  CHECK((ekf.covariance() - ref.P).cwiseAbs().maxCoeff() < 1e-12);
}

}  // namespace unity_landmarks_inverse_depth_radius
