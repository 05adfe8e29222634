// First-estimates Jacobians (LinearizationPoint::kFirstEstimates): where the Jacobians are
// taken, the transition Jacobian of eq. 34 of Huang, Mourikis and Roumeliotis (2010), the
// refusal for a robot without one, and the consistency it is there for (Monte Carlo NEES).

#include <cmath>
#include <random>
#include <vector>

#include <Eigen/Geometry>
#include <sylva/consistency.hpp>
#include <sylva/filter/ekf.hpp>
#include <sylva/landmarks.hpp>
#include <sylva/measurements.hpp>
#include <sylva/diff/numeric_diff.hpp>
#include <sylva/motion/ackermann_2d.hpp>
#include <sylva/motion/constant_velocity_3d.hpp>
#include <sylva/motion/odometry_2d.hpp>
#include <sylva/motion/unicycle_2d.hpp>

#include "filter/planar_scene.hpp"
#include "sylva_catch.hpp"

using namespace sylva;

namespace unity_filter_first_estimates {

using Filter = Ekf<Unicycle2D, Point2>;

using sylva_test::filterWithLandmark7;
using sylva_test::planarControlNoise;
using sylva_test::planarSensorNoise;

/// A filter that has seen landmark 7, then moved and fused two observations of it, so that
/// the landmark's estimate and the robot's differ from the first estimate and the latest
/// prediction.
struct Scene {
  Filter ekf;
  Vec<2> first_landmark;
  Vec<3> latest_prediction;
  explicit Scene(LinearizationPoint point) : ekf(filterWithLandmark7(Vec<3>::Zero(), point)) {
    first_landmark = ekf.landmarkMean<Point2>(7);
    ekf.predict(Vec<2>(1.0, 0.2), 1.0, planarControlNoise());
    ekf.update(RangeBearing(), 7, Vec<2>(4.3, 0.35), planarSensorNoise());
    ekf.predict(Vec<2>(1.0, 0.1), 1.0, planarControlNoise());
    latest_prediction = ekf.robotMean();
    ekf.update(RangeBearing(), 7, Vec<2>(3.1, 0.1), planarSensorNoise());
  }
};

}  // namespace unity_filter_first_estimates

using namespace unity_filter_first_estimates;

TEST_CASE("first estimates: measurement Jacobians at the first landmark estimate and the latest prediction") {
  Scene fej(LinearizationPoint::kFirstEstimates);
  REQUIRE(fej.ekf.linearizationPoint() == LinearizationPoint::kFirstEstimates);
  const Vec<2> landmark = fej.ekf.landmarkMean<Point2>(7);
  const Vec<3> robot = fej.ekf.robotMean();
  REQUIRE((landmark - fej.first_landmark).norm() > 0.05);  // the update moved both
  REQUIRE((robot - fej.latest_prediction).norm() > 0.05);

  const Linearization<RangeBearing> lin = fej.ekf.linearize(RangeBearing(), 7);
  Mat<2, 3> J_x;
  Mat<2, 2> J_l;
  RangeBearing()(fej.latest_prediction, fej.first_landmark, J_x, J_l);
  CHECK(lin.J_z_x.isApprox(J_x, 1e-12));
  CHECK(lin.J_z_l.isApprox(J_l, 1e-12));
  // The prediction itself is still taken at the current estimate.
  CHECK(lin.z_hat.isApprox(RangeBearing()(robot, landmark), 1e-12));

  // The textbook filter takes everything at the current estimate.
  Scene current(LinearizationPoint::kCurrentEstimate);
  const Linearization<RangeBearing> cur = current.ekf.linearize(RangeBearing(), 7);
  RangeBearing()(current.ekf.robotMean(), current.ekf.landmarkMean<Point2>(7), J_x, J_l);
  CHECK(cur.J_z_x.isApprox(J_x, 1e-12));
  CHECK(cur.J_z_l.isApprox(J_l, 1e-12));
  CHECK_FALSE(lin.J_z_l.isApprox(J_l, 1e-3));
}

TEST_CASE("first estimates: the transition Jacobian spans the latest two predictions") {
  Scene scene(LinearizationPoint::kFirstEstimates);
  Filter& ekf = scene.ekf;
  const Eigen::MatrixXd P = ekf.covariance();
  const Vec<3> posterior = ekf.robotMean();
  const Vec<2> u(1.0, -0.3);
  const double dt = 0.5;
  Mat<3, 3> F;
  Mat<3, 2> G;
  const Vec<3> next = Unicycle2D()(posterior, u, dt, F, G);
  ekf.predict(u, dt, planarControlNoise());
  CHECK(ekf.robotMean().isApprox(next, 1e-12));

  // eq. 34: [1 0 -(y' - y_prior); 0 1 (x' - x_prior); 0 0 1] with the previous prediction.
  Mat<3, 3> Phi = Mat<3, 3>::Identity();
  Phi(0, 2) = -(next[1] - scene.latest_prediction[1]);
  Phi(1, 2) = next[0] - scene.latest_prediction[0];
  REQUIRE_FALSE(Phi.isApprox(F, 1e-3));  // differs from the textbook Jacobian here
  const Mat<3, 3> expected_rr =
      Phi * P.topLeftCorner<3, 3>() * Phi.transpose() + G * planarControlNoise().covariance() * G.transpose();
  const Mat<3, 2> expected_rl = Phi * P.block<3, 2>(0, 3);
  CHECK(ekf.robotCovariance().isApprox(expected_rr, 1e-12));
  CHECK(ekf.robotLandmarkCovariance<Point2>(7).isApprox(expected_rl, 1e-12));
  CHECK(ekf.landmarkCovariance<Point2>(7).isApprox(P.block<2, 2>(3, 3), 1e-14));
}

namespace unity_filter_first_estimates {

/// Pose2D::firstEstimatesJacobian(x, f(x, u)) must be the true Jacobian of f at x (no
/// update in between: both rules agree), which holds when f moves the robot by a rigid
/// increment in its own frame. Checked numerically for every planar robot of sylva.
template <typename Robot>
void checkFirstEstimatesJacobian(const Robot& robot, const typename Robot::Control& u, double dt) {
  const Vec<3> states[] = {Vec<3>(1.0, 2.0, 0.3), Vec<3>(-4.0, 0.5, -2.0), Vec<3>(0.0, 0.0, kPi - 1e-3)};
  for (const Vec<3>& x : states) {
    const Vec<3> next = robot(x, u, dt);
    const Mat<3, 3> numeric = numericJacobian<3, 3>([&](const Vec<3>& y) { return robot(y, u, dt); }, x,
                                                    [](const Vec<3>& a, const Vec<3>& b) { return Pose2D::difference(a, b); });
    INFO(Robot::kName << " at " << x.transpose());
    CHECK((Pose2D::firstEstimatesJacobian(x, next) - numeric).cwiseAbs().maxCoeff() < 1e-7);
  }
}

}  // namespace unity_filter_first_estimates

TEST_CASE("first estimates: the transition Jacobian of every planar robot matches numerical differentiation") {
  checkFirstEstimatesJacobian(Unicycle2D(), Vec<2>(1.5, 0.4), 0.5);
  checkFirstEstimatesJacobian(Unicycle2D(), Vec<2>(0.0, 1.0), 0.5);  // turning on the spot
  checkFirstEstimatesJacobian(Odometry2D(), Vec<3>(0.8, -0.2, 0.3), 1.0);
  checkFirstEstimatesJacobian(Ackermann2D(2.83, 0.76), Vec<2>(3.0, -0.4), 0.2);
  checkFirstEstimatesJacobian(Ackermann2D(2.83, 0.76), Vec<2>(-1.0, 0.5), 0.2);  // reversing
}

namespace unity_filter_first_estimates {

/// A point robot in the plane moved by a velocity control, with no first-estimates Jacobian.
struct PointRobot {
  static constexpr int kDim = 2;
  static constexpr int kControlDim = 2;
  static constexpr int kNoiseDim = 2;
  static constexpr const char* kName = "PointRobot";
  using State = Vec<2>;
  using Control = Vec<2>;
  State operator()(const State& x, const Control& u, double dt, JacobianRef<2, 2> J_x = {},
                   JacobianRef<2, 2> J_n = {}) const {
    if (J_x) (*J_x).setIdentity();
    if (J_n) *J_n = dt * Mat<2, 2>::Identity();
    return x + dt * u;
  }
};

/// The seven directions monocular SLAM cannot observe, at camera state x: translation (3),
/// world-frame rotation (3), scale (1). A velocity in the camera frame does not turn with the
/// world.
Mat<13, 7> unobservableDirections(const Vec<13>& x,
                                  ConstantVelocity3D::VelocityFrame frame = ConstantVelocity3D::VelocityFrame::kWorld) {
  Mat<13, 7> N = Mat<13, 7>::Zero();
  const Vec<4> q = x.segment<4>(3);
  for (int i = 0; i < 3; ++i) {
    N(i, i) = 1.0;
    const Vec<3> phi = Vec<3>::Unit(i);
    N.block<3, 1>(0, 3 + i) = phi.cross(Vec<3>(x.head<3>()));
    N.block<4, 1>(3, 3 + i) = 0.5 * quaternionProduct<double>(Vec<4>(0.0, phi[0], phi[1], phi[2]), q);
    if (frame == ConstantVelocity3D::VelocityFrame::kWorld) N.block<3, 1>(7, 3 + i) = phi.cross(Vec<3>(x.segment<3>(7)));
  }
  N.block<3, 1>(0, 6) = x.head<3>();
  N.block<3, 1>(7, 6) = x.segment<3>(7);
  return N;
}

Vec<13> cameraState(const Vec<3>& r, const Vec<3>& rotation, const Vec<3>& v, const Vec<3>& omega) {
  Vec<13> x;
  x << r, quaternionFromRotationVector<double>(rotation), v, omega;
  return x;
}

}  // namespace unity_filter_first_estimates

TEST_CASE("first estimates: the camera's transition Jacobian carries the seven unobservable directions") {
  using Frame = ConstantVelocity3D::VelocityFrame;
  const double dt = 0.1;
  const Vec<13> from = cameraState(Vec<3>(1.0, -2.0, 1.5), Vec<3>(0.3, -1.2, 0.4), Vec<3>(0.8, 0.4, -0.1),
                                   Vec<3>(0.05, -0.3, 0.02));
  // The new prediction from a posterior that an update moved away from `from`.
  const Vec<13> posterior = cameraState(Vec<3>(1.1, -2.05, 1.48), Vec<3>(0.32, -1.15, 0.38), Vec<3>(0.7, 0.5, -0.08),
                                        Vec<3>(0.06, -0.28, 0.0));
  for (const Frame frame : {Frame::kWorld, Frame::kCamera}) {
    INFO((frame == Frame::kWorld ? "velocity in the world frame" : "velocity in the camera frame"));
    const ConstantVelocity3D motion{frame};
    const Vec<13> to = motion(posterior, Vec<0>(), dt);
    const Mat<13, 13> F = motion.firstEstimatesJacobian(from, to, dt);
    CHECK((F * unobservableDirections(from, frame) - unobservableDirections(to, frame)).cwiseAbs().maxCoeff() < 1e-12);
    // The textbook Jacobian at the posterior does not.
    Mat<13, 13> F_textbook;
    motion(posterior, Vec<0>(), dt, F_textbook);
    CHECK((F_textbook * unobservableDirections(from, frame) - unobservableDirections(to, frame)).cwiseAbs().maxCoeff() > 1e-3);
    // The textbook Jacobian at any state carries the directions there into those at its
    // prediction: the motion commutes with moving, turning and scaling the world.
    CHECK((F_textbook * unobservableDirections(posterior, frame) - unobservableDirections(to, frame)).cwiseAbs().maxCoeff() < 1e-12);
  }
}

TEST_CASE("first estimates: without an update in between, the camera's Jacobian is the textbook one") {
  // On the tangent space of the quaternion (the filter keeps no variance along q itself).
  const double dt = 0.1;
  const Vec<13> states[] = {
      cameraState(Vec<3>(1.0, -2.0, 1.5), Vec<3>(0.3, -1.2, 0.4), Vec<3>(0.8, 0.4, -0.1), Vec<3>(0.05, -0.3, 0.02)),
      cameraState(Vec<3>::Zero(), Vec<3>(0.0, 3.1, 0.0), Vec<3>::Zero(), Vec<3>(1.0, 2.0, -0.5)),  // at rest, turning
      cameraState(Vec<3>(5.0, 0.0, 0.0), Vec<3>(1e-9, 0.0, 0.0), Vec<3>(0.0, 0.0, 3.0), Vec<3>::Zero())};
  for (const auto frame : {ConstantVelocity3D::VelocityFrame::kWorld, ConstantVelocity3D::VelocityFrame::kCamera})
    for (const Vec<13>& x : states) {
      const ConstantVelocity3D motion{frame};
      Mat<13, 13> F_textbook;
      const Vec<13> next = motion(x, Vec<0>(), dt, F_textbook);
      const Mat<13, 13> tangent = ConstantVelocity3D::normalizationJacobian(x);
      const Mat<13, 13> F = motion.firstEstimatesJacobian(x, next, dt);
      INFO("state " << x.transpose() << (frame == ConstantVelocity3D::VelocityFrame::kCamera ? ", camera frame" : ", world frame"));
      CHECK((F * tangent - F_textbook * tangent).cwiseAbs().maxCoeff() < 1e-9);
      // ... and the textbook Jacobian agrees with numerical differentiation.
      const Mat<13, 13> numeric = numericJacobian<13, 13>([&](const Vec<13>& y) { return motion(y, Vec<0>(), dt); }, x);
      CHECK((F * tangent - numeric * tangent).cwiseAbs().maxCoeff() < 1e-6);
    }
}

TEST_CASE("first estimates: a robot without a first-estimates Jacobian is refused") {
  Ekf<PointRobot, Point2> ekf(Vec<2>::Zero(), Mat<2, 2>::Identity());
  const Eigen::VectorXd mean = ekf.mean();
  CHECK_THROWS_AS(ekf.setLinearizationPoint(LinearizationPoint::kFirstEstimates), Error);
  try {
    ekf.setLinearizationPoint(LinearizationPoint::kFirstEstimates);
  } catch (const Error& e) {
    CHECK(e.code() == ErrorCode::kInvalidArgument);
    CHECK(std::string(e.what()).find("firstEstimatesJacobian") != std::string::npos);
  }
  CHECK(ekf.linearizationPoint() == LinearizationPoint::kCurrentEstimate);
  CHECK(ekf.mean() == mean);
  // The camera has one.
  Ekf<ConstantVelocity3D, Point3> camera(Vec<13>::Zero(), Mat<13, 13>::Identity());
  CHECK_NOTHROW(camera.setLinearizationPoint(LinearizationPoint::kFirstEstimates));
}

namespace unity_filter_first_estimates {

/// Robot-pose NEES over the second lap of `runs` Monte Carlo runs from `seed`: a robot driving
/// laps of a circle among landmarks on a ring, odometry and range-bearing noise as the filter
/// assumes, known association, landmarks added at first sight.
NeesEnsemble poseNees(LinearizationPoint point, int runs, unsigned seed) {
  const int steps = 240;
  const double dt = 0.5;
  const Vec<2> u_true(1.0, 2.0 * kPi / (steps / 2 * dt));  // two laps
  // Landmarks on two rings around the circle's centre (0, rho), 2 m inside and outside.
  const double rho = u_true[0] / u_true[1];
  const std::vector<Vec<2>> landmarks = sylva_test::landmarksOnTwoRings(16, rho, rho - 2.0, rho + 2.0);
  const double sv = 0.05, sw = 0.1;  // odometry noise [m/s, rad/s], true and assumed
  const double sr = 0.1, sb = 0.05;  // sensor noise [m, rad], true and assumed
  const Gaussian<2> Q = Gaussian<2>::sigmas(Vec<2>(sv, sw));
  const Gaussian<2> R = Gaussian<2>::sigmas(Vec<2>(sr, sb));
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal;
  NeesEnsemble ensemble(3);
  for (int run = 0; run < runs; ++run) {
    Filter ekf(Vec<3>::Zero(), Mat<3, 3>::Zero());
    ekf.setLinearizationPoint(point);
    Vec<3> truth = Vec<3>::Zero();
    for (int k = 0; k < steps; ++k) {
      truth = Unicycle2D()(truth, u_true, dt);
      const Vec<2> u(u_true[0] + sv * normal(rng), u_true[1] + sw * normal(rng));
      ekf.predict(u, dt, Q);
      std::vector<Observation<RangeBearing>> seen;
      for (std::size_t i = 0; i < landmarks.size(); ++i) {
        const Vec<2> z_true = RangeBearing()(truth, landmarks[i]);
        if (z_true[0] > 6.0) continue;
        const Vec<2> z(z_true[0] + sr * normal(rng), wrapAngle(z_true[1] + sb * normal(rng)));
        const Id id = static_cast<Id>(i);
        if (ekf.contains(id))
          seen.push_back(Observation<RangeBearing>{id, z, R});
        else
          ekf.add(id, InverseRangeBearing(), z, R);
      }
      ekf.update(RangeBearing(), seen);
      if (k >= steps / 2)
        ensemble.add(run, k - steps / 2, nees(Unicycle2D::difference(truth, ekf.robotMean()), ekf.robotCovariance()));
    }
  }
  return ensemble;
}

}  // namespace unity_filter_first_estimates

TEST_CASE("first estimates and the invariant EKF: the robot's NEES stays consistent where the textbook EKF's grows",
          "[filter][consistency][slow]") {
  // Ten ensembles (seeds 1-10) of 30 runs, the three filters on the same noise (paired).
  const int runs = 30, seeds = 10;
  std::vector<double> textbook, first, invariant;
  double textbook_sum = 0.0, first_sum = 0.0, invariant_sum = 0.0;
  for (unsigned seed = 1; seed <= static_cast<unsigned>(seeds); ++seed) {
    textbook.push_back(poseNees(LinearizationPoint::kCurrentEstimate, runs, seed).summary().mean);
    first.push_back(poseNees(LinearizationPoint::kFirstEstimates, runs, seed).summary().mean);
    invariant.push_back(poseNees(LinearizationPoint::kInvariant, runs, seed).summary().mean);
    textbook_sum += textbook.back();
    first_sum += first.back();
    invariant_sum += invariant.back();
  }
  // Printed on every run: docs/filter.md quotes the means.
  WARN("mean pose NEES, second lap, " << seeds << " x " << runs << " runs: textbook " << textbook_sum / seeds
                                      << ", first estimates " << first_sum / seeds << ", invariant "
                                      << invariant_sum / seeds);
  // Paired: each consistent filter lower on every seed (a sign test: 10 of 10 has
  // probability 2^-10 if neither filter were better).
  for (int i = 0; i < seeds; ++i) {
    const auto at = static_cast<std::size_t>(i);
    INFO("seed " << i + 1 << ": textbook " << textbook[at] << ", first estimates " << first[at] << ", invariant "
                 << invariant[at]);
    CHECK(first[at] < textbook[at]);
    CHECK(invariant[at] < textbook[at]);
  }
  // The grand mean over all 300 runs against the 99% bounds of a 300-run average of chi2(3)
  // at one step. Averaging correlated steps as well can only lower the variance of the mean
  // (Var(sum / n) <= max Var), so the bound is conservative.
  const auto bounds = averageChiSquareBounds(3, runs * seeds, 0.99);
  CHECK(first_sum / seeds > bounds.first);
  CHECK(first_sum / seeds < bounds.second);
  CHECK(invariant_sum / seeds > bounds.first);
  CHECK(invariant_sum / seeds < bounds.second);
  CHECK(textbook_sum / seeds > bounds.second);
}
