// Unicycle2DWithBias: the commanded differential-drive robot with a speed scale error, a turn
// rate scale error and a turn-rate offset as states. Jacobians against central differences
// and forward-mode automatic differentiation at ordinary and awkward inputs; the pose part is
// Unicycle2D's at the actual motion, and a standstill command does not turn the robot; the
// pose view; and in a filter, the gains of a simulated robot recovered from range-bearing
// readings, with their NEES inside its bounds over an ensemble of seeds.

#include <cmath>
#include <random>
#include <vector>

#include <sylva/consistency/chi_square.hpp>
#include <sylva/diff/numeric_diff.hpp>
#include <sylva/filter/ekf.hpp>
#include <sylva/landmarks/point2.hpp>
#include <sylva/measurements/range_bearing.hpp>
#include <sylva/motion/unicycle_2d.hpp>
#include <sylva/motion/unicycle_2d_with_bias.hpp>
#include <sylva/testing/check_jacobians.hpp>

#include "motion_autodiff.hpp"
#include "sylva_catch.hpp"

namespace unity_motion_unicycle_2d_with_bias {

using namespace sylva;

const Unicycle2DWithBias kBiasedUnicycle;

struct UnicycleCase {
  const char* name;
  Vec<6> x;
  Vec<2> u;
  double dt;
};

const UnicycleCase kUnicycleCases[] = {
    {"ordinary", (Vec<6>() << 1.0, 2.0, 0.3, 0.04, -0.07, -0.002).finished(), Vec<2>(0.08, 0.2), 0.1},
    {"no bias", (Vec<6>() << 1.0, 2.0, 0.3, 0.0, 0.0, 0.0).finished(), Vec<2>(0.08, 0.2), 0.2},
    {"turning in place", (Vec<6>() << 1.0, 2.0, 0.3, 0.05, 0.03, 0.01).finished(), Vec<2>(0.0, 0.4), 0.1},
    {"standstill command", (Vec<6>() << 1.0, 2.0, 0.3, 0.05, 0.03, 0.01).finished(), Vec<2>(0.0, 0.0), 0.5},
    {"reversing", (Vec<6>() << 0.0, 0.0, 2.0, 0.1, -0.02, 0.003).finished(), Vec<2>(-0.1, 0.3), 0.2},
    {"heading at the seam", (Vec<6>() << 0.0, 0.0, kPi - 1e-3, 0.0, 0.01, -0.01).finished(), Vec<2>(0.05, 0.5), 0.1},
    {"long step", (Vec<6>() << 5.0, 5.0, 2.0, 0.02, 0.02, 0.002).finished(), Vec<2>(0.07, -0.4), 1.4},
    {"zero time step", (Vec<6>() << 5.0, 5.0, 2.0, 0.02, 0.02, 0.002).finished(), Vec<2>(0.03, -0.2), 0.0},
};

}  // namespace unity_motion_unicycle_2d_with_bias

using namespace unity_motion_unicycle_2d_with_bias;

TEST_CASE("Unicycle2DWithBias: the pose moves as Unicycle2D under the actual motion", "[motion][unicycle]") {
  for (const UnicycleCase& c : kUnicycleCases) {
    INFO(c.name);
    const Vec<6> next = kBiasedUnicycle(c.x, c.u, c.dt);
    const bool standstill = c.u.isZero(0.0);
    const Vec<2> actual(c.u[0] * (1.0 + c.x[3]), standstill ? 0.0 : c.u[1] * (1.0 + c.x[4]) + c.x[5]);
    const Vec<3> pose = Unicycle2D()(Vec<3>(c.x.head<3>()), actual, c.dt);
    CHECK((next.head<3>() - pose).norm() < 1e-14);
    CHECK(next.tail<3>() == c.x.tail<3>());
    if (standstill) CHECK(next.head<3>() == c.x.head<3>());
  }
}

TEST_CASE("Unicycle2DWithBias Jacobians match numerical and automatic differentiation",
          "[motion][jacobian][unicycle]") {
  for (const UnicycleCase& c : kUnicycleCases) {
    INFO(c.name);
    sylva_test::requireMotionJacobians(kBiasedUnicycle, c.x, c.u, c.dt);
  }
}

TEST_CASE("Unicycle2DWithBias: the pose view and its Jacobian", "[motion]") {
  sylva_test::requirePlanarPoseView<Unicycle2DWithBias>(kUnicycleCases[0].x);
}

TEST_CASE("Unicycle2DWithBias: a filter recovers a simulated robot's gains, consistently over seeds",
          "[motion][unicycle][filter][consistency][slow]") {
  // A robot whose gains are drawn from the filter's prior (zero mean, sigmas 0.1, 0.1,
  // 0.01 rad/s) drives 240 s of arcs among 12 landmarks; the filter starts at the true pose
  // and reads range and bearing with the noise it is told. Over 20 seeds, the mean NEES of
  // the three gain states at the end lies inside the two-sided 99% bounds of a 20-run mean
  // (chi-square with 60 dof / 20), every gain is within 4 of its sigmas, and the data have
  // taught the filter the gains: each final sigma is below a third of the prior's.
  using UnicycleBiasFilter = Ekf<Unicycle2DWithBias, Point2>;
  const RangeBearing model;
  const InverseRangeBearing inverse;
  const Vec<2> reading_sigma(0.05, 0.01);
  const Vec<2> command_sigma(0.005, 0.005);
  std::vector<Vec<2>> landmarks;
  for (int i = 0; i < 12; ++i) {
    const double a = 2.0 * kPi * i / 12.0;
    landmarks.emplace_back((4.0 + (i % 3)) * std::cos(a), (4.0 + (i % 3)) * std::sin(a));
  }
  const int runs = 20;
  double nees_sum = 0.0;
  int within = 0;
  for (int seed = 1; seed <= runs; ++seed) {
    std::mt19937 rng(static_cast<unsigned>(seed));
    std::normal_distribution<double> normal(0.0, 1.0);
    Vec<6> truth;
    const Vec<3> prior_sigma(0.1, 0.1, 0.01);
    truth << 0.0, -3.0, 0.0, prior_sigma[0] * normal(rng), prior_sigma[1] * normal(rng), prior_sigma[2] * normal(rng);
    Vec<6> x0 = truth;
    x0.tail<3>().setZero();
    Mat<6, 6> P0 = Mat<6, 6>::Zero();
    P0.diagonal() << 1e-6, 1e-6, 1e-6, prior_sigma.cwiseAbs2();
    UnicycleBiasFilter ekf(x0, P0);
    const double dt = 0.1;
    const Vec<5> noise_sigma(command_sigma[0], command_sigma[1], 1e-6, 1e-6, 1e-7);
    const Gaussian<5> noise = Gaussian<5>::sigmas(noise_sigma);
    for (int k = 0; k < 2400; ++k) {
      const Vec<2> u(0.3, 0.1 + 0.05 * std::sin(0.01 * k));
      // The truth follows the command with the command noise the filter is told of.
      const Vec<5> n(command_sigma[0] * normal(rng), command_sigma[1] * normal(rng), 0.0, 0.0, 0.0);
      truth = kBiasedUnicycle.propagate<double>(truth, u, n, dt);
      ekf.predict(u, dt, noise);
      if (k % 5 != 4) continue;
      std::vector<Observation<RangeBearing>> batch;
      for (std::size_t i = 0; i < landmarks.size(); ++i) {
        Vec<2> z = model(Vec<3>(truth.head<3>()), landmarks[i]);
        if (z[0] > 6.0) continue;
        z += Vec<2>(reading_sigma[0] * normal(rng), reading_sigma[1] * normal(rng));
        const Gaussian<2> R = Gaussian<2>::sigmas(reading_sigma);
        if (!ekf.contains(static_cast<Id>(i))) {
          ekf.add(static_cast<Id>(i), inverse, z, R);
        } else {
          batch.push_back({static_cast<Id>(i), z, R});
        }
      }
      ekf.update(model, batch);
    }
    const Vec<3> error = truth.tail<3>() - ekf.robotMean().tail<3>();
    const Mat<3, 3> P = ekf.robotCovariance().bottomRightCorner<3, 3>();
    nees_sum += error.dot(P.ldlt().solve(error));
    bool ok = true;
    for (int i = 0; i < 3; ++i) ok = ok && std::abs(error[i]) < 4.0 * std::sqrt(P(i, i)) && std::sqrt(P(i, i)) < prior_sigma[i] / 3.0;
    if (seed == 1) INFO("final gain sigmas " << P.diagonal().cwiseSqrt().transpose());
    within += ok ? 1 : 0;
  }
  const double nees_mean = nees_sum / runs;
  const double lower = chiSquareQuantile(0.005, 3 * runs) / runs;
  const double upper = chiSquareQuantile(0.995, 3 * runs) / runs;
  INFO("mean gain NEES " << nees_mean << ", 99% bounds [" << lower << ", " << upper << "]");
  CHECK(nees_mean > lower);
  CHECK(nees_mean < upper);
  CHECK(within == runs);
}
