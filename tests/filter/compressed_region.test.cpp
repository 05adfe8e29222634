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

/// P with `d` zero rows and columns inserted before row `at` (and x with d zeros).
MatrixXd inserted(const MatrixXd& P, int at, int d) {
  const int n = static_cast<int>(P.rows());
  MatrixXd out = MatrixXd::Zero(n + d, n + d);
  out.topLeftCorner(at, at) = P.topLeftCorner(at, at);
  out.bottomLeftCorner(n - at, at) = P.bottomLeftCorner(n - at, at);
  out.topRightCorner(at, n - at) = P.topRightCorner(at, n - at);
  out.bottomRightCorner(n - at, n - at) = P.bottomRightCorner(n - at, n - at);
  return out;
}
VectorXd inserted(const VectorXd& x, int at, int d) {
  VectorXd out = VectorXd::Zero(x.size() + d);
  out.head(at) = x.head(at);
  out.tail(x.size() - at) = x.tail(x.size() - at);
  return out;
}

/// The plain EKF on the whole state and the compressed one, fed the same inputs. The active
/// part is the first a coordinates of both (the robot, then landmarks), as the filter keeps it.
struct Pair {
  VectorXd x_plain, x_compressed;
  MatrixXd P_plain, P_compressed;
  sylva::detail::CompressedRegion region;
  /// Whether a region's first update rescales the accumulators by a factor of P_AA, as the
  /// filter does (CompressedRegion, "Scaled accumulators").
  bool scale = false;

  Pair(const VectorXd& x0, const MatrixXd& P0) : x_plain(x0), x_compressed(x0), P_plain(P0), P_compressed(P0) {}

  int dim() const { return static_cast<int>(x_plain.size()); }

  /// The robot (the first three coordinates) moves: x_r <- J x_r + u, P <- F P F^T + G Q G^T.
  void predict(const Eigen::Matrix3d& J, const VectorXd& u, const MatrixXd& Q) {
    const int n = dim();
    MatrixXd F = MatrixXd::Identity(n, n);
    F.topLeftCorner(kRobotDim, kRobotDim) = J;
    x_plain.head(kRobotDim) = J * x_plain.head(kRobotDim) + u;
    P_plain = F * P_plain * F.transpose();
    P_plain.topLeftCorner(kRobotDim, kRobotDim) += Q;

    const int a = region.activeDim();
    MatrixXd J_A = MatrixXd::Identity(a, a);
    J_A.topLeftCorner(kRobotDim, kRobotDim) = J;
    x_compressed.head(kRobotDim) = J * x_compressed.head(kRobotDim) + u;
    MatrixXd P_AA = J_A * P_compressed.topLeftCorner(a, a) * J_A.transpose();
    P_AA.topLeftCorner(kRobotDim, kRobotDim) += Q;
    P_compressed.topLeftCorner(a, a) = P_AA;
    region.predictRobot<kRobotDim>(J);
  }

  /// A linear measurement z = H_A x_A + noise of covariance R.
  void update(const MatrixXd& H_A, const MatrixXd& R, const VectorXd& z) {
    const int a = region.activeDim();
    const int m = static_cast<int>(H_A.rows());
    MatrixXd H = MatrixXd::Zero(m, dim());
    H.leftCols(a) = H_A;
    {
      const VectorXd nu = z - H * x_plain;
      const MatrixXd S = H * P_plain * H.transpose() + R;
      const MatrixXd K = Eigen::LLT<MatrixXd>(S).solve(H * P_plain).transpose();
      x_plain += K * nu;
      P_plain -= K * S * K.transpose();
      P_plain = (0.5 * (P_plain + P_plain.transpose())).eval();
    }
    const MatrixXd P_AA = P_compressed.topLeftCorner(a, a);
    const VectorXd nu = z - H_A * x_compressed.head(a);
    const MatrixXd S = H_A * P_AA * H_A.transpose() + R;
    const Eigen::LLT<MatrixXd> S_llt(S);
    const MatrixXd K_A = S_llt.solve(H_A * P_AA).transpose();
    const MatrixXd W = K_A * MatrixXd(S_llt.matrixL());  // P_AA H_A^T L^-T
    const int b = dim() - a;
    const bool first = scale && !region.scaled();
    const MatrixXd& phi = first ? region.stageScale(P_AA, P_compressed.block(a, 0, b, a)) : region.phi();
    auto HphiT = region.hphiTransposed(m);
    HphiT = (H_A * phi).transpose();
    region.stageUpdate(S_llt.matrixL(), nu, W);
    if (first) region.commitScale(P_compressed.block(a, 0, b, a));  // the stored rows become V R^-T
    region.commitUpdate();
    x_compressed.head(a) += K_A * nu;
    MatrixXd P_AA_next = P_AA - K_A * S * K_A.transpose();
    P_compressed.topLeftCorner(a, a) = 0.5 * (P_AA_next + P_AA_next.transpose());
  }

  /// A landmark of two coordinates enters the state from the robot and a measurement z with
  /// noise R: l = J_r x_r + J_z z. Both states take it at coordinate a (the compressed one
  /// appends it to the active part).
  void add(const MatrixXd& J_r, const MatrixXd& J_z, const VectorXd& z, const MatrixXd& R) {
    const int a = region.activeDim();
    const auto extend = [&](VectorXd& x, MatrixXd& P, int cols) {
      x = inserted(x, a, 2);
      P = inserted(P, a, 2);
      x.segment(a, 2) = J_r * x.head(kRobotDim) + J_z * z;
      const MatrixXd cross = J_r * P.topRows(kRobotDim).leftCols(cols);
      P.block(a, 0, 2, cols) = cross;
      P.block(0, a, cols, 2) = cross.transpose();
      P.block(a, a, 2, 2) = J_r * P.topLeftCorner(kRobotDim, kRobotDim) * J_r.transpose() + J_z * R * J_z.transpose();
    };
    extend(x_plain, P_plain, dim() + 2);
    extend(x_compressed, P_compressed, a + 2);  // its cross-covariance with B stays zero
    region.stageExtend<kRobotDim>(J_r);
    region.commitExtend();
  }

  /// The global update on the lower triangle, as the filter stores it; the upper triangle is
  /// then filled in from it (the update neither reads nor writes it: it is made stale first).
  void globalUpdate() {
    P_compressed.triangularView<Eigen::StrictlyUpper>().setConstant(std::nan(""));
    region.globalUpdate(P_compressed, x_compressed);
    P_compressed = P_compressed.selfadjointView<Eigen::Lower>();
  }

  /// Both states with their landmark blocks (of two coordinates) in a new random order.
  void shuffleLandmarks(Random& random) {
    const int landmarks = (dim() - kRobotDim) / 2;
    std::vector<int> order(landmarks);
    std::iota(order.begin(), order.end(), 0);
    std::shuffle(order.begin(), order.end(), random.rng);
    Eigen::VectorXi perm(dim());
    for (int k = 0; k < kRobotDim; ++k) perm[k] = k;
    for (int k = 0; k < landmarks; ++k) {
      perm[kRobotDim + 2 * k] = kRobotDim + 2 * order[k];
      perm[kRobotDim + 2 * k + 1] = kRobotDim + 2 * order[k] + 1;
    }
    const auto permuted = [&](VectorXd& x, MatrixXd& P) {
      VectorXd y(dim());
      MatrixXd Q(dim(), dim());
      for (int i = 0; i < dim(); ++i) {
        y[i] = x[perm[i]];
        for (int j = 0; j < dim(); ++j) Q(i, j) = P(perm[i], perm[j]);
      }
      x = y;
      P = Q;
    };
    permuted(x_plain, P_plain);
    permuted(x_compressed, P_compressed);
  }

  /// Largest difference between the two, relative to the largest entry.
  double meanDifference() const { return (x_plain - x_compressed).cwiseAbs().maxCoeff() / x_plain.cwiseAbs().maxCoeff(); }
  double covarianceDifference() const {
    return (P_plain - P_compressed).cwiseAbs().maxCoeff() / P_plain.cwiseAbs().maxCoeff();
  }
};

/// `steps` local steps in the current region: a prediction, an update of 1 to 6 rows (up to 4
/// taken in place, more through the staged products: CompressedRegion::stageUpdate), or
/// (with `adds`) a new landmark.
void localSteps(Pair& pair, Random& random, int steps, bool adds = false) {
  for (int s = 0; s < steps; ++s) {
    const int kind = random.uniform(0, adds ? 2 : 1);
    if (kind == 0) {
      const Eigen::Matrix3d J = Eigen::Matrix3d::Identity() + 0.1 * Eigen::Matrix3d(random.normal(kRobotDim, kRobotDim));
      pair.predict(J, 0.3 * random.normal(kRobotDim, 1), random.spd(kRobotDim, 0.01));
    } else if (kind == 1) {
      const int m = random.uniform(1, 6);
      pair.update(random.normal(m, pair.region.activeDim()), random.spd(m, 0.05), 3.0 * random.normal(m, 1));
    } else {
      pair.add(random.normal(2, kRobotDim), random.normal(2, 2), random.normal(2, 1), random.spd(2, 0.05));
    }
  }
}

/// The robot and `landmarks` landmarks of two coordinates: the size of an active part.
int activeDim(int landmarks) { return kRobotDim + 2 * landmarks; }

}  // namespace

TEST_CASE("compressed EKF: local steps and one global update give the plain EKF's mean and covariance",
          "[filter][compressed]") {
  for (unsigned seed = 1; seed <= 20; ++seed) {
    INFO("seed " << seed);
    Random random(seed);
    const int landmarks = 25;
    const int n = kRobotDim + 2 * landmarks;
    Pair pair(4.0 * random.normal(n, 1), random.spd(n, 1.0));
    pair.scale = seed % 2 == 0;
    INFO("scaled accumulators: " << pair.scale);
    pair.region.begin(activeDim(random.uniform(1, 8)));
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
          "[filter][compressed][slow]") {
  for (unsigned seed = 1; seed <= 10; ++seed) {
    INFO("seed " << seed);
    Random random(100 + seed);
    const int landmarks = 30;
    const int n = kRobotDim + 2 * landmarks;
    Pair pair(4.0 * random.normal(n, 1), random.spd(n, 1.0));
    pair.scale = seed % 2 == 0;
    INFO("scaled accumulators: " << pair.scale);
    for (int region = 0; region < 6; ++region) {
      INFO("region " << region);
      pair.shuffleLandmarks(random);
      pair.region.begin(activeDim(random.uniform(0, 10)));
      localSteps(pair, random, random.uniform(1, 30), /*adds=*/true);
      pair.globalUpdate();
      CHECK(pair.meanDifference() <= 1e-9);
      CHECK(pair.covarianceDifference() <= 1e-9);
    }
  }
}

/// A map whose landmarks are known far better relative to the robot than absolutely (each is
/// the robot's position plus an offset of 1e-3 m standard deviation; the robot's own is 1 m),
/// observed relative to the robot with 1e-4 m noise: P_AA's condition number is about 1e6 and
/// the information H^T S^-1 H is about 1e8 in the directions the sensor pins down, where the
/// stored cross-covariances of the passive landmarks are small.
Pair correlatedMap(Random& random, int landmarks) {
  const int n = kRobotDim + 2 * landmarks;
  MatrixXd T = MatrixXd::Zero(n, n);  // state = T [robot; offsets]
  T.topLeftCorner(kRobotDim, kRobotDim).setIdentity();
  for (int k = 0; k < landmarks; ++k) {
    T.block(kRobotDim + 2 * k, 0, 2, 2).setIdentity();
    T.block(kRobotDim + 2 * k, kRobotDim + 2 * k, 2, 2).setIdentity();
  }
  VectorXd sigma = VectorXd::Constant(n, 1e-3);
  sigma.head(kRobotDim) << 1.0, 1.0, 0.1;
  const MatrixXd P = T * sigma.array().square().matrix().asDiagonal() * T.transpose();
  return Pair(10.0 * random.normal(n, 1), 0.5 * (P + P.transpose()));
}

/// `steps` rounds of a prediction (a random walk of the robot) and an update of the
/// robot-relative positions of 3 landmarks of the active part.
void preciseSteps(Pair& pair, Random& random, int steps) {
  const int landmarks = (pair.region.activeDim() - kRobotDim) / 2;
  for (int s = 0; s < steps; ++s) {
    pair.predict(Eigen::Matrix3d::Identity(), 0.1 * random.normal(kRobotDim, 1), 1e-6 * MatrixXd::Identity(kRobotDim, kRobotDim));
    MatrixXd H = MatrixXd::Zero(6, pair.region.activeDim());
    for (int i = 0; i < 3; ++i) {
      const int l = random.uniform(0, landmarks - 1);
      H.block(2 * i, 0, 2, 2) = -Eigen::Matrix2d::Identity();
      H.block(2 * i, kRobotDim + 2 * l, 2, 2).setIdentity();
    }
    const VectorXd z = H * pair.x_plain.head(pair.region.activeDim()) + 1e-4 * random.normal(6, 1);
    pair.update(H, 1e-8 * MatrixXd::Identity(6, 6), z);
  }
}

TEST_CASE("compressed EKF: scaled accumulators keep a precise sensor's global update at round-off",
          "[filter][compressed]") {
  // Unscaled, psi grows to about 1/sigma^2 = 1e8 in the directions where the stored rows V
  // are small, and V psi V^T loses up to about eps |V|^2 |psi| ~ 1e-8 of |P| to cancellation.
  // Scaled, every accumulator is on the scale of P (CompressedRegion, "Scaled
  // accumulators"), so the covariance's error is that of the products the global update
  // forms, a few eps |P| per entry and step: under 40 steps x 23 active rows x eps ~ 1e-13.
  // The mean is held to the suite's usual 1e-9 of its largest entry (here both forms stay
  // far under it: the innovations of a 1e-4 m sensor against coordinates of tens of metres
  // carry their own cancellation, in the plain filter too).
  double worst_unscaled = 0.0;
  for (unsigned seed = 1; seed <= 5; ++seed) {
    INFO("seed " << seed);
    for (const bool scale : {false, true}) {
      INFO("scaled accumulators: " << scale);
      Random random(300 + seed);  // the same inputs for both
      Pair pair = correlatedMap(random, 30);
      pair.scale = scale;
      pair.region.begin(activeDim(10));
      preciseSteps(pair, random, 40);
      pair.globalUpdate();
      CHECK(pair.meanDifference() <= 1e-9);
      if (scale) {
        CHECK(pair.covarianceDifference() <= 1e-13);
      } else {
        worst_unscaled = std::max(worst_unscaled, pair.covarianceDifference());
      }
    }
  }
  INFO("worst unscaled covariance difference " << worst_unscaled);
  CHECK(worst_unscaled > 1e-11);  // the case this test is for: without scaling the bound fails
}

TEST_CASE("compressed EKF: a global update with no local step changes nothing", "[filter][compressed]") {
  Random random(7);
  const int n = kRobotDim + 2 * 12;
  const VectorXd x0 = random.normal(n, 1);
  const MatrixXd P0 = random.spd(n, 1.0);
  VectorXd x = x0;
  MatrixXd P = P0;
  sylva::detail::CompressedRegion region;
  region.begin(activeDim(4));
  region.globalUpdate(P, x);
  CHECK((x.array() == x0.array()).all());
  CHECK((P.array() == P0.array()).all());
}

TEST_CASE("compressed EKF: the accumulators start as identity and zeros, and follow a prediction",
          "[filter][compressed]") {
  Random random(3);
  sylva::detail::CompressedRegion region;
  region.begin(5);
  CHECK(region.activeDim() == 5);
  CHECK(region.phi().isIdentity(0.0));
  CHECK(region.psi().isZero(0.0));
  CHECK(region.theta().isZero(0.0));
  const Eigen::Matrix3d J = Eigen::Matrix3d::Identity() + 0.1 * Eigen::Matrix3d(random.normal(3, 3));
  region.predictRobot<3>(J);
  MatrixXd expected = MatrixXd::Identity(5, 5);
  expected.topLeftCorner(3, 3) = J;
  CHECK((region.phi() - expected).cwiseAbs().maxCoeff() == 0.0);
  CHECK(region.steps() == 1);
}

}  // namespace unity_filter_compressed_region
