// Sensors written against a pose serve robots with more states (Robot::Pose, Robot::pose):
// RangeBearing and its inverse on Ackermann2DWithBias. The chained Jacobians against
// numerical differentiation; the filter equals the plain Ackermann2D filter when the biases
// are known to be zero; association works through the view; and the filter estimates a
// steering offset and a speed scale error that the simulated car has.

#include <cmath>
#include <random>
#include <vector>

#include <sylva/association/jcbb.hpp>
#include <sylva/consistency/chi_square.hpp>
#include <sylva/core/angles.hpp>
#include <sylva/diff/numeric_diff.hpp>
#include <sylva/filter/ekf.hpp>
#include <sylva/landmarks/point2.hpp>
#include <sylva/measurements/range_bearing.hpp>
#include <sylva/motion/ackermann_2d.hpp>
#include <sylva/motion/ackermann_2d_with_bias.hpp>

#include "filter/planar_scene.hpp"
#include "sylva_catch.hpp"

using namespace sylva;

namespace unity_filter_pose_view {

using BiasFilter = Ekf<Ackermann2DWithBias, Point2>;
using PlainFilter = Ekf<Ackermann2D, Point2>;
const Ackermann2DWithBias kBiasCar(2.83, 0.76);
const Ackermann2D kCar(2.83, 0.76);
const Gaussian<2> kReadingNoise = Gaussian<2>::sigmas(Vec<2>(0.1, 0.02));
const Vec<2> kCarMount(3.78, 0.5);  // a sensor ahead of the rear axle, as on the Victoria Park car

/// Landmarks 11 m and 19 m from the centre (0, 15) of the car's circle.
std::vector<Vec<2>> landmarks() { return sylva_test::landmarksOnTwoRings(24, 15.0, 11.0, 19.0); }

/// The noise of the 5-state car for a step of dt: control noise, bias random walks of
/// spectral density q_k and q_b (Var(w) = q / dt).
Gaussian<4> biasCarNoise(double dt, double q_k, double q_b) {
  return Gaussian<4>::sigmas(Vec<4>(0.05, 0.01, std::sqrt(q_k / dt), std::sqrt(q_b / dt)));
}

}  // namespace unity_filter_pose_view

using namespace unity_filter_pose_view;

TEST_CASE("pose view: a planar sensor's Jacobians chain through the robot's pose") {
  Vec<5> x;
  x << 2.0, -1.0, 0.7, 0.03, -0.02;
  BiasFilter ekf(x, Mat<5, 5>::Identity() * 0.01, kBiasCar);
  const RangeBearing model(kCarMount);
  ekf.add(4, InverseRangeBearing(kCarMount), Vec<2>(8.0, 0.3), kReadingNoise);
  const Vec<2> l = ekf.landmarkMean<Point2>(4);
  // The new landmark sits where the plain inverse model puts it from the pose.
  CHECK((l - InverseRangeBearing(kCarMount)(Vec<3>(x.head<3>()), Vec<2>(8.0, 0.3))).norm() < 1e-12);
  const auto lin = ekf.linearize(model, 4);
  static_assert(decltype(lin)::kRobotDim == 5, "the linearization spans the filter's robot block");
  const Mat<2, 5> numeric =
      numericJacobian<2, 5>([&](const Vec<5>& y) { return model(Vec<3>(y.head<3>()), l); }, x);
  CHECK((lin.J_z_x - numeric).cwiseAbs().maxCoeff() < 1e-6);
  CHECK(lin.J_z_x.rightCols<2>().isZero(0.0));  // the biases are not seen by the sensor
  // The landmark's cross-covariance with the robot came through J_l_x = J_l_pose [I 0].
  CHECK(ekf.robotLandmarkCovariance<Point2>(4).bottomRows<2>().isZero(0.0));
}

TEST_CASE("pose view: with the biases known to be zero the filter is the plain car's") {
  const double dt = 0.2;
  Mat<5, 5> P0 = Mat<5, 5>::Zero();
  P0.topLeftCorner<3, 3>() = Vec<3>(0.01, 0.01, 0.001).asDiagonal();
  BiasFilter biased(Vec<5>::Zero(), P0, kBiasCar);
  PlainFilter plain(Vec<3>::Zero(), P0.topLeftCorner<3, 3>(), kCar);
  const RangeBearing model(kCarMount);
  const InverseRangeBearing inverse(kCarMount);
  const std::vector<Vec<2>> map = landmarks();
  std::mt19937_64 rng(4);
  std::normal_distribution<double> normal;
  Vec<3> truth = Vec<3>::Zero();
  const Vec<2> u(4.0, std::atan(2.83 / 15.0));
  for (int k = 0; k < 40; ++k) {
    truth = kCar(truth, u, dt);
    biased.predict(u, dt, biasCarNoise(dt, 1e-300, 1e-300));  // (a Gaussian must be positive definite)
    plain.predict(u, dt, Gaussian<2>::sigmas(Vec<2>(0.05, 0.01)));
    std::vector<Vec<2>> z;
    for (const Vec<2>& l : map) {
      const Vec<2> zt = model(truth, l);
      if (zt[0] < 12.0) z.emplace_back(zt[0] + 0.1 * normal(rng), wrapAngle(zt[1] + 0.02 * normal(rng)));
    }
    // Unknown association: JCBB through the pose view, against every mapped landmark.
    std::vector<Id> candidates;
    for (const auto& s : plain.slots()) candidates.push_back(s.id);
    const auto pairs_plain = associateJcbb(plain, model, z, kReadingNoise, candidates);
    const auto pairs_biased = associateJcbb(biased, model, z, kReadingNoise, candidates);
    REQUIRE(pairs_plain == pairs_biased);
    std::vector<Observation<RangeBearing>> paired;
    for (std::size_t i = 0; i < z.size(); ++i)
      if (pairs_plain[i]) paired.push_back({*pairs_plain[i], z[i], kReadingNoise});
    plain.update(model, paired);
    biased.update(model, paired);
    for (std::size_t i = 0; i < z.size(); ++i) {
      if (pairs_plain[i]) continue;
      const Id id = static_cast<Id>(100 * k + static_cast<int>(i));
      plain.add(id, inverse, z[i], kReadingNoise);
      biased.add(id, inverse, z[i], kReadingNoise);
    }
    REQUIRE(biased.dim() == plain.dim() + 2);
    // The biased filter's state without the two bias rows and columns.
    std::vector<int> keep{0, 1, 2};
    for (int i = 5; i < biased.dim(); ++i) keep.push_back(i);
    const Eigen::VectorXd mean = biased.mean();
    const Eigen::MatrixXd cov = biased.covariance();
    Eigen::VectorXd mean_kept(plain.dim());
    Eigen::MatrixXd cov_kept(plain.dim(), plain.dim());
    for (int a = 0; a < plain.dim(); ++a) {
      mean_kept[a] = mean[keep[static_cast<std::size_t>(a)]];
      for (int b = 0; b < plain.dim(); ++b) cov_kept(a, b) = cov(keep[static_cast<std::size_t>(a)], keep[static_cast<std::size_t>(b)]);
    }
    INFO("step " << k);
    CHECK((mean_kept - plain.mean()).cwiseAbs().maxCoeff() < 1e-10);
    CHECK((cov_kept - plain.covariance()).cwiseAbs().maxCoeff() < 1e-10);
    CHECK(cov.block(3, 0, 2, biased.dim()).cwiseAbs().maxCoeff() < 1e-100);
  }
}

TEST_CASE("pose view: the filter estimates the car's steering offset and speed scale error", "[filter][slow]") {
  // A car whose steering reads 0.03 rad off and whose encoder reads 4% slow, among point
  // landmarks with a mounted range-bearing sensor; the filter starts with both biases at 0.
  const double dt = 0.2, true_offset = 0.03, true_scale = 0.04;
  const RangeBearing model(kCarMount);
  const InverseRangeBearing inverse(kCarMount);
  const std::vector<Vec<2>> map = landmarks();
  const Vec<2> u_true(4.0, std::atan(2.83 / 15.0));
  Mat<5, 5> P0 = Mat<5, 5>::Zero();
  P0(3, 3) = 0.05 * 0.05;
  P0(4, 4) = 0.05 * 0.05;
  double nees_sum = 0.0;
  const int seeds = 10;
  for (unsigned seed = 1; seed <= static_cast<unsigned>(seeds); ++seed) {
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> normal;
    BiasFilter ekf(Vec<5>::Zero(), P0, kBiasCar);
    ekf.setLinearizationPoint(LinearizationPoint::kInvariant);
    Vec<3> truth = Vec<3>::Zero();
    for (int k = 0; k < 300; ++k) {  // two laps
      truth = kCar(truth, u_true, dt);
      // What the sensors read: the true control through the biases, plus noise.
      const Vec<2> u(u_true[0] / (1.0 + true_scale) + 0.05 * normal(rng), u_true[1] - true_offset + 0.01 * normal(rng));
      ekf.predict(u, dt, biasCarNoise(dt, 1e-8, 1e-8));
      std::vector<Observation<RangeBearing>> seen;
      for (std::size_t i = 0; i < map.size(); ++i) {
        const Vec<2> zt = model(truth, map[i]);
        if (zt[0] > 12.0) continue;
        const Vec<2> z(zt[0] + 0.1 * normal(rng), wrapAngle(zt[1] + 0.02 * normal(rng)));
        const Id id = static_cast<Id>(i);
        if (ekf.contains(id))
          seen.push_back({id, z, kReadingNoise});
        else
          ekf.add(id, inverse, z, kReadingNoise);
      }
      ekf.update(model, seen);
    }
    // The encoder reads u_true / (1 + s) and the steering alpha_true - offset, so the filter's
    // v = v_e (1 + k), alpha = alpha_m + b hold at k = s, b = offset.
    const Vec<2> truth_bias(true_scale, true_offset);
    const Vec<2> e = Vec<2>(ekf.robotMean().tail<2>()) - truth_bias;
    const Mat<2, 2> P = ekf.robotCovariance().bottomRightCorner<2, 2>();
    INFO("seed " << seed << ": bias estimate " << ekf.robotMean().tail<2>().transpose() << ", sigmas "
                 << P.diagonal().cwiseSqrt().transpose());
    CHECK(std::sqrt(P(1, 1)) < 0.2 * 0.05);  // the offset's sigma fell below a fifth of its prior
    nees_sum += e.dot(P.ldlt().solve(e));
  }
  // The average of ten independent 2-dof NEES values against the two-sided 99% bounds of
  // chi2(2 * 10) / 10.
  const auto bounds = averageChiSquareBounds(2, seeds, 0.99);
  INFO("mean bias NEES " << nees_sum / seeds << ", bounds " << bounds.first << " - " << bounds.second);
  CHECK(nees_sum / seeds > bounds.first);
  CHECK(nees_sum / seeds < bounds.second);
}
