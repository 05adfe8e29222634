// Automatic and numeric differentiation adapters give the analytic signature to a model
// that only has predict<T>, and the filter uses autodiff for such a model on its own.

#include <sylva/sylva.hpp>
#include <sylva/testing/check_jacobians.hpp>

#include "sylva_catch.hpp"

using namespace sylva;

namespace {
/// RangeBearing without its analytic operator(): only the Scalar-generic prediction.
struct PredictOnlyRangeBearing {
  using Robot = Unicycle2D;
  using Landmark = Point2;
  static constexpr int kDim = 2;
  static constexpr const char* kName = "PredictOnlyRangeBearing";
  template <typename T>
  Vec<2, T> predict(const Vec<3, T>& x, const Vec<2, T>& l) const {
    return RangeBearing{}.predict<T>(x, l);
  }
  Vec<2> residual(const Vec<2>& z, const Vec<2>& z_hat) const { return RangeBearing{}.residual(z, z_hat); }
};
}  // namespace

TEST_CASE("model traits detect what a model provides", "[diff]") {
  STATIC_REQUIRE(detail::HasAnalyticJacobians<RangeBearing>::value);
  STATIC_REQUIRE_FALSE(detail::HasAnalyticJacobians<PredictOnlyRangeBearing>::value);
  STATIC_REQUIRE(detail::HasAnalyticJacobians<AutoDiff<PredictOnlyRangeBearing>>::value);
  STATIC_REQUIRE(detail::HasAnalyticJacobians<NumericDiff<PredictOnlyRangeBearing>>::value);
  STATIC_REQUIRE(detail::HasResidual<RangeBearing>::value);
  STATIC_REQUIRE(detail::HasNormalize<Unicycle2D>::value);
  STATIC_REQUIRE_FALSE(detail::HasNormalize<Point2>::value);
}

TEST_CASE("autodiff and numeric Jacobians agree with the analytic ones", "[diff][jacobian]") {
  const Vec<3> x(1.0, -2.0, 2.5);
  const Vec<2> l(-4.0, 3.0);
  Mat<2, 3> J_x, A_x, N_x;
  Mat<2, 2> J_l, A_l, N_l;
  const Vec<2> z = RangeBearing{}(x, l, J_x, J_l);
  const Vec<2> za = AutoDiff<PredictOnlyRangeBearing>{}(x, l, A_x, A_l);
  const Vec<2> zn = NumericDiff<PredictOnlyRangeBearing>{}(x, l, N_x, N_l);
  CHECK(za == z);
  CHECK(zn == z);
  CHECK((A_x - J_x).norm() < 1e-14);
  CHECK((A_l - J_l).norm() < 1e-14);
  CHECK((N_x - J_x).norm() < 1e-8);
  CHECK((N_l - J_l).norm() < 1e-8);
  // Skipped Jacobians are not computed and do not disturb the prediction.
  CHECK(AutoDiff<PredictOnlyRangeBearing>{}(x, l) == z);
}

TEST_CASE("the filter differentiates a predict-only model automatically", "[diff][filter]") {
  const auto r = Gaussian<2>::sigmas(Vec<2>(0.1, 0.02));
  Ekf<Unicycle2D, Point2> analytic(Vec<3>(0.0, 0.0, 0.2), Mat<3, 3>::Identity() * 0.01);
  analytic.add(1, InverseRangeBearing{}, Vec<2>(5.0, 0.3), r);
  auto automatic = analytic;
  analytic.update(RangeBearing{}, 1, Vec<2>(5.2, 0.28), r);
  automatic.update(PredictOnlyRangeBearing{}, 1, Vec<2>(5.2, 0.28), r);
  CHECK((analytic.mean() - automatic.mean()).norm() < 1e-13);
  CHECK((analytic.covariance() - automatic.covariance()).norm() < 1e-13);
}
