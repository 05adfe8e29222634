// The filter against the textbook dense EKF (sylva::testing::DenseReferenceEkf): predict,
// single and batched updates, add, remove and reparametrize, for both covariance update
// forms and for two landmark parametrizations side by side.

#include <random>
#include <string>
#include <type_traits>

#include <Eigen/Eigenvalues>
#include <sylva/sylva.hpp>
#include <sylva/testing/dense_reference_ekf.hpp>

#include "filter/test_models.hpp"
#include "sylva_catch.hpp"

// Own namespace: the tests of a folder are compiled as one unity translation unit.
namespace unity_filter_ekf {

using namespace sylva;
using sylva_test::InverseDistance2;
using sylva_test::InverseDistanceFromRangeBearing;
using sylva_test::InverseDistanceToPoint;
using sylva_test::PointToInverseDistance;
using sylva_test::RangeBearingToInverseDistance;

namespace {

using Reference = testing::DenseReferenceEkf<Unicycle2D>;

double maxAbs(const Eigen::MatrixXd& a) { return a.size() == 0 ? 0.0 : a.cwiseAbs().maxCoeff(); }

/// Asserts filter == reference: mean to `tol`, covariance to `tol` relative to its scale.
template <typename Filter>
void requireSame(const Filter& ekf, const Reference& ref, double tol = 1e-9) {
  REQUIRE(ekf.dim() == ref.dim());
  Eigen::VectorXd dx = ekf.mean() - ref.x;
  dx[2] = wrapAngle(dx[2]);
  const double scale = std::max(1.0, maxAbs(ref.P));
  CHECK(maxAbs(dx) < tol);
  CHECK(maxAbs(ekf.covariance() - ref.P) < tol * scale);
}

/// Finite and PSD to round-off (covariance() mirrors the stored lower triangle, so it is
/// symmetric by construction and that needs no check).
void requirePsd(const Eigen::MatrixXd& P) {
  REQUIRE(P.allFinite());
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(P, Eigen::EigenvaluesOnly);
  CHECK(eig.eigenvalues().minCoeff() > -1e-10 * std::max(1.0, maxAbs(P)));
}

struct Problem {
  std::mt19937_64 rng;
  explicit Problem(unsigned seed) : rng(seed) {}
  double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); }
  Vec<2> rangeBearing() { return Vec<2>(uniform(2.0, 15.0), uniform(-3.0, 3.0)); }
};

template <typename Filter>
void addRandomLandmarks(Filter& ekf, Reference& ref, Problem& p, int count, const Gaussian<2>& noise) {
  for (int i = 0; i < count; ++i) {
    const Vec<2> z = p.rangeBearing();
    if (i % 3 == 2) {
      ekf.add(100 + i, InverseDistanceFromRangeBearing{}, z, noise);
      ref.add(InverseDistanceFromRangeBearing{}, z, noise.covariance());
    } else {
      ekf.add(100 + i, InverseRangeBearing{}, z, noise);
      ref.add(InverseRangeBearing{}, z, noise.covariance());
    }
  }
}

template <typename Filter>
void runRandomProblem(unsigned seed, int landmarks) {
  Problem p(seed);
  const Vec<3> x0(p.uniform(-5, 5), p.uniform(-5, 5), p.uniform(-3, 3));
  Mat<3, 3> A = Mat<3, 3>::Random() * 0.1;
  const Mat<3, 3> P0 = A * A.transpose() + 0.01 * Mat<3, 3>::Identity();
  Filter ekf(x0, P0);
  Reference ref{Unicycle2D{}, x0, P0};
  const auto r = Gaussian<2>::sigmas(Vec<2>(0.1, 0.02));
  const auto q = Gaussian<2>::sigmas(Vec<2>(0.1, 0.05));
  addRandomLandmarks(ekf, ref, p, landmarks, r);
  requireSame(ekf, ref);

  for (int step = 0; step < 5; ++step) {
    const Vec<2> u(p.uniform(0.0, 2.0), p.uniform(-0.5, 0.5));
    ekf.predict(u, 0.2, q);
    ref.predict(u, 0.2, q.covariance());
    requireSame(ekf, ref);
    // A single update of every third landmark, through the analytic or the autodiff model.
    for (int i = step % 3; i < landmarks; i += 3) {
      const Id id = 100 + i;
      const int offset = ekf.slot(id).offset;
      const Vec<2> noise_offset(p.uniform(-0.2, 0.2), p.uniform(-0.05, 0.05));
      if (ekf.template holds<Point2>(id)) {
        const Vec<2> z = RangeBearing{}(ekf.robotMean(), ekf.template landmarkMean<Point2>(id)) + noise_offset;
        ekf.update(RangeBearing{}, id, z, r);
        ref.update(RangeBearing{}, offset, z, r.covariance());
      } else {
        const Vec<2> z = RangeBearingToInverseDistance{}.predict<double>(
                             ekf.robotMean(), ekf.template landmarkMean<InverseDistance2>(id)) +
                         noise_offset;
        ekf.update(RangeBearingToInverseDistance{}, id, z, r);
        ref.update(RangeBearingToInverseDistance{}, offset, z, r.covariance());
      }
      requireSame(ekf, ref);
    }
  }
  requirePsd(ekf.covariance());
}

}  // namespace

TEST_CASE("update, predict and add equal the dense textbook EKF", "[filter]") {
  for (unsigned seed : {1u, 2u, 3u}) {
    for (int landmarks : {1, 4, 13}) {
      INFO("seed " << seed << ", landmarks " << landmarks);
      runRandomProblem<Ekf<Unicycle2D, Point2, InverseDistance2>>(seed, landmarks);
      runRandomProblem<JosephEkf<Unicycle2D, Point2, InverseDistance2>>(seed, landmarks);
    }
  }
}

TEMPLATE_TEST_CASE("batched update equals the dense update with stacked H", "[filter]",
                   (Ekf<Unicycle2D, Point2>), (JosephEkf<Unicycle2D, Point2>)) {
  Problem p(7);
  const Vec<3> x0(1.0, -2.0, 0.3);
  const Mat<3, 3> P0 = Vec<3>(0.04, 0.09, 0.01).asDiagonal();
  TestType ekf(x0, P0);
  Reference ref{Unicycle2D{}, x0, P0};
  const auto r = Gaussian<2>::sigmas(Vec<2>(0.1, 0.02));
  for (int i = 0; i < 8; ++i) {
    const Vec<2> z = p.rangeBearing();
    ekf.add(i, InverseRangeBearing{}, z, r);
    ref.add(InverseRangeBearing{}, z, r.covariance());
  }
  ekf.predict(Vec<2>(1.0, 0.2), 0.5, Gaussian<2>::sigmas(Vec<2>(0.2, 0.1)));
  ref.predict(Vec<2>(1.0, 0.2), 0.5, Gaussian<2>::sigmas(Vec<2>(0.2, 0.1)).covariance());

  std::vector<Observation<RangeBearing>> batch;
  Eigen::MatrixXd H(0, ref.dim());
  Eigen::VectorXd nu(0);
  for (Id id : {1, 3, 4, 6}) {
    const int offset = ekf.slot(id).offset;
    Vec<2> z_hat;
    const Eigen::MatrixXd H_i = ref.jacobian(RangeBearing{}, offset, &z_hat);
    const Vec<2> z = z_hat + Vec<2>(p.uniform(-0.3, 0.3), p.uniform(-0.05, 0.05));
    batch.push_back({id, z, r});
    H.conservativeResize(H.rows() + 2, Eigen::NoChange);
    H.bottomRows(2) = H_i;
    nu.conservativeResize(nu.size() + 2);
    nu.tail(2) = RangeBearing{}.residual(z, z_hat);
  }
  Eigen::MatrixXd R = Eigen::MatrixXd::Zero(H.rows(), H.rows());
  for (int i = 0; i < H.rows() / 2; ++i) R.block(2 * i, 2 * i, 2, 2) = r.covariance();
  ekf.update(RangeBearing{}, batch);
  ref.updateLinear(H, nu, R);
  requireSame(ekf, ref);
  requirePsd(ekf.covariance());
}

TEST_CASE("remove and reparametrize equal the dense reference", "[filter]") {
  Problem p(11);
  const Vec<3> x0(0.5, 0.5, 0.1);
  const Mat<3, 3> P0 = Vec<3>(0.02, 0.03, 0.005).asDiagonal();
  Ekf<Unicycle2D, Point2, InverseDistance2> ekf(x0, P0);
  Reference ref{Unicycle2D{}, x0, P0};
  const auto r = Gaussian<2>::sigmas(Vec<2>(0.1, 0.02));
  addRandomLandmarks(ekf, ref, p, 9, r);
  for (int i = 0; i < 9; ++i) {  // correlate everything
    const Id id = 100 + i;
    const int offset = ekf.slot(id).offset;
    if (ekf.holds<Point2>(id)) {
      const Vec<2> z = RangeBearing{}(ekf.robotMean(), ekf.landmarkMean<Point2>(id)) + Vec<2>(0.05, -0.01);
      ekf.update(RangeBearing{}, id, z, r);
      ref.update(RangeBearing{}, offset, z, r.covariance());
    }
  }
  requireSame(ekf, ref);

  SECTION("remove the first, a middle and the last landmark") {
    for (Id id : {100, 104, 108}) {
      const LandmarkSlot s = ekf.slot(id);
      ekf.remove(id);
      ref.remove(s.offset, s.dim);
      requireSame(ekf, ref);
      CHECK_FALSE(ekf.contains(id));
    }
    CHECK(ekf.landmarkCount() == 6);
    requirePsd(ekf.covariance());
    // The remaining slots are contiguous and in order.
    int offset = Unicycle2D::kDim;
    for (const LandmarkSlot& s : ekf.slots()) {
      CHECK(s.offset == offset);
      offset += s.dim;
    }
  }

  SECTION("inverse distance -> point and point -> inverse distance") {
    // 102 is an InverseDistance2 (every third), 103 a Point2.
    REQUIRE(ekf.holds<InverseDistance2>(102));
    REQUIRE(ekf.holds<Point2>(103));
    LandmarkSlot s = ekf.slot(102);
    ekf.reparametrize(102, InverseDistanceToPoint{});
    ref.reparametrize(s.offset, InverseDistanceToPoint{});
    requireSame(ekf, ref);
    CHECK(ekf.holds<Point2>(102));
    s = ekf.slot(103);
    ekf.reparametrize(103, PointToInverseDistance{});
    ref.reparametrize(s.offset, PointToInverseDistance{});
    requireSame(ekf, ref);
    CHECK(ekf.holds<InverseDistance2>(103));
    requirePsd(ekf.covariance());
    // The reparametrized landmarks still update like the reference.
    for (Id id : {102, 103}) {
      const int offset = ekf.slot(id).offset;
      if (ekf.holds<Point2>(id)) {
        const Vec<2> z = RangeBearing{}(ekf.robotMean(), ekf.landmarkMean<Point2>(id)) + Vec<2>(0.1, 0.02);
        ekf.update(RangeBearing{}, id, z, r);
        ref.update(RangeBearing{}, offset, z, r.covariance());
      } else {
        const Vec<2> z = RangeBearingToInverseDistance{}.predict<double>(
                             ekf.robotMean(), ekf.landmarkMean<InverseDistance2>(id)) +
                         Vec<2>(0.1, 0.02);
        ekf.update(RangeBearingToInverseDistance{}, id, z, r);
        ref.update(RangeBearingToInverseDistance{}, offset, z, r.covariance());
      }
      requireSame(ekf, ref);
    }
  }
}

TEST_CASE("storage grows past its capacity without changing the estimate", "[filter]") {
  Problem p(5);
  Ekf<Unicycle2D, Point2> ekf(Vec<3>::Zero(), Mat<3, 3>::Identity() * 0.01);
  Reference ref{Unicycle2D{}, Vec<3>::Zero(), Mat<3, 3>::Identity() * 0.01};
  const auto r = Gaussian<2>::sigmas(Vec<2>(0.1, 0.02));
  for (int i = 0; i < 40; ++i) {  // capacity doubles several times
    const Vec<2> z = p.rangeBearing();
    ekf.add(i, InverseRangeBearing{}, z, r);
    ref.add(InverseRangeBearing{}, z, r.covariance());
  }
  requireSame(ekf, ref);
  ekf.reserve(1000);
  requireSame(ekf, ref);
}

TEST_CASE("typed access returns the blocks of the full covariance", "[filter]") {
  Problem p(3);
  Ekf<Unicycle2D, Point2, InverseDistance2> ekf(Vec<3>(1, 2, 0.5), Mat<3, 3>::Identity() * 0.02);
  const auto r = Gaussian<2>::sigmas(Vec<2>(0.1, 0.02));
  ekf.add(7, InverseRangeBearing{}, Vec<2>(5, 0.2), r);
  ekf.add(8, InverseDistanceFromRangeBearing{}, Vec<2>(6, -0.4), r);
  ekf.update(RangeBearing{}, 7, Vec<2>(5.1, 0.21), r);
  const Eigen::MatrixXd P = ekf.covariance();
  const int o7 = ekf.slot(7).offset;
  const int o8 = ekf.slot(8).offset;
  CHECK(ekf.robotCovariance() == P.topLeftCorner<3, 3>());
  CHECK(ekf.landmarkCovariance<Point2>(7) == P.block<2, 2>(o7, o7));
  CHECK(ekf.landmarkCovariance<InverseDistance2>(8) == P.block<4, 4>(o8, o8));
  CHECK(ekf.robotLandmarkCovariance<InverseDistance2>(8) == P.block<3, 4>(0, o8));
  CHECK(ekf.landmarkMean<Point2>(7) == ekf.mean().segment<2>(o7));
  CHECK(ekf.robotMean() == ekf.mean().head<3>());
  CHECK(std::string(ekf.typeName(ekf.slot(8).type_index)) == "InverseDistance2");
  STATIC_REQUIRE(decltype(ekf)::typeIndexOf<InverseDistance2>() == 1);
  STATIC_REQUIRE(decltype(ekf)::kHolds<Point2>);
}

TEST_CASE("visit hands the callback the landmark's parametrization", "[filter]") {
  Ekf<Unicycle2D, Point2, InverseDistance2> ekf(Vec<3>(1, 2, 0.5), Mat<3, 3>::Identity() * 0.02);
  const auto r = Gaussian<2>::sigmas(Vec<2>(0.1, 0.02));
  ekf.add(7, InverseRangeBearing{}, Vec<2>(5, 0.2), r);
  ekf.add(8, InverseDistanceFromRangeBearing{}, Vec<2>(6, -0.4), r);
  // The callback sees the type: it can read the landmark's mean at the right size.
  const auto dimOf = [&](Id id) {
    return ekf.visit(id, [&](auto type) {
      using Landmark = typename decltype(type)::type;
      return static_cast<int>(ekf.landmarkMean<Landmark>(id).size());
    });
  };
  CHECK(dimOf(7) == 2);
  CHECK(dimOf(8) == 4);
  // It follows a reparametrization, and returns references as references.
  ekf.reparametrize(8, InverseDistanceToPoint{});
  CHECK(dimOf(8) == 2);
  const std::string names[] = {"point", "inverse distance"};
  const std::string& name = ekf.visit(8, [&](auto type) -> const std::string& {
    return names[std::is_same_v<typename decltype(type)::type, Point2> ? 0 : 1];
  });
  CHECK(&name == &names[0]);
  // An unknown id is refused before the callback runs.
  bool called = false;
  try {
    ekf.visit(9, [&](auto) { called = true; });
    FAIL("no error for an unknown id");
  } catch (const Error& e) {
    CHECK(e.code() == ErrorCode::kUnknownId);
  }
  CHECK_FALSE(called);
}

}  // namespace unity_filter_ekf
