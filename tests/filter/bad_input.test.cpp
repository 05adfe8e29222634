// Every public operation that receives bad input throws sylva::Error with the right code
// and a message naming the problem, and leaves the filter bit-identical.

#include <limits>

#include <sylva/sylva.hpp>

#include "filter/test_models.hpp"
#include "error_helpers.hpp"
#include "filter_snapshot.hpp"
#include "sylva_catch.hpp"

// Own namespace: the tests of a folder are compiled as one unity translation unit.
namespace unity_filter_bad_input {

using namespace sylva;
using sylva_test::InverseDistance2;
using sylva_test::InverseDistanceFromRangeBearing;
using sylva_test::PointToInverseDistance;

namespace {

using Filter = Ekf<Unicycle2D, Point2, InverseDistance2>;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

using sylva_test::requireRejected;
using sylva_test::Snapshot;

Filter makeFilter() {
  Filter ekf(Vec<3>(1.0, 2.0, 0.3), Mat<3, 3>(Vec<3>(0.01, 0.02, 0.003).asDiagonal()));
  const auto r = Gaussian<2>::sigmas(Vec<2>(0.1, 0.02));
  ekf.add(1, InverseRangeBearing{}, Vec<2>(4.0, 0.5), r);
  ekf.add(2, InverseDistanceFromRangeBearing{}, Vec<2>(7.0, -0.5), r);
  ekf.add(3, InverseRangeBearing{}, Vec<2>(3.0, -1.5), r);
  ekf.update(RangeBearing{}, 1, Vec<2>(4.1, 0.49), r);
  return ekf;
}

/// A 1D "sensor" reading 1e6 * x_robot: any negative round-off in P_xx is magnified.
struct AmplifiedX {
  using Robot = Unicycle2D;
  using Landmark = Point2;
  static constexpr int kDim = 1;
  static constexpr const char* kName = "AmplifiedX";
  template <typename T>
  Vec<1, T> predict(const Vec<3, T>& x, const Vec<2, T>& /*l*/) const {
    return Vec<1, T>(T(1e6) * x[0]);
  }
};

}  // namespace

TEST_CASE("update rejects bad observations and leaves the filter unchanged", "[filter][errors]") {
  Filter ekf = makeFilter();
  const auto r = Gaussian<2>::sigmas(Vec<2>(0.1, 0.02));
  requireRejected(ekf, ErrorCode::kNonFinite, "not finite",
                  [&] { ekf.update(RangeBearing{}, 1, Vec<2>(kNaN, 0.1), r); });
  requireRejected(ekf, ErrorCode::kNonFinite, "not finite",
                  [&] { ekf.update(RangeBearing{}, 1, Vec<2>(4.0, kInf), r); });
  requireRejected(ekf, ErrorCode::kUnknownId, "id 42",
                  [&] { ekf.update(RangeBearing{}, 42, Vec<2>(4.0, 0.1), r); });
  requireRejected(ekf, ErrorCode::kWrongLandmarkType, "InverseDistance2, not a Point2",
                  [&] { ekf.update(RangeBearing{}, 2, Vec<2>(4.0, 0.1), r); });
}

TEST_CASE("update rejects degenerate geometry", "[filter][errors]") {
  // A landmark exactly at the robot position has no bearing.
  Filter ekf(Vec<3>(0.0, 0.0, 0.0), Mat<3, 3>::Identity() * 0.01);
  const auto r = Gaussian<2>::sigmas(Vec<2>(0.1, 0.02));
  ekf.add(1, InverseRangeBearing{}, Vec<2>(2.0, 0.0), r);
  ekf.predict(Vec<2>(2.0, 0.0), 1.0, Gaussian<2>::sigmas(Vec<2>(0.01, 0.01)));  // drive onto it
  REQUIRE((ekf.robotMean().head<2>() - ekf.landmarkMean<Point2>(1)).norm() < 1e-12);
  requireRejected(ekf, ErrorCode::kDegenerateGeometry, "coincides with the robot",
                  [&] { ekf.update(RangeBearing{}, 1, Vec<2>(0.1, 0.0), r); });
  requireRejected(ekf, ErrorCode::kDegenerateGeometry, "coincides with the robot",
                  [&] { (void)ekf.innovation(RangeBearing{}, 1, Vec<2>(0.1, 0.0), r); });
}

TEST_CASE("update rejects an innovation covariance that is not positive definite", "[filter][errors]") {
  // P0 is accepted as positive semi-definite up to round-off (-1e-13), but the amplified
  // sensor turns that round-off into S = 1e12 * (-1e-13) + 0.01 < 0.
  Mat<3, 3> P0 = Mat<3, 3>::Zero();
  P0(0, 0) = -1e-13;
  Ekf<Unicycle2D, Point2> ekf(Vec<3>::Zero(), P0);
  ekf.add(1, InverseRangeBearing{}, Vec<2>(2.0, 0.0), Gaussian<2>::sigmas(Vec<2>(0.1, 0.02)));
  requireRejected(ekf, ErrorCode::kNotPositiveDefinite, "not positive definite",
                  [&] { ekf.update(AmplifiedX{}, 1, Vec<1>(0.0), Gaussian<1>::sigmas(Vec<1>(0.1))); });
}

TEST_CASE("a batch with one bad observation is rejected whole", "[filter][errors]") {
  Filter ekf = makeFilter();
  const auto r = Gaussian<2>::sigmas(Vec<2>(0.1, 0.02));
  std::vector<Observation<RangeBearing>> batch{{1, Vec<2>(4.0, 0.5), r}, {3, Vec<2>(kNaN, 0.0), r}};
  requireRejected(ekf, ErrorCode::kNonFinite, "measurement 1", [&] { ekf.update(RangeBearing{}, batch); });
  batch[1] = {99, Vec<2>(3.0, -1.5), r};
  requireRejected(ekf, ErrorCode::kUnknownId, "id 99", [&] { ekf.update(RangeBearing{}, batch); });
  batch[1] = {2, Vec<2>(3.0, -1.5), r};
  requireRejected(ekf, ErrorCode::kWrongLandmarkType, "not a Point2", [&] { ekf.update(RangeBearing{}, batch); });
}

TEST_CASE("predict rejects bad time steps and controls", "[filter][errors]") {
  Filter ekf = makeFilter();
  const auto q = Gaussian<2>::sigmas(Vec<2>(0.1, 0.05));
  requireRejected(ekf, ErrorCode::kNegativeTimeStep, "dt = -0.1 s is negative",
                  [&] { ekf.predict(Vec<2>(1.0, 0.0), -0.1, q); });
  requireRejected(ekf, ErrorCode::kNonFinite, "dt is not finite",
                  [&] { ekf.predict(Vec<2>(1.0, 0.0), kNaN, q); });
  requireRejected(ekf, ErrorCode::kNonFinite, "control is not finite",
                  [&] { ekf.predict(Vec<2>(kNaN, 0.0), 0.1, q); });
  // dt = 0 is allowed and changes nothing but adds no noise either.
  const Snapshot before(ekf);
  ekf.predict(Vec<2>(1.0, 0.5), 0.0, q);
  CHECK(Snapshot(ekf) == before);
}

TEST_CASE("add, remove and reparametrize reject bad input", "[filter][errors]") {
  Filter ekf = makeFilter();
  const auto r = Gaussian<2>::sigmas(Vec<2>(0.1, 0.02));
  requireRejected(ekf, ErrorCode::kDuplicateId, "id 1 already exists",
                  [&] { ekf.add(1, InverseRangeBearing{}, Vec<2>(4.0, 0.5), r); });
  requireRejected(ekf, ErrorCode::kNonFinite, "not finite",
                  [&] { ekf.add(9, InverseRangeBearing{}, Vec<2>(kNaN, 0.5), r); });
  requireRejected(ekf, ErrorCode::kDegenerateGeometry, "must be > 0",
                  [&] { ekf.add(9, InverseRangeBearing{}, Vec<2>(0.0, 0.5), r); });
  requireRejected(ekf, ErrorCode::kUnknownId, "id 77", [&] { ekf.remove(77); });
  requireRejected(ekf, ErrorCode::kWrongLandmarkType, "InverseDistance2, not a Point2",
                  [&] { ekf.reparametrize(2, PointToInverseDistance{}); });
  requireRejected(ekf, ErrorCode::kUnknownId, "id 77",
                  [&] { ekf.reparametrize(77, PointToInverseDistance{}); });
  // A point at the robot position has no anchored bearing: the conversion is not finite.
  Filter at_robot(Vec<3>::Zero(), Mat<3, 3>::Identity() * 0.01);
  at_robot.add(5, InverseRangeBearing{}, Vec<2>(1.0, 0.0), r);
  at_robot.predict(Vec<2>(1.0, 0.0), 1.0, Gaussian<2>::sigmas(Vec<2>(0.01, 0.01)));
  requireRejected(at_robot, ErrorCode::kNonFinite, "conversion is not finite",
                  [&] { at_robot.reparametrize(5, PointToInverseDistance{}); });
}

TEST_CASE("typed access checks id and type", "[filter][errors]") {
  Filter ekf = makeFilter();
  requireRejected(ekf, ErrorCode::kWrongLandmarkType, "landmark 1 is a Point2, not a InverseDistance2",
                  [&] { (void)ekf.landmarkMean<InverseDistance2>(1); });
  requireRejected(ekf, ErrorCode::kUnknownId, "id 5", [&] { (void)ekf.landmarkCovariance<Point2>(5); });
  CHECK_FALSE(ekf.holds<Point2>(2));
  CHECK_FALSE(ekf.holds<Point2>(5));
}

TEST_CASE("construction validates the prior and the noise", "[filter][errors]") {
  using Catch::Matchers::Contains;
  CHECK_THROWS_WITH((Ekf<Unicycle2D, Point2>(Vec<3>(kNaN, 0, 0), Mat<3, 3>::Identity())),
                    Contains("initial robot state is not finite"));
  Mat<3, 3> not_psd = Mat<3, 3>::Identity();
  not_psd(0, 0) = -1.0;
  CHECK_THROWS_WITH((Ekf<Unicycle2D, Point2>(Vec<3>::Zero(), not_psd)), Contains("not positive semi-definite"));
  // Semi-definite priors are valid (a pose known exactly, a rank-one spread); an indefinite
  // one is refused even with a positive diagonal or a zero one, and the tolerance is 1e-12 of
  // the largest entry.
  const Vec<3> v(1.0, -2.0, 0.5);
  CHECK_NOTHROW(Ekf<Unicycle2D, Point2>(Vec<3>::Zero(), Mat<3, 3>::Zero()));
  CHECK_NOTHROW(Ekf<Unicycle2D, Point2>(Vec<3>::Zero(), Mat<3, 3>(v * v.transpose())));
  Mat<3, 3> positive_diagonal = Mat<3, 3>::Identity();
  positive_diagonal(0, 1) = positive_diagonal(1, 0) = 1.5;  // eigenvalues 2.5, 1, -0.5
  CHECK_THROWS_WITH((Ekf<Unicycle2D, Point2>(Vec<3>::Zero(), positive_diagonal)), Contains("not positive semi-definite"));
  Mat<3, 3> zero_diagonal = Mat<3, 3>::Zero();
  zero_diagonal(0, 1) = zero_diagonal(1, 0) = 1.0;  // eigenvalues 1, 0, -1
  CHECK_THROWS_WITH((Ekf<Unicycle2D, Point2>(Vec<3>::Zero(), zero_diagonal)), Contains("not positive semi-definite"));
  Mat<3, 3> slightly_negative = 4.0 * Mat<3, 3>::Identity();
  slightly_negative(2, 2) = -1e-13;  // within 1e-12 of the largest entry, 4
  CHECK_NOTHROW(Ekf<Unicycle2D, Point2>(Vec<3>::Zero(), slightly_negative));
  slightly_negative(2, 2) = -1e-10;
  CHECK_THROWS_WITH((Ekf<Unicycle2D, Point2>(Vec<3>::Zero(), slightly_negative)), Contains("not positive semi-definite"));
  Mat<3, 3> asymmetric = Mat<3, 3>::Identity();
  asymmetric(0, 1) = 0.5;
  CHECK_THROWS_WITH((Ekf<Unicycle2D, Point2>(Vec<3>::Zero(), asymmetric)), Contains("not symmetric"));

  CHECK_THROWS_WITH(Gaussian<2>::sigmas(Vec<2>(0.1, -0.1)), Contains("sigma[1] = -0.1"));
  CHECK_THROWS_WITH(Gaussian<2>::sigmas(Vec<2>(0.0, 0.1)), Contains("sigma[0] = 0"));
  CHECK_THROWS_WITH(Gaussian<2>::sigmas(Vec<2>(kNaN, 0.1)), Contains("non-finite"));
  CHECK_THROWS_WITH(Gaussian<2>::sigmas(Vec<2>(1e-200, 0.1)), Contains("under- or overflows"));
  Mat<2, 2> cov;
  cov << 1.0, 2.0, 2.0, 1.0;  // symmetric, eigenvalues 3 and -1
  CHECK_THROWS_WITH(Gaussian<2>::covariance(cov), Contains("not positive definite"));
  cov << 1.0, 0.2, 0.1, 1.0;
  CHECK_THROWS_WITH(Gaussian<2>::covariance(cov), Contains("not symmetric"));
  CHECK(Gaussian<2>::variances(Vec<2>(4.0, 9.0)).covariance() == Mat<2, 2>(Vec<2>(4.0, 9.0).asDiagonal()));
  // A variance is named as the variance the caller passed, with the code of what is wrong.
  CHECK_THROWS_WITH(Gaussian<2>::variances(Vec<2>(-1.0, 1.0)), Contains("variance[0] = -1 must be finite and > 0"));
  CHECK(sylva_test::throwsCode([] { Gaussian<2>::variances(Vec<2>(-1.0, 1.0)); }, ErrorCode::kNotPositiveDefinite));
  CHECK(sylva_test::throwsCode([] { Gaussian<2>::variances(Vec<2>(1.0, kInf)); }, ErrorCode::kNonFinite));
}

TEST_CASE("finite inputs whose products overflow are refused before the filter changes", "[filter][errors]") {
  Filter ekf = makeFilter();
  // The predict noise term G Q G^T overflows: a speed noise of 1e150 m/s (its variance 1e300
  // is finite) over a step of 1e6 s.
  requireRejected(ekf, ErrorCode::kNonFinite, "not finite",
                  [&] { ekf.predict(Vec<2>(1.0, 0.0), 1e6, Gaussian<2>::sigmas(Vec<2>(1e150, 0.05))); });
  // The new block of add: a range of 1e160 m puts 1e320 into J P J^T.
  requireRejected(ekf, ErrorCode::kNonFinite, "not finite", [&] {
    ekf.add(9, InverseRangeBearing{}, Vec<2>(1e160, 0.5), Gaussian<2>::sigmas(Vec<2>(0.1, 0.02)));
  });
}

TEST_CASE("innovation refuses an innovation covariance that is not positive definite", "[filter][errors]") {
  Mat<3, 3> P0 = Mat<3, 3>::Zero();
  P0(0, 0) = -1e-13;
  Ekf<Unicycle2D, Point2> ekf(Vec<3>::Zero(), P0);
  ekf.add(1, InverseRangeBearing{}, Vec<2>(2.0, 0.0), Gaussian<2>::sigmas(Vec<2>(0.1, 0.02)));
  // S = 1e12 * (-1e-13) + 0.01 < 0: a gate would read a negative NIS as a perfect match.
  requireRejected(ekf, ErrorCode::kNotPositiveDefinite, "not positive definite",
                  [&] { ekf.innovation(AmplifiedX{}, 1, Vec<1>(0.0), Gaussian<1>::sigmas(Vec<1>(0.1))); });
  Innovation<1> bad{Vec<1>(1.0), Mat<1, 1>(-0.5)};
  CHECK(sylva_test::throwsCode([&] { (void)bad.nis(); }, ErrorCode::kNotPositiveDefinite));
}

}  // namespace unity_filter_bad_input
