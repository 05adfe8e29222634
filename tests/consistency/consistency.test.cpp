// NEES / NIS / NMEE and their chi-square bounds.

#include <Eigen/LU>
#include <random>

#include <sylva/consistency.hpp>

#include "sylva_catch.hpp"

using namespace sylva;
using Catch::Matchers::Contains;

TEST_CASE("chi-square quantiles match tabulated values", "[consistency]") {
  // Standard table values (e.g. Abramowitz & Stegun 26.4).
  CHECK(chiSquareQuantile(0.95, 1) == Approx(3.841459).epsilon(1e-6));
  CHECK(chiSquareQuantile(0.95, 2) == Approx(5.991465).epsilon(1e-6));
  CHECK(chiSquareQuantile(0.99, 2) == Approx(9.210340).epsilon(1e-6));
  CHECK(chiSquareQuantile(0.025, 3) == Approx(0.2157953).epsilon(1e-6));
  CHECK(chiSquareQuantile(0.975, 3) == Approx(9.348404).epsilon(1e-6));
  CHECK(chiSquareGate(2, 0.95) == chiSquareQuantile(0.95, 2));
  const auto [lo, hi] = averageChiSquareBounds(3, 50, 0.95);
  CHECK(lo == Approx(chiSquareQuantile(0.025, 150) / 50));
  CHECK(hi == Approx(chiSquareQuantile(0.975, 150) / 50));
  CHECK(lo < 3.0);
  CHECK(hi > 3.0);
  CHECK_THROWS_WITH(chiSquareQuantile(1.5, 2), Contains("0 < p < 1"));
  CHECK_THROWS_WITH(averageChiSquareBounds(0, 10), Contains("dof > 0"));
}

TEST_CASE("nees, nis and normalized error are the textbook quadratic forms", "[consistency]") {
  Mat<2, 2> P;
  P << 4.0, 1.0, 1.0, 2.0;
  const Vec<2> e(1.0, -1.0);
  CHECK(nees(e, P) == Approx(e.dot(P.inverse() * e)));
  CHECK(nis(e, P) == nees(e, P));
  const Vec<2> ne = normalizedError(e, P);
  CHECK(ne[0] == Approx(0.5));
  CHECK(ne[1] == Approx(-1.0 / std::sqrt(2.0)));
  Eigen::MatrixXd Pd = P;
  Eigen::VectorXd ed = e;
  CHECK(nees(ed, Pd) == Approx(nees(e, P)));
  CHECK_THROWS_WITH(nees(e, Mat<2, 2>(-P)), Contains("not positive definite"));
  CHECK_THROWS_WITH(nees(Eigen::VectorXd::Ones(3), Pd), Contains("sizes do not match"));
  CHECK_THROWS_WITH(nees(Vec<2>(NAN, 0.0), P), Contains("not finite"));
}

namespace {
/// NEES of errors drawn from N(0, P_true) but judged with P_filter, over runs x steps.
NeesSeries simulateNees(double filter_scale, int runs, int steps, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal;
  Mat<3, 3> A;
  A << 1.0, 0.0, 0.0, 0.5, 2.0, 0.0, -0.3, 0.2, 0.1;
  const Mat<3, 3> P_true = A * A.transpose();
  NeesSeries series(3);
  for (int r = 0; r < runs; ++r)
    for (int k = 0; k < steps; ++k) {
      const Vec<3> e = A * Vec<3>(normal(rng), normal(rng), normal(rng));
      series.add(k, nees(e, Mat<3, 3>(filter_scale * P_true)));
    }
  return series;
}
}  // namespace

TEST_CASE("a consistent estimator's averaged NEES stays inside the 95% bounds, a 2x wrong one outside",
          "[consistency][slow]") {
  // Over seeds 1-20. Per step the 50-run average of a 3-dof NEES is chi-square(150) / 50, so
  // each of the 400 independent steps is inside its 95% bounds with probability 0.95: the
  // share inside is binomial(400, 0.95) / 400, standard deviation 0.011, and [0.90, 0.99] lies
  // 4.6 and 3.7 standard deviations away (a seed fails with probability about 1e-4).
  // Told half the variance, the average is 2 chi-square(150) / 50: mean 6, sd 0.69, against an
  // upper bound of 3.7, so a step is inside with probability 4e-4; told twice the variance,
  // mean 1.5, sd 0.17, against a lower bound of 2.4 (probability below 1e-7). A share inside
  // of 0.05 would need about 20 of 400 such steps.
  for (unsigned seed = 1; seed <= 20; ++seed) {
    INFO("seed " << seed);
    const NeesSeries consistent = simulateNees(1.0, 50, 400, seed);
    CHECK(consistent.runs() == 50);
    CHECK(consistent.steps() == 400);
    // The grand mean of 20,000 chi-square(3) draws: sd sqrt(6 / 20000) = 0.017; 0.08 is 4.6 sd.
    CHECK(consistent.mean() == Approx(3.0).margin(0.08));
    CHECK(consistent.fractionInside() > 0.90);
    CHECK(consistent.fractionInside() < 0.99);

    const NeesSeries optimistic = simulateNees(0.5, 50, 400, seed);  // told half the variance
    CHECK(optimistic.mean() > optimistic.bounds().second);
    CHECK(optimistic.fractionInside() < 0.05);
    const NeesSeries pessimistic = simulateNees(2.0, 50, 400, seed);  // told twice the variance
    CHECK(pessimistic.mean() < pessimistic.bounds().first);
    CHECK(pessimistic.fractionInside() < 0.05);
  }
}

TEST_CASE("NMEE bounds are those of an N(0, 1/N) average", "[consistency]") {
  const auto [lo, hi] = NmeeSeries<2>::bounds(50, 0.95);
  CHECK(hi == Approx(1.959964 / std::sqrt(50.0)).epsilon(1e-6));
  CHECK(lo == -hi);
  NmeeSeries<2> series;
  std::mt19937_64 rng(3);
  std::normal_distribution<double> normal;
  int inside = 0;
  const int steps = 400;
  for (int r = 0; r < 50; ++r)
    for (int k = 0; k < steps; ++k) series.add(k, Vec<2>(normal(rng), normal(rng)));
  for (const Vec<2>& a : series.averages()) inside += (a[0] > lo && a[0] < hi) ? 1 : 0;
  CHECK(static_cast<double>(inside) / steps > 0.90);
  CHECK_THROWS_WITH(NmeeSeries<2>::bounds(0), Contains("runs > 0"));
  CHECK_THROWS_WITH(series.add(-1, Vec<2>::Zero()), Contains("negative step"));
}

TEST_CASE("camera pose NEES is chi-square(6) for errors drawn from the covariance", "[consistency]") {
  // True camera: somewhere, turned about a tilted axis.
  Vec<13> truth = Vec<13>::Zero();
  truth.head<3>() << 1.0, -2.0, 1.5;
  truth.segment<4>(3) = quaternionFromRotationVector<double>(Vec<3>(0.3, -0.5, 1.2));
  // Tangent-space covariance of [position error, rotation error]: correlated, SPD.
  Mat<6, 6> A;
  A << 0.05, 0.01, 0.0, 0.002, 0.0, 0.0,  //
      0.0, 0.04, 0.01, 0.0, 0.001, 0.0,   //
      0.0, 0.0, 0.03, 0.0, 0.0, 0.003,    //
      0.0, 0.0, 0.0, 0.010, 0.002, 0.0,   //
      0.0, 0.0, 0.0, 0.0, 0.008, 0.001,   //
      0.0, 0.0, 0.0, 0.0, 0.0, 0.012;
  const Mat<6, 6> Sigma = A * A.transpose();
  std::mt19937_64 rng(11);
  std::normal_distribution<double> normal;
  const int runs = 4000;
  double sum = 0.0;
  for (int i = 0; i < runs; ++i) {
    Vec<6> w;
    for (int k = 0; k < 6; ++k) w[k] = normal(rng);
    const Vec<6> delta = A * w;  // ~ N(0, Sigma)
    // The estimate: t_hat = t - delta_p, q_hat = q (x) exp(-delta_theta), so that
    // e = [t - t_hat, 2 vec(q_hat^* (x) q)] = delta to first order.
    Vec<13> estimate = truth;
    estimate.head<3>() -= delta.head<3>();
    estimate.segment<4>(3) = quaternionProduct<double>(truth.segment<4>(3), quaternionFromRotationVector<double>(Vec<3>(-delta.tail<3>())));
    // The filter's covariance of [t, q] about its estimate: dq = 0.5 q_hat (x) (0, dtheta).
    Mat<7, 6> H = Mat<7, 6>::Zero();
    H.topLeftCorner<3, 3>() = -Mat<3, 3>::Identity();
    for (int k = 0; k < 3; ++k) {
      Vec<4> v = Vec<4>::Zero();
      v[k + 1] = 1.0;
      H.block<4, 1>(3, 3 + k) = -0.5 * quaternionProduct<double>(Vec<4>(estimate.segment<4>(3)), v);
    }
    Mat<13, 13> P = Mat<13, 13>::Identity();
    P.topLeftCorner<7, 7>() = H * Sigma * H.transpose();
    sum += cameraPoseNees(estimate, P, truth);
  }
  // Mean of 4000 chi-square(6): 6 with standard deviation sqrt(12 / 4000) = 0.055.
  CHECK(sum / runs == Approx(6.0).margin(0.25));

  // The exact estimate has NEES 0; -q is the same orientation.
  Mat<13, 13> P = Mat<13, 13>::Identity() * 0.01;
  CHECK(cameraPoseNees(truth, P, truth) == Approx(0.0).margin(1e-20));
  Vec<13> off = truth;
  off[0] += 0.1;
  Vec<13> flipped = truth;
  flipped.segment<4>(3) *= -1.0;
  CHECK(cameraPoseNees(off, P, flipped) == Approx(cameraPoseNees(off, P, truth)));
  // Bad input.
  Vec<13> nan_state = truth;
  nan_state[1] = NAN;
  CHECK_THROWS_WITH(cameraPoseNees(nan_state, P, truth), Contains("not finite"));
  CHECK_THROWS_WITH(cameraPoseNees(off, Mat<13, 13>::Zero(), truth), Contains("not positive definite"));
  Vec<13> zero_q = truth;
  zero_q.segment<4>(3).setZero();
  CHECK_THROWS_WITH(cameraPoseNees(zero_q, P, truth), Contains("zero norm"));
}

namespace {
/// chi-square(dof) samples: sums of squared standard normals.
double chiSquareSample(int dof, std::mt19937_64& rng) {
  std::normal_distribution<double> normal;
  double sum = 0.0;
  for (int i = 0; i < dof; ++i) {
    const double x = normal(rng);
    sum += x * x;
  }
  return sum;
}
}  // namespace

TEST_CASE("NeesEnsemble: a consistent ensemble sits inside its bounds, step by step and run by run", "[consistency]") {
  // 40 ensembles of 50 runs x 60 steps of independent chi2(3) samples: at each step the
  // ensemble average lies inside its 95% bounds with probability 0.95, so the share of steps
  // inside averages 0.95 over the ensembles.
  std::mt19937_64 rng(2024);
  double fraction_sum = 0.0, mean_sum = 0.0;
  const int ensembles = 40;
  for (int e = 0; e < ensembles; ++e) {
    NeesEnsemble ensemble(3);
    for (int run = 0; run < 50; ++run)
      for (int step = 0; step < 60; ++step) ensemble.add(run, step, chiSquareSample(3, rng));
    const auto s = ensemble.summary();
    CHECK(s.runs == 50);
    CHECK(s.dof == 3);
    const auto [lo, hi] = averageChiSquareBounds(3, 50);
    CHECK(s.lower == lo);
    CHECK(s.upper == hi);
    fraction_sum += s.fraction_inside;
    mean_sum += s.mean;
    // The median of 50 run averages of 60 chi2(3) samples: each has sd sqrt(6 / 60) = 0.32.
    CHECK(std::abs(s.median_run - 3.0) < 0.5);
  }
  CHECK(fraction_sum / ensembles == Approx(0.95).margin(0.015));
  CHECK(mean_sum / ensembles == Approx(3.0).margin(0.03));
}

TEST_CASE("NeesEnsemble: a diverged run counts as infinite, and the median tolerates it", "[consistency]") {
  NeesEnsemble ensemble(2);
  for (int run = 0; run < 5; ++run)
    for (int step = 0; step < 4; ++step) ensemble.add(run, step, run == 4 && step >= 2 ? INFINITY : 1.0 + run);
  const auto s = ensemble.summary();
  CHECK(std::isinf(s.mean));
  CHECK(s.median_run == Approx(3.0));  // run averages 1, 2, 3, 4, inf
  CHECK(s.fraction_inside <= 0.5);     // the last two steps are infinite
  const auto runs = ensemble.runAverages();
  REQUIRE(runs.size() == 5);
  CHECK(std::isinf(runs[4]));
  // Runs of different lengths: each step is averaged over the runs that recorded it.
  NeesEnsemble ragged(1);
  ragged.add(0, 0, 1.0);
  ragged.add(0, 1, 3.0);
  ragged.add(1, 0, 2.0);
  std::vector<int> counts;
  const auto averages = ragged.stepAverages(&counts);
  CHECK(averages[0] == Approx(1.5));
  CHECK(averages[1] == Approx(3.0));
  CHECK(counts == std::vector<int>{2, 1});
  CHECK(ragged.summary().median_run == Approx(2.0));  // run averages 2 and 2
}

TEST_CASE("NeesEnsemble and NisTally refuse what is not a NEES or NIS", "[consistency]") {
  CHECK_THROWS_WITH(NeesEnsemble(0), Contains("dof must be > 0"));
  NeesEnsemble ensemble(3);
  CHECK_THROWS_WITH(ensemble.summary(), Contains("no samples"));
  CHECK_THROWS_WITH(ensemble.add(0, 0, NAN), Contains("NaN or negative"));
  CHECK_THROWS_WITH(ensemble.add(0, 0, -1.0), Contains("NaN or negative"));
  CHECK_THROWS_WITH(ensemble.add(-1, 0, 1.0), Contains("negative run or step"));
  ensemble.add(0, 0, 1.0);
  CHECK_THROWS_WITH(ensemble.add(0, 0, 2.0), Contains("already has a value at step 0"));
  CHECK_THROWS_WITH(NisTally(0), Contains("dof must be > 0"));
  NisTally tally(2);
  CHECK_THROWS_WITH(tally.bounds(), Contains("no samples"));
  CHECK_THROWS_WITH(tally.add(INFINITY), Contains("not a NIS"));
  CHECK_THROWS_WITH(tally.add(-0.5), Contains("not a NIS"));
  CHECK_THROWS_WITH(tally.merge(NisTally(3)), Contains("differ"));
  CHECK(tally.count() == 0);
}

TEST_CASE("NisTally: chi-square samples have the mean and the exceedance rate they should", "[consistency]") {
  std::mt19937_64 rng(7);
  NisTally first(2), second(2);
  for (int i = 0; i < 20000; ++i) (i % 2 ? first : second).add(chiSquareSample(2, rng));
  first.merge(second);
  CHECK(first.count() == 20000);
  const auto [lo, hi] = first.bounds();
  CHECK(lo < 2.0);
  CHECK(hi > 2.0);
  // 20000 samples: the mean has sd 2 / sqrt(20000) = 0.014, the share above the 95% gate
  // sd sqrt(0.05 * 0.95 / 20000) = 0.0015.
  CHECK(first.mean() == Approx(2.0).margin(0.06));
  CHECK(first.fractionAbove() == Approx(0.05).margin(0.006));
  CHECK(first.gateProbability() == 0.95);
}
