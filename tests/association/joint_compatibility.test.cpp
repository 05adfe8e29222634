// jointNis / jointlyCompatible: the joint compatibility statistic of one hypothesis
// (Neira & Tardos 2001), checked against the textbook formula on the full state.

#include "sylva_catch.hpp"

#include <limits>

#include <sylva/association/joint_compatibility.hpp>

#include "association/scenarios.hpp"

using namespace sylva;
using sylva_test::ids;
using sylva_test::Pairing;
using sylva_test::Scenario;

namespace {

/// nu_H^T (H P H^T + R_H)^-1 nu_H with the dense k d x n Jacobian and the full covariance.
double denseJointNis(const Scenario& s, const std::vector<Vec<2>>& z, const Pairing& pairing) {
  const RangeBearing model;
  std::vector<std::size_t> paired;
  for (std::size_t i = 0; i < pairing.size(); ++i)
    if (pairing[i]) paired.push_back(i);
  const int k = static_cast<int>(paired.size());
  const int n = s.ekf.dim();
  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(2 * k, n);
  Eigen::MatrixXd R = Eigen::MatrixXd::Zero(2 * k, 2 * k);
  Eigen::VectorXd nu(2 * k);
  for (int a = 0; a < k; ++a) {
    const std::size_t i = paired[static_cast<std::size_t>(a)];
    const Id id = *pairing[i];
    const int offset = s.ekf.slot(id).offset;
    Mat<2, 3> J_z_x;
    Mat<2, 2> J_z_l;
    const Vec<2> z_hat = model(s.ekf.robotMean(), s.ekf.landmarkMean<Point2>(id), J_z_x, J_z_l);
    H.block<2, 3>(2 * a, 0) = J_z_x;
    H.block<2, 2>(2 * a, offset) = J_z_l;
    R.block<2, 2>(2 * a, 2 * a) = s.noise.covariance();
    nu.segment<2>(2 * a) = Vec<2>(z[i][0] - z_hat[0], wrapAngle(z[i][1] - z_hat[1]));
  }
  const Eigen::MatrixXd S = H * s.ekf.covariance() * H.transpose() + R;
  return nu.dot(S.ldlt().solve(nu));
}

}  // namespace

TEST_CASE("joint NIS matches the dense formula", "[association][joint]") {
  const Scenario s = sylva_test::treeRowScenario(0.7);
  const std::vector<Vec<2>> z = s.measureLandmarks({0, 1, 2, 3, 4});
  for (const Pairing& h : {ids({10, 11, 12, 13, 14}),
                           ids({11, 12, 13, 14, std::nullopt}),
                           ids({std::nullopt, 10, std::nullopt, 14, 12}),
                           ids({13, 13, 13, 13, 13})}) {
    const double expected = denseJointNis(s, z, h);
    const double actual = jointNis(s.ekf, RangeBearing{}, z, s.noise, h);
    CAPTURE(expected, actual);
    CHECK(actual == Approx(expected).epsilon(1e-9));
  }
}

TEST_CASE("joint NIS of one pairing is the individual NIS", "[association][joint]") {
  const Scenario s = sylva_test::treeRowScenario(0.7);
  const std::vector<Vec<2>> z = s.measureLandmarks({2, 3});
  const double individual = s.ekf.innovation(RangeBearing{}, 13, z[1], s.noise).nis();
  CHECK(jointNis(s.ekf, RangeBearing{}, z, s.noise, ids({std::nullopt, 13})) ==
        Approx(individual).epsilon(1e-12));
}

TEST_CASE("joint NIS adds up when the innovations are uncorrelated", "[association][joint]") {
  // A robot that knows its pose exactly maps the landmarks independently: H P H^T is block
  // diagonal and the joint statistic is the sum of the individual ones.
  Scenario s = sylva_test::mapPoints(Vec<3>::Zero(),
                                     Mat<3, 3>::Zero(),
                                     {Vec<2>(4.0, 1.0), Vec<2>(3.0, -2.0), Vec<2>(-1.0, 5.0)},
                                     Gaussian<2>::sigmas(Vec<2>(0.1, 0.02)),
                                     1);
  std::vector<Vec<2>> z = s.measureLandmarks({0, 1, 2});
  z[0] += Vec<2>(0.1, -0.01);
  z[1] += Vec<2>(-0.05, 0.03);
  z[2] += Vec<2>(0.2, 0.02);
  double sum = 0.0;
  for (std::size_t i = 0; i < 3; ++i)
    sum += s.ekf.innovation(RangeBearing{}, s.ids[i], z[i], s.noise).nis();
  CHECK(jointNis(s.ekf, RangeBearing{}, z, s.noise, ids({1, 2, 3})) == Approx(sum).epsilon(1e-9));
  // With the robot uncertain, the same innovations are correlated and the sum is wrong.
  s.ekf.predict(Vec<2>::Zero(), 1.0, Gaussian<2>::sigmas(Vec<2>(0.3, 0.05)));
  double sum_uncertain = 0.0;
  for (std::size_t i = 0; i < 3; ++i)
    sum_uncertain += s.ekf.innovation(RangeBearing{}, s.ids[i], z[i], s.noise).nis();
  CHECK(std::abs(jointNis(s.ekf, RangeBearing{}, z, s.noise, ids({1, 2, 3})) - sum_uncertain) >
        0.1);
}

TEST_CASE("joint compatibility of the empty hypothesis and the gate", "[association][joint]") {
  const Scenario s = sylva_test::treeRowScenario(0.7);
  const std::vector<Vec<2>> z = s.measureLandmarks({0, 1});
  const Pairing none = ids({std::nullopt, std::nullopt});
  CHECK(jointNis(s.ekf, RangeBearing{}, z, s.noise, none) == 0.0);
  CHECK(jointlyCompatible(s.ekf, RangeBearing{}, z, s.noise, none));
  const Pairing truth = ids({10, 11});
  const double d2 = jointNis(s.ekf, RangeBearing{}, z, s.noise, truth);
  // The gate is chi2(2 k, p): this hypothesis passes at p = 0.99 and fails at a p whose
  // quantile is below its statistic.
  CHECK(jointlyCompatible(s.ekf, RangeBearing{}, z, s.noise, truth, 0.99));
  CHECK(d2 > chiSquareGate(4, 0.05));
  CHECK_FALSE(jointlyCompatible(s.ekf, RangeBearing{}, z, s.noise, truth, 0.05));
}

TEST_CASE("joint compatibility rejects bad input", "[association][joint][errors]") {
  const Scenario s = sylva_test::treeRowScenario(0.7);
  const std::vector<Vec<2>> z = s.measureLandmarks({0, 1});
  const double nan = std::numeric_limits<double>::quiet_NaN();
  sylva_test::requireRejected(s.ekf, ErrorCode::kInvalidArgument, "3 entries for 2", [&] {
    jointNis(s.ekf, RangeBearing{}, z, s.noise, ids({10, 11, 12}));
  });
  sylva_test::requireRejected(s.ekf, ErrorCode::kUnknownId, "landmark id 99", [&] {
    jointNis(s.ekf, RangeBearing{}, z, s.noise, ids({10, 99}));
  });
  sylva_test::requireRejected(s.ekf, ErrorCode::kNonFinite, "measurement 0", [&] {
    jointNis(s.ekf, RangeBearing{}, {Vec<2>(nan, 0.0), z[1]}, s.noise, ids({std::nullopt, 11}));
  });
  sylva_test::requireRejected(s.ekf, ErrorCode::kInvalidArgument, "gate_probability", [&] {
    jointlyCompatible(s.ekf, RangeBearing{}, z, s.noise, ids({10, 11}), 1.0);
  });
}
