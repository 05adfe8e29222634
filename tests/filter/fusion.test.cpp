// Batched and sequential fusion of a range of observations, the tiled lower-triangle rank
// update behind the batched form, and the symmetric covariance view.

#include <random>

#include <sylva/core/thread_pool.hpp>
#include <sylva/detail/lower_rank_update.hpp>
#include <sylva/filter/update_form.hpp>
#include <sylva/sylva.hpp>
#include <sylva/testing/dense_reference_ekf.hpp>

#include "error_helpers.hpp"
#include "sylva_catch.hpp"

// Own namespace: the tests of a folder are compiled as one unity translation unit.
namespace unity_filter_fusion {

using namespace sylva;

namespace {

using Filter = Ekf<Unicycle2D, Point2>;

double maxAbsDiff(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) { return (a - b).cwiseAbs().maxCoeff(); }

/// A filter with `count` landmarks around the robot, after one prediction (dense P).
Filter mapWith(int count, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> range(2.0, 30.0), bearing(-3.0, 3.0);
  Filter ekf(Vec<3>(0.5, -1.0, 0.2), Vec<3>(0.04, 0.09, 0.01).asDiagonal());
  const auto r = Gaussian<2>::sigmas(Vec<2>(0.1, 0.02));
  for (int i = 0; i < count; ++i) ekf.add(i, InverseRangeBearing{}, Vec<2>(range(rng), bearing(rng)), r);
  ekf.predict(Vec<2>(1.0, 0.2), 0.5, Gaussian<2>::sigmas(Vec<2>(0.2, 0.1)));
  return ekf;
}

/// Observations of `ids` at their prediction plus a fixed offset pattern.
std::vector<Observation<RangeBearing>> observe(const Filter& ekf, const std::vector<Id>& ids) {
  const auto r = Gaussian<2>::sigmas(Vec<2>(0.1, 0.02));
  std::vector<Observation<RangeBearing>> out;
  for (std::size_t j = 0; j < ids.size(); ++j) {
    const Vec<2> z_hat = RangeBearing{}(ekf.robotMean(), ekf.landmarkMean<Point2>(ids[j]));
    const double sign = j % 2 == 0 ? 1.0 : -1.0;
    out.push_back({ids[j], z_hat + sign * Vec<2>(0.15, 0.01), r});
  }
  return out;
}

/// RangeBearing that refuses landmarks beyond x = 1000 m (a failure found only by the update).
struct RangeBearingRefusingFar {
  using Robot = Unicycle2D;
  using Landmark = Point2;
  static constexpr int kDim = 2;
  static constexpr const char* kName = "RangeBearingRefusingFar";
  Vec<2> operator()(const Vec<3>& robot, const Vec<2>& landmark, JacobianRef<2, 3> J_z_x = {},
                    JacobianRef<2, 2> J_z_l = {}) const {
    if (landmark[0] > 1000.0) fail(ErrorCode::kDegenerateGeometry, "landmark beyond 1000 m");
    return RangeBearing{}(robot, landmark, J_z_x, J_z_l);
  }
  Vec<2> residual(const Vec<2>& z, const Vec<2>& z_hat) const { return RangeBearing{}.residual(z, z_hat); }
};

}  // namespace

TEST_CASE("the tiled lower rank update equals the dense one for every tile remainder", "[filter][fusion][slow]") {
  std::mt19937_64 rng(3);
  std::normal_distribution<double> normal;
  for (int m : {1, 2, 24, 300}) {
    for (int n : {1, 7, 255, 256, 257, 700}) {
      INFO("n = " << n << ", m = " << m << ", tile " << detail::lowerRankUpdateTile(m));
      Eigen::MatrixXd W(n, m), A(n, n);
      for (Eigen::Index i = 0; i < W.size(); ++i) W.data()[i] = normal(rng);
      for (Eigen::Index i = 0; i < A.size(); ++i) A.data()[i] = normal(rng);
      Eigen::MatrixXd P = A * A.transpose();
      const Eigen::MatrixXd expected = P - W * W.transpose();
      P.triangularView<Eigen::StrictlyUpper>().setConstant(std::nan(""));  // must not be read
      detail::subtractLowerRankUpdate(P.topLeftCorner(n, n), W);
      const Eigen::MatrixXd lower = P.triangularView<Eigen::Lower>();
      const Eigen::MatrixXd expected_lower = expected.triangularView<Eigen::Lower>();
      CHECK(maxAbsDiff(lower, expected_lower) < 1e-9 * expected.cwiseAbs().maxCoeff());
    }
  }
}

TEST_CASE("the tiled lower rank update gives the same bits on 1, 2 and 3 threads", "[filter][fusion]") {
  std::mt19937_64 rng(4);
  std::normal_distribution<double> normal;
  ThreadPool two(2), three(3);
  // Below detail::kParallelMinRows the update stays on the calling thread; above it, the
  // tiles are shared out.
  for (int m : {2, 24, 300}) {
    for (int n : {639, 640, 700, 1100}) {
      INFO("n = " << n << ", m = " << m);
      Eigen::MatrixXd W(n, m), P(n, n);
      for (Eigen::Index i = 0; i < W.size(); ++i) W.data()[i] = normal(rng);
      for (Eigen::Index i = 0; i < P.size(); ++i) P.data()[i] = normal(rng);
      Eigen::MatrixXd serial = P, on_two = P, on_three = P;
      detail::subtractLowerRankUpdate(serial, W);
      detail::subtractLowerRankUpdate(on_two, W, &two);
      detail::subtractLowerRankUpdate(on_three, W, &three);
      CHECK((on_two.array() == serial.array()).all());
      CHECK((on_three.array() == serial.array()).all());
      // The strictly upper part is left as it was.
      CHECK((serial.triangularView<Eigen::StrictlyUpper>().toDenseMatrix().array() ==
             P.triangularView<Eigen::StrictlyUpper>().toDenseMatrix().array())
                .all());
    }
  }
}

TEST_CASE("a batch's gain by a triangular solve agrees with the product with L^-1", "[filter][fusion]") {
  // SymmetricUpdate::increment forms W = P H^T L^-T one of two ways (kGainBySolve): both must
  // give the same W and mean increment to round-off, on one thread and on two.
  std::mt19937_64 rng(9);
  std::normal_distribution<double> normal;
  ThreadPool two(2);
  for (int n : {103, 700}) {
    for (int k : {2, 17, 24}) {
      INFO("n = " << n << ", k = " << k);
      Eigen::MatrixXd A(k, k), PHt(n, k);
      for (Eigen::Index i = 0; i < A.size(); ++i) A.data()[i] = normal(rng);
      for (Eigen::Index i = 0; i < PHt.size(); ++i) PHt.data()[i] = normal(rng);
      Eigen::MatrixXd S = A * A.transpose() + Eigen::MatrixXd::Identity(k, k);
      Eigen::VectorXd nu(k);
      for (Eigen::Index i = 0; i < k; ++i) nu[i] = normal(rng);
      Eigen::LLT<Eigen::Ref<Eigen::MatrixXd>> llt(S);
      REQUIRE(llt.info() == Eigen::Success);
      for (Parallel* parallel : {static_cast<Parallel*>(nullptr), static_cast<Parallel*>(&two)}) {
        detail::BatchWorkspace<> ws_product, ws_solve;
        Eigen::Map<Eigen::MatrixXd> PHt_map(PHt.data(), n, k);
        Eigen::VectorXd delta_product(n), delta_solve(n);
        const Eigen::MatrixXd W_product =
            SymmetricUpdate::increment<Eigen::Dynamic, false>(PHt_map, llt, nu, ws_product, delta_product, parallel);
        const Eigen::MatrixXd W_solve =
            SymmetricUpdate::increment<Eigen::Dynamic, true>(PHt_map, llt, nu, ws_solve, delta_solve, parallel);
        // W L^T = P H^T, whichever way W was formed.
        CHECK(maxAbsDiff(W_solve * llt.matrixU(), PHt) <= 1e-12 * PHt.cwiseAbs().maxCoeff());
        CHECK(maxAbsDiff(W_product, W_solve) <= 1e-12 * W_product.cwiseAbs().maxCoeff());
        CHECK(maxAbsDiff(delta_product, delta_solve) <= 1e-12 * delta_product.cwiseAbs().maxCoeff());
      }
    }
  }
}

TEST_CASE("batched updates with a ThreadPool give the serial filter's bits", "[filter][fusion]") {
  ThreadPool pool(2);
  const Filter start = mapWith(350, 6);  // n = 703, above detail::kParallelMinRows
  static_assert(detail::kParallelMinRows <= 703, "this test must reach the threads");
  Filter serial = start, threaded = start;
  threaded.setParallel(&pool);
  CHECK(threaded.parallel() == &pool);
  const auto q = Gaussian<2>::sigmas(Vec<2>(0.2, 0.1));
  for (int step = 0; step < 3; ++step) {
    std::vector<Id> ids;
    for (int k = 0; k < 12; ++k) ids.push_back((step * 41 + k * 29) % 350);
    serial.update(RangeBearing{}, observe(serial, ids));
    threaded.update(RangeBearing{}, observe(threaded, ids));
    serial.predict(Vec<2>(1.0, 0.1), 0.2, q);
    threaded.predict(Vec<2>(1.0, 0.1), 0.2, q);
  }
  CHECK((threaded.mean().array() == serial.mean().array()).all());
  CHECK((threaded.covariance().array() == serial.covariance().array()).all());
  // A copy shares the pool; nullptr goes back to one thread.
  Filter copy = threaded;
  CHECK(copy.parallel() == &pool);
  copy.setParallel(nullptr);
  CHECK(copy.parallel() == nullptr);
}

TEST_CASE("a batched update over many tiles equals the dense update with stacked H", "[filter][fusion][slow]") {
  Filter ekf = mapWith(350, 5);  // n = 703: several tiles in both directions
  testing::DenseReferenceEkf<Unicycle2D> ref{Unicycle2D{}, ekf.robotMean(), ekf.robotCovariance()};
  ref.x = ekf.mean();
  ref.P = ekf.covariance();
  const std::vector<Id> ids = {0, 17, 99, 100, 101, 250, 349, 3, 200, 311, 42, 128};
  const auto batch = observe(ekf, ids);
  Eigen::MatrixXd H(2 * ids.size(), ekf.dim());
  Eigen::VectorXd nu(2 * ids.size());
  Eigen::MatrixXd R = Eigen::MatrixXd::Zero(H.rows(), H.rows());
  for (std::size_t j = 0; j < ids.size(); ++j) {
    Vec<2> z_hat;
    H.middleRows(2 * j, 2) = ref.jacobian(RangeBearing{}, ekf.slot(ids[j]).offset, &z_hat);
    nu.segment<2>(2 * j) = RangeBearing{}.residual(batch[j].z, z_hat);
    R.block(2 * j, 2 * j, 2, 2) = batch[j].noise.covariance();
  }
  ekf.update(RangeBearing{}, batch);
  ref.updateLinear(H, nu, R);
  Eigen::VectorXd dx = ekf.mean() - ref.x;
  dx[2] = wrapAngle(dx[2]);
  CHECK(dx.cwiseAbs().maxCoeff() < 1e-9);
  CHECK(maxAbsDiff(ekf.covariance(), ref.P) < 1e-9 * ref.P.cwiseAbs().maxCoeff());
}

TEST_CASE("sequential fusion equals one update per observation, batched differs by linearization",
          "[filter][fusion]") {
  const Filter start = mapWith(40, 9);
  const auto batch = observe(start, {1, 5, 9, 13, 30, 39});
  Filter by_hand = start;
  for (const auto& obs : batch) by_hand.update(RangeBearing{}, obs.id, obs.z, obs.noise);
  Filter sequential = start;
  sequential.update(RangeBearing{}, batch, Fusion::kSequential);
  CHECK(maxAbsDiff(sequential.mean(), by_hand.mean()) == 0.0);
  CHECK(maxAbsDiff(sequential.covariance(), by_hand.covariance()) == 0.0);
  // Both run the filter's own single-update path, so that equality checks the loop, not the
  // algebra: the dense textbook filter, updated once per observation, checks the algebra.
  testing::DenseReferenceEkf<Unicycle2D> ref{Unicycle2D{}, start.robotMean(), start.robotCovariance()};
  ref.x = start.mean();
  ref.P = start.covariance();
  for (const auto& obs : batch) ref.update(RangeBearing{}, start.slot(obs.id).offset, obs.z, obs.noise.covariance());
  Eigen::VectorXd dx = sequential.mean() - ref.x;
  dx[2] = wrapAngle(dx[2]);
  CHECK(dx.cwiseAbs().maxCoeff() < 1e-9);
  CHECK(maxAbsDiff(sequential.covariance(), ref.P) < 1e-9 * ref.P.cwiseAbs().maxCoeff());
  // One linearization point instead of six: the estimates are close but not identical.
  Filter batched = start;
  batched.update(RangeBearing{}, batch, Fusion::kBatched);
  const double mean_gap = maxAbsDiff(batched.mean(), sequential.mean());
  CHECK(mean_gap > 0.0);
  CHECK(mean_gap < 0.05);
}

TEST_CASE("sequential fusion checks every observation first, then names the one that failed",
          "[filter][fusion]") {
  const Filter start = mapWith(10, 13);
  auto batch = observe(start, {1, 2, 3});
  batch[2].id = 77;  // unknown: found before anything is fused
  Filter ekf = start;
  CHECK(sylva_test::throwsCode([&] { ekf.update(RangeBearing{}, batch, Fusion::kSequential); }, ErrorCode::kUnknownId));
  CHECK(maxAbsDiff(ekf.mean(), start.mean()) == 0.0);
  CHECK(maxAbsDiff(ekf.covariance(), start.covariance()) == 0.0);

  batch = observe(start, {1, 2, 3});
  batch[1].z[0] = std::nan("");
  CHECK(sylva_test::throwsCode([&] { ekf.update(RangeBearing{}, batch, Fusion::kSequential); }, ErrorCode::kNonFinite));
  CHECK(maxAbsDiff(ekf.mean(), start.mean()) == 0.0);

  // A model that refuses landmarks beyond x = 1000 m: only the update itself finds out. The
  // observation before the refused one stays fused, and the message says where it stopped.
  Filter far = start;
  far.add(50, InverseRangeBearing{}, Vec<2>(2000.0, -0.2), Gaussian<2>::sigmas(Vec<2>(0.1, 0.02)));
  auto with_far = observe(far, {1, 50, 2});
  Filter after_first = far;
  after_first.update(RangeBearing{}, with_far[0].id, with_far[0].z, with_far[0].noise);
  std::vector<Observation<RangeBearingRefusingFar>> refusing;
  for (const auto& obs : with_far) refusing.push_back({obs.id, obs.z, obs.noise});
  std::string message;
  try {
    far.update(RangeBearingRefusingFar{}, refusing, Fusion::kSequential);
  } catch (const Error& e) {
    CHECK(e.code() == ErrorCode::kDegenerateGeometry);
    message = e.what();
  }
  INFO(message);
  CHECK(message.find("sequential update stopped at observation 1 (the 1 before it stay fused)") != std::string::npos);
  CHECK(message.find("beyond 1000 m") != std::string::npos);
  CHECK(maxAbsDiff(far.mean(), after_first.mean()) == 0.0);
  CHECK(maxAbsDiff(far.covariance(), after_first.covariance()) == 0.0);
}

TEST_CASE("the covariance view reads the same symmetric matrix as the copy", "[filter][fusion]") {
  Filter ekf = mapWith(30, 21);
  ekf.update(RangeBearing{}, observe(ekf, {2, 4, 8, 16}));
  const Eigen::MatrixXd copy = ekf.covariance();
  const Eigen::MatrixXd from_view = ekf.covarianceView();
  CHECK(maxAbsDiff(copy, from_view) == 0.0);
  const Eigen::VectorXd v = Eigen::VectorXd::LinSpaced(ekf.dim(), -1.0, 1.0);
  const Eigen::VectorXd product = ekf.covarianceView() * v;
  CHECK((product - copy * v).cwiseAbs().maxCoeff() < 1e-12);
}

}  // namespace unity_filter_fusion
