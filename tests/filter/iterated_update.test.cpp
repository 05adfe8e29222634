// The iterated update (LinearizationPoint::kIterated): against a dense iterated EKF written
// out in this file, the Gauss-Newton fixed point it converges to, its stopping rule, and
// bad input leaving the filter unchanged.

#include <cmath>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <sylva/diff/numeric_diff.hpp>
#include <sylva/filter/ekf.hpp>
#include <sylva/landmarks.hpp>
#include <sylva/measurements.hpp>
#include <sylva/motion/unicycle_2d.hpp>

#include "filter_snapshot.hpp"
#include "sylva_catch.hpp"

using namespace sylva;

namespace unity_filter_iterated_update {

using Filter = Ekf<Unicycle2D, Point2>;

Gaussian<2> iteratedSensorNoise() { return Gaussian<2>::sigmas(Vec<2>(0.05, 0.02)); }

/// A filter whose robot is uncertain enough (0.5 m, 0.3 rad) that one range-bearing update
/// of a near landmark is far from linear.
Filter uncertainFilter() {
  Filter ekf(Vec<3>(0.0, 0.0, 0.0), Mat<3, 3>(Vec<3>(0.25, 0.25, 0.09).asDiagonal()));
  ekf.add(1, InverseRangeBearing(), Vec<2>(2.0, 0.3), Gaussian<2>::sigmas(Vec<2>(0.3, 0.1)));
  ekf.add(2, InverseRangeBearing(), Vec<2>(3.0, -0.8), Gaussian<2>::sigmas(Vec<2>(0.3, 0.1)));
  return ekf;
}

/// The iterated EKF over the full state with dense matrices, as Bell and Cathey (1993) write
/// it: x_{i+1} = x + K_i (z - h(x_i) - H_i (x - x_i)), K_i = P H_i^T (H_i P H_i^T + R)^-1,
/// then P - K_N H_N P. H_i is taken by central differences of h over the whole state.
struct DenseIteratedEkf {
  Eigen::VectorXd x;
  Eigen::MatrixXd P;

  /// Stacked h of range-bearing observations of the landmarks `ids` (slot offsets `offsets`).
  static Eigen::VectorXd h(const Eigen::VectorXd& state, const std::vector<int>& offsets) {
    Eigen::VectorXd z(2 * static_cast<int>(offsets.size()));
    for (std::size_t a = 0; a < offsets.size(); ++a)
      z.segment<2>(2 * static_cast<int>(a)) =
          RangeBearing()(Vec<3>(state.head<3>()), Vec<2>(state.segment<2>(offsets[a])));
    return z;
  }

  void update(const Eigen::VectorXd& z, const Eigen::MatrixXd& R, const std::vector<int>& offsets, int iterations) {
    const int n = static_cast<int>(x.size());
    const int m = static_cast<int>(z.size());
    const Eigen::VectorXd prior = x;
    Eigen::VectorXd xi = prior;
    Eigen::MatrixXd H(m, n), K;
    for (int it = 0; it < iterations; ++it) {
      for (int j = 0; j < n; ++j) {
        const double step = 1e-6;
        Eigen::VectorXd plus = xi, minus = xi;
        plus[j] += step;
        minus[j] -= step;
        Eigen::VectorXd d = h(plus, offsets) - h(minus, offsets);
        for (int r = 1; r < m; r += 2) d[r] = wrapAngle(d[r]);
        H.col(j) = d / (2.0 * step);
      }
      const Eigen::MatrixXd S = H * P * H.transpose() + R;
      K = P * H.transpose() * S.llt().solve(Eigen::MatrixXd::Identity(m, m));
      Eigen::VectorXd nu = z - h(xi, offsets);
      for (int r = 1; r < m; r += 2) nu[r] = wrapAngle(nu[r]);
      xi = prior + K * (nu - H * (prior - xi));
    }
    x = xi;
    P = P - K * H * P;
  }
};

}  // namespace unity_filter_iterated_update

using namespace unity_filter_iterated_update;
using sylva_test::requireRejected;

TEST_CASE("iterated update: matches a dense iterated EKF written out in full") {
  for (const int iterations : {1, 2, 5}) {
    Filter ekf = uncertainFilter();
    DenseIteratedEkf dense{ekf.mean(), ekf.covariance()};
    ekf.setLinearizationPoint(LinearizationPoint::kIterated);
    ekf.setIteratedUpdate({iterations, 1e-300});  // exactly `iterations` linearizations
    const std::vector<Observation<RangeBearing>> batch = {{1, Vec<2>(1.6, 0.55), iteratedSensorNoise()},
                                                           {2, Vec<2>(3.3, -0.5), iteratedSensorNoise()}};
    ekf.update(RangeBearing(), batch);
    Eigen::VectorXd z(4);
    z << 1.6, 0.55, 3.3, -0.5;
    Eigen::MatrixXd R = Eigen::MatrixXd::Zero(4, 4);
    R.block<2, 2>(0, 0) = R.block<2, 2>(2, 2) = iteratedSensorNoise().covariance();
    dense.update(z, R, {ekf.slot(1).offset, ekf.slot(2).offset}, iterations);
    INFO(iterations << " linearizations");
    CHECK((ekf.mean() - dense.x).cwiseAbs().maxCoeff() < 1e-7);
    CHECK((ekf.covariance() - dense.P).cwiseAbs().maxCoeff() < 1e-7);
  }
}

TEST_CASE("iterated update: one linearization is the textbook update, bit for bit") {
  // A single observation (the fixed-size path) and a batch of two (the batched path), each
  // against the textbook update of the same form.
  Filter textbook = uncertainFilter();
  Filter iterated = uncertainFilter();
  iterated.setLinearizationPoint(LinearizationPoint::kIterated);
  iterated.setIteratedUpdate({1, 1e-3});
  const Innovation<2> textbook_nu = textbook.update(RangeBearing(), 1, Vec<2>(1.6, 0.55), iteratedSensorNoise());
  const Innovation<2> iterated_nu = iterated.update(RangeBearing(), 1, Vec<2>(1.6, 0.55), iteratedSensorNoise());
  CHECK((textbook.mean().array() == iterated.mean().array()).all());
  CHECK((textbook.covariance().array() == iterated.covariance().array()).all());
  CHECK((textbook_nu.nu.array() == iterated_nu.nu.array()).all());
  CHECK((textbook_nu.S.array() == iterated_nu.S.array()).all());

  Filter textbook_batch = uncertainFilter();
  Filter iterated_batch = uncertainFilter();
  iterated_batch.setLinearizationPoint(LinearizationPoint::kIterated);
  iterated_batch.setIteratedUpdate({1, 1e-3});
  const std::vector<Observation<RangeBearing>> two = {{1, Vec<2>(1.6, 0.55), iteratedSensorNoise()},
                                                      {2, Vec<2>(3.3, -0.5), iteratedSensorNoise()}};
  textbook_batch.update(RangeBearing(), two);
  iterated_batch.update(RangeBearing(), two);
  CHECK((textbook_batch.mean().array() == iterated_batch.mean().array()).all());
  CHECK((textbook_batch.covariance().array() == iterated_batch.covariance().array()).all());
}

TEST_CASE("iterated update: one observation iterates as a batch of one") {
  // The single-observation update iterates on fixed-size blocks, the batched one on dynamic
  // ones: the same Gauss-Newton iterates, equal to round-off.
  Filter single = uncertainFilter();
  Filter batch = uncertainFilter();
  for (Filter* f : {&single, &batch}) {
    f->setLinearizationPoint(LinearizationPoint::kIterated);
    f->setIteratedUpdate({20, 1e-9});
  }
  const Innovation<2> prior = single.update(RangeBearing(), 1, Vec<2>(1.6, 0.55), iteratedSensorNoise());
  const std::vector<Observation<RangeBearing>> one = {{1, Vec<2>(1.6, 0.55), iteratedSensorNoise()}};
  batch.update(RangeBearing(), one);
  const double scale = batch.covariance().cwiseAbs().maxCoeff();
  CHECK((single.mean() - batch.mean()).cwiseAbs().maxCoeff() < 1e-12);
  CHECK((single.covariance() - batch.covariance()).cwiseAbs().maxCoeff() < 1e-12 * scale);
  // The innovation returned is the prior's, as a textbook filter would see it.
  Filter textbook = uncertainFilter();
  const Innovation<2> expected = textbook.innovation(RangeBearing(), 1, Vec<2>(1.6, 0.55), iteratedSensorNoise());
  CHECK((prior.nu - expected.nu).cwiseAbs().maxCoeff() < 1e-12);
  CHECK((prior.S - expected.S).cwiseAbs().maxCoeff() < 1e-12);
}

TEST_CASE("iterated update: converges to the Gauss-Newton fixed point of the MAP cost") {
  // At convergence x solves P^-1 (x - x_prior) = H(x)^T R^-1 (z - h(x)), the stationarity of
  // (x - x_prior)^T P^-1 (x - x_prior) + (z - h(x))^T R^-1 (z - h(x)). The textbook update does
  // not, with this prior.
  const Vec<2> z(1.6, 0.55);
  const auto residual = [&](const Filter& before, const Filter& after) {
    const Eigen::VectorXd x = after.mean();
    const Eigen::VectorXd dx = x - before.mean();
    Mat<2, 3> J_x;
    Mat<2, 2> J_l;
    const int off = before.slot(1).offset;
    Vec<2> nu = z - RangeBearing()(Vec<3>(x.head<3>()), Vec<2>(x.segment<2>(off)), J_x, J_l);
    nu[1] = wrapAngle(nu[1]);
    Eigen::MatrixXd H = Eigen::MatrixXd::Zero(2, x.size());
    H.leftCols<3>() = J_x;
    H.middleCols<2>(off) = J_l;
    const Eigen::VectorXd gradient = before.covariance().llt().solve(dx) -
                                     H.transpose() * iteratedSensorNoise().covariance().inverse() * nu;
    return gradient.norm();
  };
  const Filter before = uncertainFilter();
  Filter iterated = before, textbook = before;
  iterated.setLinearizationPoint(LinearizationPoint::kIterated);
  iterated.setIteratedUpdate({50, 1e-10});
  iterated.update(RangeBearing(), 1, z, iteratedSensorNoise());
  textbook.update(RangeBearing(), 1, z, iteratedSensorNoise());
  const double textbook_gradient = residual(before, textbook);
  CHECK(textbook_gradient > 1.0);
  CHECK(residual(before, iterated) < 1e-6 * textbook_gradient);
}

TEST_CASE("iterated update: the stopping rule and bad settings") {
  Filter ekf = uncertainFilter();
  ekf.setLinearizationPoint(LinearizationPoint::kIterated);
  requireRejected(ekf, ErrorCode::kInvalidArgument, "max_iterations >= 1", [&] { ekf.setIteratedUpdate({0, 1e-3}); });
  requireRejected(ekf, ErrorCode::kInvalidArgument, "tolerance > 0", [&] { ekf.setIteratedUpdate({5, 0.0}); });
  requireRejected(ekf, ErrorCode::kInvalidArgument, "tolerance > 0", [&] { ekf.setIteratedUpdate({5, NAN}); });
  CHECK(ekf.iteratedUpdate().max_iterations == IteratedUpdate().max_iterations);
  // A loose tolerance stops after the second linearization: the same result as exactly two.
  Filter loose = uncertainFilter(), two = uncertainFilter();
  for (Filter* f : {&loose, &two}) f->setLinearizationPoint(LinearizationPoint::kIterated);
  loose.setIteratedUpdate({50, 1e6});
  two.setIteratedUpdate({2, 1e-300});
  loose.update(RangeBearing(), 1, Vec<2>(1.6, 0.55), iteratedSensorNoise());
  two.update(RangeBearing(), 1, Vec<2>(1.6, 0.55), iteratedSensorNoise());
  CHECK((loose.mean().array() == two.mean().array()).all());
  // Bad input leaves the filter unchanged, iterations or not.
  requireRejected(ekf, ErrorCode::kNonFinite, "not finite",
                  [&] { ekf.update(RangeBearing(), 1, Vec<2>(NAN, 0.5), iteratedSensorNoise()); });
  requireRejected(ekf, ErrorCode::kUnknownId, "no landmark with id 9",
                  [&] { ekf.update(RangeBearing(), 9, Vec<2>(1.0, 0.5), iteratedSensorNoise()); });
}
