// The invariant EKF (LinearizationPoint::kInvariant; Barrau and Bonnabel 2015): the filter,
// which keeps its covariance in additive coordinates, against a right-invariant EKF written
// here directly on the group SE_{1+k}(2) (covariance of the invariant error, the exponential
// taken as a matrix exponential); the property that lets the filter keep the textbook
// prediction; the heading-variance bound that the invariant filter keeps and the textbook
// one breaks; and the refusals.

#include <cmath>
#include <random>
#include <vector>

#include <unsupported/Eigen/MatrixFunctions>

#include <Eigen/LU>
#include <sylva/core/angles.hpp>
#include <sylva/filter/ekf.hpp>
#include <sylva/landmarks/point2.hpp>
#include <sylva/landmarks/point3.hpp>
#include <sylva/landmarks/tree_xyr.hpp>
#include <sylva/measurements/range_bearing.hpp>
#include <sylva/measurements/range_bearing_diameter.hpp>
#include <sylva/motion/ackermann_2d.hpp>
#include <sylva/motion/constant_velocity_3d.hpp>
#include <sylva/motion/odometry_2d.hpp>
#include <sylva/motion/unicycle_2d.hpp>

#include "filter/planar_scene.hpp"
#include "filter_snapshot.hpp"
#include "sylva_catch.hpp"

using namespace sylva;

namespace unity_filter_invariant_ekf {

using Filter = Ekf<Unicycle2D, Point2>;

/// T(x): the additive error of the state [x, y, theta, p_1, ..., p_k] as a function of the
/// right-invariant error xi, delta = T(x) xi (delta_p = xi_p + xi_theta J p).
Eigen::MatrixXd additiveFromInvariant(const Eigen::VectorXd& x) {
  const Eigen::Index n = x.size();
  Eigen::MatrixXd T = Eigen::MatrixXd::Identity(n, n);
  for (Eigen::Index o = 0; o < n; o += (o == 0 ? 3 : 2)) {
    T(o, 2) = -x[o + 1];
    T(o + 1, 2) = x[o];
  }
  return T;
}

/// A right-invariant EKF for a unicycle among Point2 landmarks, written on the group: the
/// state chi = (R(theta), robot position, landmark positions), the error
/// eta = chi chi_hat^-1 = exp(xi), the covariance that of xi. Dense, no tricks.
struct InvariantReference {
  Eigen::VectorXd x;  // [x, y, theta, p_1, ..., p_k], the filter's layout
  Eigen::MatrixXd P;  // covariance of xi
  std::vector<Id> ids;

  InvariantReference(const Vec<3>& x0, const Mat<3, 3>& P0_additive) : x(x0) {
    const Eigen::MatrixXd T_inv = additiveFromInvariant(x).inverse();
    P = T_inv * P0_additive * T_inv.transpose();
  }

  int offsetOf(Id id) const {
    for (std::size_t i = 0; i < ids.size(); ++i)
      if (ids[i] == id) return 3 + 2 * static_cast<int>(i);
    return -1;
  }

  /// A rigid increment in the robot frame leaves the invariant error unchanged; the noise
  /// enters through T(x+)^-1 applied to the robot's noise Jacobian.
  void predict(const Vec<2>& u, double dt, const Gaussian<2>& q) {
    Mat<3, 2> G;
    x.head<3>() = Unicycle2D()(Vec<3>(x.head<3>()), u, dt, {}, G);
    Eigen::MatrixXd G_full = Eigen::MatrixXd::Zero(x.size(), 2);
    G_full.topRows<3>() = G;
    const Eigen::MatrixXd G_xi = additiveFromInvariant(x).inverse() * G_full;
    P += G_xi * q.covariance() * G_xi.transpose();
  }

  /// The new landmark's invariant error: xi_p = J_l_x T_r xi_r + J_l_z n - xi_theta J p.
  void add(Id id, const Vec<2>& z, const Gaussian<2>& r) {
    Mat<2, 3> J_x;
    Mat<2, 2> J_z;
    const Vec<2> p = InverseRangeBearing()(Vec<3>(x.head<3>()), z, J_x, J_z);
    const Eigen::Index n = x.size();
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(2, n);
    A.leftCols<3>() = J_x * additiveFromInvariant(Eigen::VectorXd(x.head<3>()));
    A(0, 2) -= -p.y();
    A(1, 2) -= p.x();
    Eigen::MatrixXd P_new(n + 2, n + 2);
    P_new.topLeftCorner(n, n) = P;
    P_new.topRightCorner(n, 2) = P * A.transpose();
    P_new.bottomLeftCorner(2, n) = A * P;
    P_new.bottomRightCorner(2, 2) = A * P * A.transpose() + J_z * r.covariance() * J_z.transpose();
    P = P_new;
    x.conservativeResize(n + 2);
    x.tail<2>() = p;
    ids.push_back(id);
  }

  /// One stacked update: H_xi = H(x) T(x), xi = K nu, chi <- exp(xi) chi, Joseph covariance.
  void update(const std::vector<Observation<RangeBearing>>& observations) {
    const Eigen::Index n = x.size();
    const Eigen::Index m = 2 * static_cast<Eigen::Index>(observations.size());
    Eigen::MatrixXd H = Eigen::MatrixXd::Zero(m, n);
    Eigen::MatrixXd R = Eigen::MatrixXd::Zero(m, m);
    Eigen::VectorXd nu(m);
    for (std::size_t a = 0; a < observations.size(); ++a) {
      const int o = offsetOf(observations[a].id);
      Mat<2, 3> H_x;
      Mat<2, 2> H_l;
      const Vec<2> z_hat = RangeBearing()(Vec<3>(x.head<3>()), Vec<2>(x.segment<2>(o)), H_x, H_l);
      const Eigen::Index row = 2 * static_cast<Eigen::Index>(a);
      H.block(row, 0, 2, 3) = H_x;
      H.block(row, o, 2, 2) = H_l;
      R.block(row, row, 2, 2) = observations[a].noise.covariance();
      nu.segment<2>(row) = RangeBearing().residual(observations[a].z, z_hat);
    }
    const Eigen::MatrixXd H_xi = H * additiveFromInvariant(x);
    const Eigen::MatrixXd S = H_xi * P * H_xi.transpose() + R;
    const Eigen::MatrixXd K = P * H_xi.transpose() * S.inverse();
    const Eigen::VectorXd xi = K * nu;
    // exp(xi) acts on every position p as the SE(2) element (xi_theta, xi_p) on [p; 1].
    for (Eigen::Index o = 0; o < n; o += (o == 0 ? 3 : 2)) {
      Eigen::Matrix3d a = Eigen::Matrix3d::Zero();
      a(0, 1) = -xi[2];
      a(1, 0) = xi[2];
      a(0, 2) = xi[o];
      a(1, 2) = xi[o + 1];
      const Eigen::Matrix3d E = a.exp();
      x.segment<2>(o) = E.topLeftCorner<2, 2>() * x.segment<2>(o) + E.topRightCorner<2, 1>();
    }
    x[2] = wrapAngle(x[2] + xi[2]);
    const Eigen::MatrixXd I_KH = Eigen::MatrixXd::Identity(n, n) - K * H_xi;
    P = I_KH * P * I_KH.transpose() + K * R * K.transpose();
  }

  Eigen::MatrixXd additiveCovariance() const {
    const Eigen::MatrixXd T = additiveFromInvariant(x);
    return T * P * T.transpose();
  }
};

const Gaussian<2> kControlNoise = Gaussian<2>::sigmas(Vec<2>(0.1, 0.08));
const Gaussian<2> kSensorNoise = Gaussian<2>::sigmas(Vec<2>(0.1, 0.04));

/// The scene of the comparisons: `steps` steps of a noisy circle, readings within 5 m, the
/// seen landmarks fused as one batch (or one by one), new ones added after the update. Calls
/// `step(k)` after each step.
template <typename FilterT, typename Step>
void driveCircle(FilterT& ekf, InvariantReference* reference, int steps, unsigned seed, Fusion fusion, Step&& step) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal;
  // The robot drives a circle of radius 4 m (1 m/s, 0.25 rad/s); landmarks 2 m and 6 m from its centre.
  const std::vector<Vec<2>> landmarks = sylva_test::landmarksOnTwoRings(12, 4.0, 2.0, 6.0);
  const Vec<2> u_true(1.0, 0.25);
  const double dt = 0.5;
  Vec<3> truth = Vec<3>::Zero();
  for (int k = 0; k < steps; ++k) {
    truth = Unicycle2D()(truth, u_true, dt);
    const Vec<2> u(u_true[0] + 0.1 * normal(rng), u_true[1] + 0.08 * normal(rng));
    ekf.predict(u, dt, kControlNoise);
    if (reference) reference->predict(u, dt, kControlNoise);
    std::vector<Observation<RangeBearing>> seen;
    std::vector<std::pair<Id, Vec<2>>> fresh;
    for (std::size_t i = 0; i < landmarks.size(); ++i) {
      const Vec<2> z_true = RangeBearing()(truth, landmarks[i]);
      if (z_true[0] > 5.0) continue;
      const Vec<2> z(z_true[0] + 0.1 * normal(rng), wrapAngle(z_true[1] + 0.04 * normal(rng)));
      const Id id = static_cast<Id>(i);
      if (ekf.contains(id))
        seen.push_back({id, z, kSensorNoise});
      else
        fresh.emplace_back(id, z);
    }
    ekf.update(RangeBearing(), seen, fusion);
    if (reference) {
      if (fusion == Fusion::kBatched) {
        if (!seen.empty()) reference->update(seen);
      } else {
        for (const auto& obs : seen) reference->update({obs});
      }
    }
    for (const auto& [id, z] : fresh) {
      ekf.add(id, InverseRangeBearing(), z, kSensorNoise);
      if (reference) reference->add(id, z, kSensorNoise);
    }
    step(k);
  }
}

}  // namespace unity_filter_invariant_ekf

using namespace unity_filter_invariant_ekf;

TEMPLATE_TEST_CASE("invariant EKF: matches a right-invariant EKF written on the group", "[filter][invariant]",
                   (Ekf<Unicycle2D, Point2>), (JosephEkf<Unicycle2D, Point2>)) {
  for (const Fusion fusion : {Fusion::kBatched, Fusion::kSequential}) {
    // The robot starts away from the origin with a full covariance, so T(x) matters at once.
    const Vec<3> x0(1.0, -0.5, 0.3);
    Mat<3, 3> P0;
    P0 << 0.02, 0.005, 0.01, 0.005, 0.03, -0.004, 0.01, -0.004, 0.02;
    TestType ekf(x0, P0);
    ekf.setLinearizationPoint(LinearizationPoint::kInvariant);
    InvariantReference reference(x0, P0);
    // And a textbook filter on the same data, to show the comparison can tell them apart.
    TestType textbook(x0, P0);
    driveCircle(ekf, &reference, 30, 3, fusion, [&](int k) {
      INFO("fusion " << (fusion == Fusion::kBatched ? "batched" : "sequential") << ", step " << k);
      REQUIRE(ekf.dim() == reference.x.size());
      const Eigen::VectorXd mean = ekf.mean();
      Eigen::VectorXd difference = mean - reference.x;
      difference[2] = wrapAngle(difference[2]);
      CHECK(difference.cwiseAbs().maxCoeff() < 1e-9);
      CHECK((ekf.covariance() - reference.additiveCovariance()).cwiseAbs().maxCoeff() < 1e-9);
    });
    driveCircle(textbook, nullptr, 30, 3, fusion, [&](int) {});  // the same noise draws
    CHECK((textbook.mean() - ekf.mean()).cwiseAbs().maxCoeff() > 1e-4);
    CHECK((textbook.covariance() - ekf.covariance()).cwiseAbs().maxCoeff() > 1e-4);
  }
}

namespace unity_filter_invariant_ekf {

/// T(x+)^-1 F T(x) for a robot block alone: the transition of the invariant error.
template <typename Robot>
void checkInvariantTransition(const Robot& robot, const Vec<3>& x, const typename Robot::Control& u, double dt) {
  Mat<3, 3> F;
  const Vec<3> next = robot(x, u, dt, F);
  const Eigen::MatrixXd T = additiveFromInvariant(Eigen::VectorXd(x));
  const Eigen::MatrixXd T_next = additiveFromInvariant(Eigen::VectorXd(next));
  INFO(Robot::kName << " from " << x.transpose() << " to " << next.transpose());
  CHECK((T_next.inverse() * F * T - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() < 1e-12);
}

}  // namespace unity_filter_invariant_ekf

TEST_CASE("invariant EKF: every planar robot's textbook transition moves the invariant error by the identity") {
  // Why kInvariant keeps the textbook predict: F = T(x+) T(x)^-1 exactly for a motion that is
  // a rigid increment in the robot frame, far from the origin and with large turns too.
  for (const Vec<3>& x : {Vec<3>(0.0, 0.0, 0.0), Vec<3>(120.0, -40.0, 2.9), Vec<3>(-3.0, 7.0, -1.2)}) {
    checkInvariantTransition(Unicycle2D(), x, Vec<2>(1.5, 0.4), 0.5);
    checkInvariantTransition(Unicycle2D(), x, Vec<2>(0.0, 3.0), 0.5);  // turning on the spot
    checkInvariantTransition(Odometry2D(), x, Vec<3>(0.8, -0.2, 0.3), 1.0);
    checkInvariantTransition(Ackermann2D(2.83, 0.76), x, Vec<2>(3.0, -0.4), 0.2);
    checkInvariantTransition(Ackermann2D(2.83, 0.76), x, Vec<2>(-1.0, 0.5), 0.2);  // reversing
  }
}

TEST_CASE("invariant EKF: the robot's heading variance never falls below its prior") {
  // With no absolute heading measurement, the heading error at any time is the initial one
  // plus odometry noise, and the initial one is independent of every reading: its posterior
  // variance cannot fall below the prior's (Huang and Dissanayake 2007 show the textbook EKF
  // breaking this bound; it is their test of inconsistency). The invariant filter's linearized
  // system has that structure exactly (readings do not see a global rotation, whatever the
  // estimate), so the bound holds at every step, for every noise draw.
  const double prior_heading_variance = 0.04;
  const Mat<3, 3> P0 = Vec<3>(1e-4, 1e-4, prior_heading_variance).asDiagonal();
  double smallest_textbook = prior_heading_variance;
  for (unsigned seed = 1; seed <= 5; ++seed) {
    for (const LinearizationPoint point : {LinearizationPoint::kInvariant, LinearizationPoint::kCurrentEstimate}) {
      Filter ekf(Vec<3>::Zero(), P0);
      ekf.setLinearizationPoint(point);
      double smallest = prior_heading_variance;
      driveCircle(ekf, nullptr, 60, seed, Fusion::kBatched,
                  [&](int) { smallest = std::min(smallest, ekf.robotCovariance()(2, 2)); });
      if (point == LinearizationPoint::kInvariant) {
        INFO("seed " << seed << ": smallest heading variance " << smallest);
        CHECK(smallest > prior_heading_variance * (1.0 - 1e-9));
      } else {
        smallest_textbook = std::min(smallest_textbook, smallest);
      }
    }
  }
  // The textbook filter on the same draws goes below the bound.
  INFO("textbook: smallest heading variance " << smallest_textbook);
  CHECK(smallest_textbook < 0.99 * prior_heading_variance);
}

TEST_CASE("invariant EKF: refused where it does not apply, and bad updates leave the filter unchanged") {
  // A landmark type without a planar position (Point3) in the list: refused, naming it.
  Ekf<Unicycle2D, Point2, Point3> mixed(Vec<3>::Zero(), Mat<3, 3>::Identity());
  sylva_test::requireRejected(mixed, ErrorCode::kInvalidArgument, "Point3",
                              [&] { mixed.setLinearizationPoint(LinearizationPoint::kInvariant); });
  CHECK(mixed.linearizationPoint() == LinearizationPoint::kCurrentEstimate);
  // The 6-DOF camera declares no planar frame.
  Ekf<ConstantVelocity3D, Point3> camera(Vec<13>::Zero(), Mat<13, 13>::Identity());
  sylva_test::requireRejected(camera, ErrorCode::kInvalidArgument, "ConstantVelocity3D",
                              [&] { camera.setLinearizationPoint(LinearizationPoint::kInvariant); });
  // Trees (a planar position and a frame-free radius) are accepted; an update that would
  // make a radius negative is rejected with the filter unchanged, as is a non-finite one.
  Ekf<Unicycle2D, TreeXYR> trees(Vec<3>(2.0, 1.0, 0.4), Mat<3, 3>::Identity() * 0.01);
  trees.setLinearizationPoint(LinearizationPoint::kInvariant);
  const Gaussian<3> noise = Gaussian<3>::sigmas(Vec<3>(0.1, 0.02, 0.05));
  trees.add(1, InverseRangeBearingDiameter(), Vec<3>(6.0, 0.3, 0.4), noise);
  trees.predict(Vec<2>(1.0, 0.1), 0.5, kControlNoise);
  sylva_test::requireRejected(trees, ErrorCode::kOutOfDomain, "radius",
                              [&] { trees.update(RangeBearingDiameter(), 1, Vec<3>(5.5, 0.3, -40.0), noise); });
  sylva_test::requireRejected(trees, ErrorCode::kNonFinite, "not finite", [&] {
    trees.update(RangeBearingDiameter(), 1, Vec<3>(5.5, std::nan(""), 0.4), noise);
  });
  // A good update goes through.
  trees.update(RangeBearingDiameter(), 1, Vec<3>(5.5, 0.3, 0.4), noise);
  CHECK(trees.mean().allFinite());
  CHECK(trees.landmarkMean<TreeXYR>(1)[2] > 0.0);
}
