// Ekf::constrain, a measurement of two landmarks without the robot, against the dense textbook
// update with the same H, for both update forms and two parametrizations; merging a landmark
// mapped twice (constrain, then remove); and its refusals, which leave the filter unchanged.

#include <limits>

#include <sylva/filter/compression.hpp>
#include <sylva/sylva.hpp>
#include <sylva/testing/dense_reference_ekf.hpp>

#include "filter/test_models.hpp"
#include "filter_snapshot.hpp"
#include "sylva_catch.hpp"

// Own namespace: the tests of a folder are compiled as one unity translation unit.
namespace unity_filter_constrain {

using namespace sylva;
using sylva_test::InverseDistance2;
using sylva_test::InverseDistanceFromRangeBearing;
using sylva_test::requireRejected;
using Reference = testing::DenseReferenceEkf<Unicycle2D>;

namespace {

/// A filter and its dense reference with five landmarks, correlated by a few updates:
/// 1, 3, 5 are points, 2 and 4 inverse distance.
template <typename Filter>
struct Scene {
  Filter ekf;
  Reference ref;
  Scene()
      : ekf(Vec<3>(0.5, -0.2, 0.3), Mat<3, 3>(Vec<3>(0.02, 0.03, 0.004).asDiagonal())),
        ref{Unicycle2D{}, Vec<3>(0.5, -0.2, 0.3), Mat<3, 3>(Vec<3>(0.02, 0.03, 0.004).asDiagonal())} {
    const auto r = Gaussian<2>::sigmas(Vec<2>(0.1, 0.02));
    const Vec<2> readings[] = {{4.0, 0.5}, {7.0, -0.4}, {3.0, -1.2}, {9.0, 1.1}, {4.1, 0.55}};
    for (int i = 0; i < 5; ++i) {
      if (i % 2 == 1) {
        ekf.add(i + 1, InverseDistanceFromRangeBearing{}, readings[i], r);
        ref.add(InverseDistanceFromRangeBearing{}, readings[i], r.covariance());
      } else {
        ekf.add(i + 1, InverseRangeBearing{}, readings[i], r);
        ref.add(InverseRangeBearing{}, readings[i], r.covariance());
      }
    }
    ekf.predict(Vec<2>(1.0, 0.1), 0.5, Gaussian<2>::sigmas(Vec<2>(0.1, 0.05)));
    ref.predict(Vec<2>(1.0, 0.1), 0.5, Mat<2, 2>(Vec<2>(0.01, 0.0025).asDiagonal()));
    for (const Id id : {1, 3}) {
      const Vec<2> z = RangeBearing{}(ekf.robotMean(), ekf.template landmarkMean<Point2>(id)) + Vec<2>(0.03, -0.01);
      const int offset = ekf.slot(id).offset;
      ekf.update(RangeBearing{}, id, z, r);
      ref.update(RangeBearing{}, offset, z, r.covariance());
    }
  }
};

template <typename Filter>
void requireSame(const Filter& ekf, const Reference& ref, double tol = 1e-9) {
  REQUIRE(ekf.dim() == ref.dim());
  Eigen::VectorXd dx = ekf.mean() - ref.x;
  dx[2] = wrapAngle(dx[2]);
  CHECK(dx.cwiseAbs().maxCoeff() < tol);
  CHECK((ekf.covariance() - ref.P).cwiseAbs().maxCoeff() < tol * std::max(1.0, ref.P.cwiseAbs().maxCoeff()));
}

}  // namespace

TEMPLATE_TEST_CASE("constrain equals the dense update with H on two landmark blocks", "[filter]",
                   (Ekf<Unicycle2D, Point2, InverseDistance2>), (JosephEkf<Unicycle2D, Point2, InverseDistance2>)) {
  Scene<TestType> scene;
  auto& ekf = scene.ekf;
  // A point (1) and an inverse-distance landmark (4), two rows of arbitrary Jacobians.
  Mat<2, 2> J_a;
  J_a << 1.0, -0.5, 0.2, 1.5;
  Mat<2, 4> J_b;
  J_b << 0.3, -1.0, 0.7, 2.0, -0.4, 0.1, 1.2, -0.8;
  const Vec<2> nu(0.12, -0.07);
  const auto noise = Gaussian<2>::sigmas(Vec<2>(0.05, 0.02));
  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(2, ekf.dim());
  H.block(0, ekf.slot(1).offset, 2, 2) = J_a;
  H.block(0, ekf.slot(4).offset, 2, 4) = J_b;
  ekf.template constrain<Point2, InverseDistance2>(1, 4, nu, J_a, J_b, noise);
  scene.ref.updateLinear(H, nu, noise.covariance());
  requireSame(ekf, scene.ref);
}

TEST_CASE("a landmark mapped twice, merged by constrain and remove", "[filter]") {
  Scene<Ekf<Unicycle2D, Point2, InverseDistance2>> scene;
  auto& ekf = scene.ekf;
  // 1 and 5 stand for the same point: their difference is fused as zero with a noise of 1 mm.
  const Vec<2> d = ekf.landmarkMean<Point2>(1) - ekf.landmarkMean<Point2>(5);
  const Mat<2, 2> C = ekf.landmarkCovariance<Point2>(1) + ekf.landmarkCovariance<Point2>(5) -
                      ekf.landmarkCrossCovariance<Point2, Point2>(1, 5) -
                      ekf.landmarkCrossCovariance<Point2, Point2>(5, 1);
  // The fused point by hand: l1 + K (0 - d), K = (P_11 - P_15) C^-1 (R neglected below 1e-5).
  const Mat<2, 2> K = (ekf.landmarkCovariance<Point2>(1) - ekf.landmarkCrossCovariance<Point2, Point2>(1, 5)) *
                      C.inverse();
  const Vec<2> fused = ekf.landmarkMean<Point2>(1) - K * d;
  const int offset_5 = ekf.slot(5).offset;
  ekf.constrain<Point2, Point2>(1, 5, Vec<2>(-d), Mat<2, 2>::Identity(), Mat<2, 2>(-Mat<2, 2>::Identity()),
                                Gaussian<2>::sigmas(Vec<2>::Constant(1e-3)));
  ekf.remove(5);
  CHECK((ekf.landmarkMean<Point2>(1) - fused).norm() < 1e-5);
  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(2, scene.ref.dim());
  H.block(0, ekf.slot(1).offset, 2, 2).setIdentity();
  H.block(0, offset_5, 2, 2) = -Mat<2, 2>::Identity();
  scene.ref.updateLinear(H, -d, Mat<2, 2>::Identity() * 1e-6);
  scene.ref.remove(offset_5, 2);
  requireSame(ekf, scene.ref, 1e-8);
  CHECK_FALSE(ekf.contains(5));
  CHECK(ekf.landmarkCount() == 4);
}

TEST_CASE("constrain refuses bad input and leaves the filter unchanged", "[filter][errors]") {
  Scene<Ekf<Unicycle2D, Point2, InverseDistance2>> scene;
  auto& ekf = scene.ekf;
  const Mat<2, 2> I = Mat<2, 2>::Identity();
  const auto noise = Gaussian<2>::sigmas(Vec<2>::Constant(1e-3));
  const Vec<2> nu(0.1, 0.1);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  requireRejected(ekf, ErrorCode::kInvalidArgument, "given twice",
                  [&] { ekf.constrain<Point2, Point2>(1, 1, nu, I, Mat<2, 2>(-I), noise); });
  requireRejected(ekf, ErrorCode::kUnknownId, "",
                  [&] { ekf.constrain<Point2, Point2>(1, 42, nu, I, Mat<2, 2>(-I), noise); });
  requireRejected(ekf, ErrorCode::kWrongLandmarkType, "not a Point2",
                  [&] { ekf.constrain<Point2, Point2>(1, 2, nu, I, Mat<2, 2>(-I), noise); });
  requireRejected(ekf, ErrorCode::kNonFinite, "not finite",
                  [&] { ekf.constrain<Point2, Point2>(1, 3, Vec<2>(nan, 0.0), I, Mat<2, 2>(-I), noise); });
  requireRejected(ekf, ErrorCode::kNonFinite, "not finite",
                  [&] { ekf.constrain<Point2, Point2>(1, 3, nu, Mat<2, 2>::Constant(nan), Mat<2, 2>(-I), noise); });
  // J_b = 0 and an overflowing J_a: S is not finite.
  requireRejected(ekf, ErrorCode::kNotPositiveDefinite, "not positive definite", [&] {
    ekf.constrain<Point2, Point2>(1, 3, nu, Mat<2, 2>(I * 1e300), Mat<2, 2>::Zero(), noise);
  });
}

TEST_CASE("constrain is refused by the compressed EKF", "[filter][errors]") {
  using Filter = Ekf<Unicycle2D, Point2, InverseDistance2>;
  Scene<Filter> scene;
  auto& ekf = scene.ekf;
  ekf.setCompression(Filter::withinRadius(100.0));
  const Mat<2, 2> I = Mat<2, 2>::Identity();
  requireRejected(ekf, ErrorCode::kInvalidArgument, "compressed", [&] {
    ekf.constrain<Point2, Point2>(1, 3, Vec<2>(0.1, 0.1), I, Mat<2, 2>(-I), Gaussian<2>::sigmas(Vec<2>::Constant(1e-3)));
  });
}

}  // namespace unity_filter_constrain
