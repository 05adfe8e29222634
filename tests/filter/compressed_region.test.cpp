// detail::CompressedRegion, the compressed EKF's bookkeeping (Guivant and Nebot 2001): local
// predictions and updates that touch only the active part, then one global update, must give
// the plain EKF's mean and covariance on the same inputs.

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <sylva/detail/compressed_region.hpp>

#include "sylva_catch.hpp"

// Own namespace: the tests of a folder are compiled as one unity translation unit.
namespace unity_filter_compressed_region {

namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;

constexpr int kRobotDim = 3;

struct Random {
  std::mt19937_64 rng;
  explicit Random(unsigned seed) : rng(seed) {}
  double normal() { return std::normal_distribution<double>(0.0, 1.0)(rng); }
  MatrixXd normal(int rows, int cols) {
    MatrixXd m(rows, cols);
    for (int j = 0; j < cols; ++j)
      for (int i = 0; i < rows; ++i) m(i, j) = normal();
    return m;
  }
  /// A well-conditioned symmetric positive-definite matrix, exactly symmetric.
  MatrixXd spd(int n, double scale) {
    const MatrixXd A = normal(n, n);
    const MatrixXd P = scale * (A * A.transpose() / n + 0.2 * MatrixXd::Identity(n, n));
    return 0.5 * (P + P.transpose());
  }
  int uniform(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); }
};

MatrixXd gather(const MatrixXd& P, const std::vector<int>& idx) {
  MatrixXd out(idx.size(), idx.size());
  for (std::size_t j = 0; j < idx.size(); ++j)
    for (std::size_t i = 0; i < idx.size(); ++i) out(i, j) = P(idx[i], idx[j]);
  return out;
}
void scatter(MatrixXd& P, const std::vector<int>& idx, const MatrixXd& block) {
  for (std::size_t j = 0; j < idx.size(); ++j)
    for (std::size_t i = 0; i < idx.size(); ++i) P(idx[i], idx[j]) = block(i, j);
}

/// The plain EKF on the whole state and the compressed one, fed the same inputs.
struct Pair {
  VectorXd x_plain, x_compressed;
  MatrixXd P_plain, P_compressed;
  sylva::detail::CompressedRegion region;

  Pair(const VectorXd& x0, const MatrixXd& P0) : x_plain(x0), x_compressed(x0), P_plain(P0), P_compressed(P0) {}

  int dim() const { return static_cast<int>(x_plain.size()); }

  /// The robot (coordinates 0..2, the first three of the active list) moves: x_r <- J x_r + u,
  /// P <- F P F^T + G Q G^T.
  void predict(const MatrixXd& J, const VectorXd& u, const MatrixXd& Q) {
    const int n = dim();
    MatrixXd F = MatrixXd::Identity(n, n);
    F.topLeftCorner(kRobotDim, kRobotDim) = J;
    x_plain.head(kRobotDim) = J * x_plain.head(kRobotDim) + u;
    P_plain = F * P_plain * F.transpose();
    P_plain.topLeftCorner(kRobotDim, kRobotDim) += Q;

    const std::vector<int>& A = region.active();
    const int a = region.activeDim();
    MatrixXd J_A = MatrixXd::Identity(a, a);
    J_A.topLeftCorner(kRobotDim, kRobotDim) = J;
    x_compressed.head(kRobotDim) = J * x_compressed.head(kRobotDim) + u;
    MatrixXd P_AA = J_A * gather(P_compressed, A) * J_A.transpose();
    P_AA.topLeftCorner(kRobotDim, kRobotDim) += Q;
    scatter(P_compressed, A, P_AA);
    region.predict(0, J);
  }

  /// A linear measurement z = H_A x_A + noise of covariance R.
  void update(const MatrixXd& H_A, const MatrixXd& R, const VectorXd& z) {
    const std::vector<int>& A = region.active();
    const int m = static_cast<int>(H_A.rows());
    MatrixXd H = MatrixXd::Zero(m, dim());
    for (std::size_t k = 0; k < A.size(); ++k) H.col(A[k]) = H_A.col(static_cast<Eigen::Index>(k));
    {
      const VectorXd nu = z - H * x_plain;
      const MatrixXd S = H * P_plain * H.transpose() + R;
      const MatrixXd K = Eigen::LLT<MatrixXd>(S).solve(H * P_plain).transpose();
      x_plain += K * nu;
      P_plain -= K * S * K.transpose();
      P_plain = (0.5 * (P_plain + P_plain.transpose())).eval();
    }
    VectorXd x_A(A.size());
    for (std::size_t k = 0; k < A.size(); ++k) x_A[static_cast<Eigen::Index>(k)] = x_compressed[A[k]];
    const MatrixXd P_AA = gather(P_compressed, A);
    const VectorXd nu = z - H_A * x_A;
    const MatrixXd S = H_A * P_AA * H_A.transpose() + R;
    const Eigen::LLT<MatrixXd> S_llt(S);
    const MatrixXd K_A = S_llt.solve(H_A * P_AA).transpose();
    region.update(H_A, K_A, S_llt, nu);
    x_A += K_A * nu;
    MatrixXd P_AA_next = P_AA - K_A * S * K_A.transpose();
    P_AA_next = (0.5 * (P_AA_next + P_AA_next.transpose())).eval();
    for (std::size_t k = 0; k < A.size(); ++k) x_compressed[A[k]] = x_A[static_cast<Eigen::Index>(k)];
    scatter(P_compressed, A, P_AA_next);
  }

  /// The global update on the lower triangle, as the filter stores it; the upper triangle is
  /// then filled in from it (the update neither reads nor writes it: it is made stale first).
  void globalUpdate() {
    P_compressed.triangularView<Eigen::StrictlyUpper>().setConstant(std::nan(""));
    region.globalUpdate(P_compressed, x_compressed);
    P_compressed = P_compressed.selfadjointView<Eigen::Lower>();
  }

  /// Largest difference between the two, relative to the largest entry.
  double meanDifference() const { return (x_plain - x_compressed).cwiseAbs().maxCoeff() / x_plain.cwiseAbs().maxCoeff(); }
  double covarianceDifference() const {
    return (P_plain - P_compressed).cwiseAbs().maxCoeff() / P_plain.cwiseAbs().maxCoeff();
  }
};

/// The robot and `landmarks` random landmarks (of two coordinates each) out of `total`,
/// the landmark coordinates in random order.
std::vector<int> activeSet(Random& random, int landmarks, int total) {
  std::vector<int> ids(total);
  std::iota(ids.begin(), ids.end(), 0);
  std::shuffle(ids.begin(), ids.end(), random.rng);
  std::vector<int> active{0, 1, 2};
  std::vector<int> coordinates;
  for (int k = 0; k < landmarks; ++k) {
    coordinates.push_back(kRobotDim + 2 * ids[k]);
    coordinates.push_back(kRobotDim + 2 * ids[k] + 1);
  }
  std::shuffle(coordinates.begin(), coordinates.end(), random.rng);
  active.insert(active.end(), coordinates.begin(), coordinates.end());
  return active;
}

/// `steps` local steps in the current region: a prediction or an update of 2 to 6 rows.
void localSteps(Pair& pair, Random& random, int steps) {
  const int a = pair.region.activeDim();
  for (int s = 0; s < steps; ++s) {
    if (random.uniform(0, 1) == 0) {
      const MatrixXd J = MatrixXd::Identity(kRobotDim, kRobotDim) + 0.1 * random.normal(kRobotDim, kRobotDim);
      pair.predict(J, 0.3 * random.normal(kRobotDim, 1), random.spd(kRobotDim, 0.01));
    } else {
      const int m = random.uniform(2, 6);
      pair.update(random.normal(m, a), random.spd(m, 0.05), 3.0 * random.normal(m, 1));
    }
  }
}

}  // namespace

TEST_CASE("compressed EKF: local steps and one global update give the plain EKF's mean and covariance",
          "[filter][compressed]") {
  for (unsigned seed = 1; seed <= 20; ++seed) {
    INFO("seed " << seed);
    Random random(seed);
    const int landmarks = 25;
    const int n = kRobotDim + 2 * landmarks;
    Pair pair(4.0 * random.normal(n, 1), random.spd(n, 1.0));
    pair.region.begin(activeSet(random, random.uniform(1, 8), landmarks));
    localSteps(pair, random, 40);
    CHECK(pair.region.steps() == 40);
    // Before the global update the passive part is stale (the test would be empty otherwise).
    CHECK(pair.covarianceDifference() > 1e-3);
    pair.globalUpdate();
    CHECK(pair.meanDifference() <= 1e-9);
    CHECK(pair.covarianceDifference() <= 1e-9);
    CHECK(pair.region.steps() == 0);
  }
}

TEST_CASE("compressed EKF: a run through several regions stays equal to the plain EKF at every global update",
          "[filter][compressed]") {
  for (unsigned seed = 1; seed <= 10; ++seed) {
    INFO("seed " << seed);
    Random random(100 + seed);
    const int landmarks = 30;
    const int n = kRobotDim + 2 * landmarks;
    Pair pair(4.0 * random.normal(n, 1), random.spd(n, 1.0));
    for (int region = 0; region < 6; ++region) {
      INFO("region " << region);
      pair.region.begin(activeSet(random, random.uniform(0, 10), landmarks));
      localSteps(pair, random, random.uniform(1, 30));
      pair.globalUpdate();
      CHECK(pair.meanDifference() <= 1e-9);
      CHECK(pair.covarianceDifference() <= 1e-9);
    }
  }
}

TEST_CASE("compressed EKF: a global update with no local step changes nothing", "[filter][compressed]") {
  Random random(7);
  const int n = kRobotDim + 2 * 12;
  const VectorXd x0 = random.normal(n, 1);
  const MatrixXd P0 = random.spd(n, 1.0);
  VectorXd x = x0;
  MatrixXd P = P0;
  sylva::detail::CompressedRegion region;
  region.begin(activeSet(random, 4, 12));
  region.globalUpdate(P, x);
  CHECK((x.array() == x0.array()).all());
  CHECK((P.array() == P0.array()).all());
}

TEST_CASE("compressed EKF: the accumulators start as identity and zeros, and follow a prediction",
          "[filter][compressed]") {
  Random random(3);
  sylva::detail::CompressedRegion region;
  region.begin({0, 1, 2, 7, 8});
  CHECK(region.activeDim() == 5);
  CHECK(region.phi().isIdentity(0.0));
  CHECK(region.psi().isZero(0.0));
  CHECK(region.theta().isZero(0.0));
  const MatrixXd J = MatrixXd::Identity(3, 3) + 0.1 * random.normal(3, 3);
  region.predict(0, J);
  MatrixXd expected = MatrixXd::Identity(5, 5);
  expected.topLeftCorner(3, 3) = J;
  CHECK((region.phi() - expected).cwiseAbs().maxCoeff() == 0.0);
  CHECK(region.steps() == 1);
}

}  // namespace unity_filter_compressed_region
