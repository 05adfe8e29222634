// Robots on manifolds (motion/on_manifold.hpp): the camera's state on SO(3) x R^9 with its
// covariance on the 12-dimensional tangent. plus and minus against Eigen's quaternions, their
// Jacobians against numerical differentiation and automatic differentiation at ordinary and
// awkward orientations, the filter against a dense tangent-space EKF written here (whose
// Jacobians are central differences of the composed maps, so it shares no chain rule with
// the filter), the quaternion staying of unit norm, the refusal of a state off the group, and
// the camera pose NEES through minus.

#include <cmath>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <unsupported/Eigen/AutoDiff>
#include <sylva/consistency/camera_pose_nees.hpp>
#include <sylva/core/quaternion.hpp>
#include <sylva/diff/numeric_diff.hpp>
#include <sylva/filter/ekf.hpp>
#include <sylva/landmarks/inverse_depth.hpp>
#include <sylva/landmarks/point3.hpp>
#include <sylva/measurements/inverse_depth_initialization.hpp>
#include <sylva/measurements/pinhole_point.hpp>
#include <sylva/motion/constant_velocity_3d.hpp>
#include <sylva/motion/on_manifold.hpp>
#include <sylva/sim/forest_trajectory.hpp>

#include "../filter_snapshot.hpp"
#include "sylva_catch.hpp"

using namespace sylva;

namespace unity_manifold_robot {

using Camera = OnManifold<ConstantVelocity3D>;
using ManifoldFilter = Ekf<Camera, InverseDepth, Point3>;
using ManifoldFrame = ConstantVelocity3D::VelocityFrame;
using Catch::Matchers::Contains;
const PinholeCamera kIntrinsics{500.0, 500.0, 320.0, 240.0, 640, 480};

Vec<13> cameraState(const Vec<3>& r, const Vec<4>& q, const Vec<3>& v, const Vec<3>& omega) {
  Vec<13> x;
  x << r, q, v, omega;
  return x;
}

/// A camera looking along `heading` (about world z), pitched down 15 degrees, driving at 1 m/s
/// while it turns.
Vec<13> drivingCamera(double heading, const Vec<3>& position) {
  const Eigen::Quaterniond q(sim::cameraOrientation(Vec<2>(std::cos(heading), std::sin(heading)), 15.0 * kRadPerDeg));
  return cameraState(position, Vec<4>(q.w(), q.x(), q.y(), q.z()), Vec<3>(std::cos(heading), std::sin(heading), 0.0),
                     Vec<3>(0.01, -0.12, 0.02));
}

/// Orientations where the maps are easy to get wrong: identity, a turn close to pi, a
/// quaternion with negative w, and an ordinary one.
std::vector<Vec<13>> awkwardStates() {
  const auto with = [](const Vec<3>& rotation, bool negate) {
    Vec<4> q = quaternionFromRotationVector<double>(rotation);
    if (negate) q = -q;
    return cameraState(Vec<3>(1.0, -2.0, 0.5), q, Vec<3>(0.3, 0.1, -0.2), Vec<3>(0.05, 0.0, -0.1));
  };
  return {with(Vec<3>::Zero(), false), with(Vec<3>(0.0, 3.1, 0.2), false), with(Vec<3>(0.4, -0.2, 1.0), true),
          with(Vec<3>(-0.7, 0.3, 0.1), false), drivingCamera(2.9, Vec<3>(-40.0, 12.0, 1.6))};
}

/// A tangent-space EKF over [camera (13 entries, 12 rows), inverse-depth points (6 each)],
/// written directly from the definitions: every Jacobian is a central difference of the map
/// composed with plus and minus.
struct DenseManifoldEkf {
  Camera motion;
  Vec<13> robot;
  Eigen::VectorXd landmarks;  // 6 per point
  Eigen::MatrixXd P;          // 12 + 6 k

  int size() const { return static_cast<int>(P.rows()); }

  void predict(double dt, const Gaussian<6>& noise) {
    const Vec<13> next = motion.propagate<double>(robot, Vec<0>(), Vec<6>::Zero(), dt);
    const Mat<12, 12> F = numericJacobian<12, 12>(
        [&](const Vec<12>& d) {
          return Camera::minus(motion.propagate<double>(Camera::plus(robot, d), Vec<0>(), Vec<6>::Zero(), dt), next);
        },
        Vec<12>(Vec<12>::Zero()));
    const Mat<12, 6> G = numericJacobian<12, 6>(
        [&](const Vec<6>& n) { return Camera::minus(motion.propagate<double>(robot, Vec<0>(), n, dt), next); },
        Vec<6>(Vec<6>::Zero()));
    Eigen::MatrixXd Phi = Eigen::MatrixXd::Identity(size(), size());
    Phi.topLeftCorner<12, 12>() = F;
    Eigen::MatrixXd Gfull = Eigen::MatrixXd::Zero(size(), 6);
    Gfull.topRows<12>() = G;
    P = Phi * P * Phi.transpose() + Gfull * noise.covariance() * Gfull.transpose();
    robot = next;
  }

  void add(const InverseDepthInitialization& init, const Vec<3>& z, const Gaussian<3>& noise) {
    const Vec<6> l = init(ConstantVelocity3D::pose(robot), z);
    const Mat<6, 12> J_x =
        numericJacobian<6, 12>([&](const Vec<12>& d) { return init(ConstantVelocity3D::pose(Camera::plus(robot, d)), z); }, Vec<12>(Vec<12>::Zero()));
    const Mat<6, 3> J_z = numericJacobian<6, 3>([&](const Vec<3>& y) { return init(ConstantVelocity3D::pose(robot), y); }, z);
    const int n = size();
    Eigen::MatrixXd J = Eigen::MatrixXd::Zero(n + 6, n + 3);
    J.topLeftCorner(n, n).setIdentity();
    J.block(n, 0, 6, 12) = J_x;
    J.block(n, n, 6, 3) = J_z;
    Eigen::MatrixXd P_z = Eigen::MatrixXd::Zero(n + 3, n + 3);
    P_z.topLeftCorner(n, n) = P;
    P_z.bottomRightCorner<3, 3>() = noise.covariance();
    P = J * P_z * J.transpose();
    landmarks.conservativeResize(landmarks.size() + 6);
    landmarks.tail<6>() = l;
  }

  void update(const PinholePoint<InverseDepth>& model, int index, const Vec<2>& z, const Gaussian<2>& noise) {
    const int o = 12 + 6 * index;
    const Vec<6> l = landmarks.segment<6>(6 * index);
    const auto h = [&](const Vec<18>& d) {
      return model(ConstantVelocity3D::pose(Camera::plus(robot, Vec<12>(d.head<12>()))), Vec<6>(l + d.tail<6>()));
    };
    const Mat<2, 18> H_local = numericJacobian<2, 18>(h, Vec<18>(Vec<18>::Zero()));
    Eigen::MatrixXd H = Eigen::MatrixXd::Zero(2, size());
    H.leftCols<12>() = H_local.leftCols<12>();
    H.middleCols<6>(o) = H_local.rightCols<6>();
    const Eigen::MatrixXd S = H * P * H.transpose() + noise.covariance();
    const Eigen::MatrixXd K = P * H.transpose() * S.inverse();
    const Eigen::VectorXd delta = K * (z - model(ConstantVelocity3D::pose(robot), l));
    robot = Camera::plus(robot, Vec<12>(delta.head<12>()));
    landmarks += delta.tail(size() - 12);
    P = ((Eigen::MatrixXd::Identity(size(), size()) - K * H) * P).eval();
    P = (0.5 * (P + P.transpose())).eval();
  }
};

}  // namespace unity_manifold_robot

using namespace unity_manifold_robot;

TEST_CASE("manifold robot: plus and minus are inverse, and agree with Eigen's quaternions", "[filter][manifold]") {
  const Vec<12> steps[] = {(Vec<12>() << 0.1, -0.2, 0.3, 0.02, -0.01, 0.03, 0.5, 0.0, -0.1, 0.01, 0.02, 0.0).finished(),
                           (Vec<12>() << 0, 0, 0, 3.0, 0.5, -0.2, 0, 0, 0, 0, 0, 0).finished(),  // a turn near pi
                           Vec<12>::Zero()};
  for (const Vec<13>& x : awkwardStates()) {
    for (const Vec<12>& d : steps) {
      INFO("x = " << x.transpose() << ", d = " << d.transpose());
      const Vec<13> y = Camera::plus(x, d);
      CHECK(std::abs(y.segment<4>(3).norm() - 1.0) < 1e-14);
      CHECK((Camera::minus(y, x) - d).cwiseAbs().maxCoeff() < 1e-12);
      // The orientation: q (x) Exp(dtheta) as Eigen composes it.
      const Eigen::Quaterniond q(x[3], x[4], x[5], x[6]);
      const Vec<3> dtheta = d.segment<3>(3);
      const Eigen::Quaterniond turn(Eigen::AngleAxisd(dtheta.norm(), dtheta.norm() > 0 ? Vec<3>(dtheta.normalized()) : Vec<3>::UnitX()));
      const Eigen::Quaterniond expected = q * turn;
      CHECK(std::abs(std::abs(expected.coeffs().dot(Eigen::Quaterniond(y[3], y[4], y[5], y[6]).coeffs())) - 1.0) < 1e-12);
      CHECK((y.head<3>() - x.head<3>() - d.head<3>()).norm() < 1e-14 * (1.0 + x.head<3>().norm()));
      CHECK((y.tail<6>() - x.tail<6>() - d.tail<6>()).norm() < 1e-14 * (1.0 + x.tail<6>().norm()));
    }
    // The same rotation written with the other sign is the same point of the group.
    Vec<13> flipped = x;
    flipped.segment<4>(3) *= -1.0;
    CHECK(Camera::minus(flipped, x).norm() < 1e-12);
  }
}

TEST_CASE("manifold robot: plusJacobian and minusJacobian match numerical and automatic differentiation",
          "[filter][manifold]") {
  for (const Vec<13>& x : awkwardStates()) {
    INFO("x = " << x.transpose());
    const Mat<13, 12> E = Camera::plusJacobian(x);
    const Mat<12, 13> M = Camera::minusJacobian(x);
    const Mat<13, 12> E_numeric =
        numericJacobian<13, 12>([&](const Vec<12>& d) { return Camera::plus(x, d); }, Vec<12>(Vec<12>::Zero()));
    CHECK((E - E_numeric).cwiseAbs().maxCoeff() < 1e-8);
    // minus moves with y on the group only: differentiate along y = x (+) d and through the
    // quaternion's tangent directions of the state's entries.
    const Mat<12, 12> ME_numeric = numericJacobian<12, 12>(
        [&](const Vec<12>& d) { return Camera::minus(Camera::plus(x, d), x); }, Vec<12>(Vec<12>::Zero()));
    CHECK((M * E - ME_numeric).cwiseAbs().maxCoeff() < 1e-8);
    CHECK((M * E - Mat<12, 12>::Identity()).cwiseAbs().maxCoeff() < 1e-14);
    // d (y (-) x) / d y in the state's own entries at y = x (minus reads the rotation of
    // q_x^* (x) q_y, whatever q_y's norm, and so does the analytic row: M q = 0).
    const Mat<12, 13> M_numeric = numericJacobian<12, 13>([&](const Vec<13>& y) { return Camera::minus(y, x); }, x);
    CHECK((M - M_numeric).cwiseAbs().maxCoeff() < 1e-6);
    // Automatic differentiation of q (x) Exp(dtheta), the quaternion block of plusJacobian.
    using Dual = Eigen::AutoDiffScalar<Vec<3>>;
    Vec<3, Dual> dtheta;
    for (int i = 0; i < 3; ++i) dtheta[i] = Dual(0.0, 3, i);
    Vec<4, Dual> q;
    for (int i = 0; i < 4; ++i) q[i] = Dual(x[3 + i]);
    const Vec<4, Dual> moved = quaternionProduct<Dual>(q, quaternionFromRotationVector<Dual>(dtheta));
    Mat<4, 3> E_auto;
    for (int r = 0; r < 4; ++r) E_auto.row(r) = moved[r].derivatives().transpose();
    CHECK((E.block<4, 3>(3, 3) - E_auto).cwiseAbs().maxCoeff() < 1e-14);
    // And of Log(q_x^* (x) q_y) at q_y = q_x, the quaternion block of minusJacobian.
    using Dual4 = Eigen::AutoDiffScalar<Vec<4>>;
    Vec<4, Dual4> q_y;
    for (int i = 0; i < 4; ++i) q_y[i] = Dual4(x[3 + i], 4, i);
    const Vec<4, Dual4> q_x_conj(Dual4(x[3]), Dual4(-x[4]), Dual4(-x[5]), Dual4(-x[6]));
    const Vec<3, Dual4> rotation = rotationVectorFromQuaternion<Dual4>(quaternionProduct<Dual4>(q_x_conj, q_y));
    Mat<3, 4> M_auto;
    for (int r = 0; r < 3; ++r) M_auto.row(r) = rotation[r].derivatives().transpose();
    const Mat<3, 4> M_q = M.block<3, 4>(3, 3);
    INFO("minusJacobian's quaternion block\n" << M_q << "\nautodiff\n" << M_auto);
    CHECK((M_q - M_auto).cwiseAbs().maxCoeff() < 1e-14);
  }
}

TEST_CASE("manifold robot: the filter equals a dense tangent-space EKF written here", "[filter][manifold]") {
  for (const ManifoldFrame frame : {ManifoldFrame::kWorld, ManifoldFrame::kCamera}) {
    INFO("velocity frame " << (frame == ManifoldFrame::kWorld ? "world" : "camera"));
    const Camera motion{ConstantVelocity3D{frame}};
    const Vec<13> x0 = drivingCamera(0.3, Vec<3>(0.5, -0.2, 1.5));
    Mat<12, 12> P0 = Mat<12, 12>::Zero();
    P0.diagonal() << Vec<3>::Constant(1e-4), Vec<3>::Constant(1e-5), Vec<3>::Constant(0.01), Vec<3>::Constant(0.004);
    ManifoldFilter ekf(x0, P0, motion);
    DenseManifoldEkf ref{motion, x0, Eigen::VectorXd(), Eigen::MatrixXd(P0)};
    const PinholePoint<InverseDepth> model(kIntrinsics);
    const InverseDepthInitialization init(kIntrinsics, 0.1, 0.5);
    const Gaussian<6> accel = Gaussian<6>::sigmas((Vec<6>() << 0.3, 0.3, 0.3, 0.2, 0.2, 0.2).finished());
    const Gaussian<2> pixel = Gaussian<2>::sigmas(Vec<2>(1.0, 1.0));
    const Vec<2> pixels[] = {Vec<2>(300.0, 260.0), Vec<2>(420.0, 300.0), Vec<2>(180.0, 250.0)};
    for (int j = 0; j < 3; ++j) {
      ekf.add(j, init, init.measurement(pixels[j]), init.noise(pixel));
      ref.add(init, init.measurement(pixels[j]), init.noise(pixel));
    }
    for (int k = 1; k <= 6; ++k) {
      ekf.predict(Vec<0>(), 0.1, accel);
      ref.predict(0.1, accel);
      for (int j = 0; j < 3; ++j) {
        // The pixel the landmark predicts, moved by a few pixels: an informative update.
        const Vec<2> z = model(ConstantVelocity3D::pose(ekf.robotMean()), ekf.landmarkMean<InverseDepth>(j)) + Vec<2>(1.5 * std::sin(k + j), -2.0 * std::cos(k * j));
        ekf.update(model, j, z, pixel);
        ref.update(model, j, z, pixel);
      }
    }
    CHECK(ekf.dim() == 12 + 18);
    CHECK(ekf.mean().size() == 13 + 18);
    CHECK(std::abs(ekf.robotMean().segment<4>(3).norm() - 1.0) < 1e-14);
    CHECK(Camera::minus(ekf.robotMean(), ref.robot).norm() < 1e-7);
    CHECK((ekf.mean().tail(18) - ref.landmarks).cwiseAbs().maxCoeff() < 1e-7);
    const Eigen::MatrixXd P = ekf.covariance();
    CHECK((P - ref.P).cwiseAbs().maxCoeff() < 1e-6 * ref.P.cwiseAbs().maxCoeff());
    // The camera's covariance is of full rank on its tangent: 6 DOF of pose, no singular
    // quaternion direction.
    const Eigen::SelfAdjointEigenSolver<Mat<12, 12>> eig(ekf.robotCovariance());
    CHECK(eig.eigenvalues().minCoeff() > 0.0);
  }
}

TEST_CASE("manifold robot: the ideal and iterated modes reduce to the textbook one where they should",
          "[filter][manifold]") {
  const Vec<13> x0 = drivingCamera(-0.4, Vec<3>(2.0, 1.0, 1.4));
  const Mat<12, 12> P0 = Mat<12, 12>::Identity() * 1e-4;
  const PinholePoint<InverseDepth> model(kIntrinsics);
  const InverseDepthInitialization init(kIntrinsics, 0.1, 0.5);
  const Gaussian<6> accel = Gaussian<6>::sigmas(Vec<6>::Constant(0.3));
  const Gaussian<2> pixel = Gaussian<2>::sigmas(Vec<2>(1.0, 1.0));
  const auto run = [&](LinearizationPoint point) {
    ManifoldFilter ekf(x0, P0);
    ekf.setLinearizationPoint(point);
    if (point == LinearizationPoint::kIterated) ekf.setIteratedUpdate(IteratedUpdate{1, 1e-3});
    ekf.add(1, init, init.measurement(Vec<2>(330.0, 250.0)), init.noise(pixel));
    for (int k = 0; k < 4; ++k) {
      // kIdeal linearized about the estimate itself: f(x) (+) F (x (-) x) is the textbook step.
      if (point == LinearizationPoint::kIdeal) ekf.setIdealRobot(ekf.robotMean());
      ekf.predict(Vec<0>(), 0.1, accel);
      if (point == LinearizationPoint::kIdeal) {
        ekf.setIdealRobot(ekf.robotMean());
        ekf.setIdealLandmark<InverseDepth>(1, ekf.landmarkMean<InverseDepth>(1));
      }
      ekf.update(model, 1, Vec<2>(332.0 + k, 247.0 - k), pixel);
    }
    return sylva_test::Snapshot(ekf);
  };
  const sylva_test::Snapshot textbook = run(LinearizationPoint::kCurrentEstimate);
  for (const LinearizationPoint point : {LinearizationPoint::kIdeal, LinearizationPoint::kIterated}) {
    const sylva_test::Snapshot other = run(point);
    CHECK((other.mean - textbook.mean).cwiseAbs().maxCoeff() < 1e-12);
    CHECK((other.covariance - textbook.covariance).cwiseAbs().maxCoeff() < 1e-12 * textbook.covariance.cwiseAbs().maxCoeff());
  }
  // First-estimates and observability-constrained filters run on the tangent too.
  for (const LinearizationPoint point : {LinearizationPoint::kFirstEstimates, LinearizationPoint::kObservabilityConstrained}) {
    const sylva_test::Snapshot other = run(point);
    CHECK(other.mean.allFinite());
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(other.covariance);
    CHECK(eig.eigenvalues().minCoeff() > 0.0);
  }
}

TEST_CASE("manifold robot: observability-constrained updates add no information along the gauge", "[filter][manifold]") {
  const Vec<13> x0 = drivingCamera(0.8, Vec<3>(-1.0, 3.0, 1.5));
  Mat<12, 12> P0 = Mat<12, 12>::Identity() * 1e-3;
  ManifoldFilter ekf(x0, P0, Camera{ConstantVelocity3D{ManifoldFrame::kCamera}});
  ekf.setLinearizationPoint(LinearizationPoint::kObservabilityConstrained);
  const PinholePoint<InverseDepth> model(kIntrinsics);
  const InverseDepthInitialization init(kIntrinsics, 0.1, 0.5);
  const Gaussian<2> pixel = Gaussian<2>::sigmas(Vec<2>(1.0, 1.0));
  ekf.add(3, init, init.measurement(Vec<2>(280.0, 260.0)), init.noise(pixel));
  ekf.add(4, init, init.measurement(Vec<2>(400.0, 230.0)), init.noise(pixel));
  ekf.predict(Vec<0>(), 0.1, Gaussian<6>::sigmas(Vec<6>::Constant(0.3)));
  // N(x) on the tangent: the camera's rows through minusJacobian, the landmarks' as they are.
  const auto gauge = [](const ManifoldFilter& f) {
    Eigen::MatrixXd N(f.dim(), kGaugeDim);
    N.topRows<12>() = Camera::minusJacobian(f.robotMean()) * f.robot().gaugeDirections(f.robotMean());
    for (const LandmarkSlot& s : f.slots()) N.middleRows<6>(s.offset) = InverseDepth::gaugeDirections(f.landmarkMean<InverseDepth>(s.id));
    return N;
  };
  const auto information = [&](const ManifoldFilter& f) {
    const Eigen::MatrixXd N = gauge(f);
    return Eigen::MatrixXd(N.transpose() * f.covariance().ldlt().solve(N));
  };
  const Eigen::MatrixXd before = information(ekf);
  ekf.update(model, 3, Vec<2>(284.0, 255.0), pixel);
  ekf.update(model, 4, Vec<2>(396.0, 236.0), pixel);
  const Eigen::MatrixXd after = information(ekf);
  CHECK((after - before).cwiseAbs().maxCoeff() < 1e-6 * before.cwiseAbs().maxCoeff());
}

TEST_CASE("manifold robot: a state off the group is refused, not renormalized", "[filter][manifold][bad-input]") {
  Vec<13> off = drivingCamera(0.1, Vec<3>::Zero());
  off.segment<4>(3) *= 1.01;
  const Mat<12, 12> P0 = Mat<12, 12>::Identity() * 1e-4;
  CHECK_THROWS_WITH(ManifoldFilter(off, P0), Contains("unit norm"));
  try {
    ManifoldFilter(off, P0);
  } catch (const Error& e) {
    CHECK(e.code() == ErrorCode::kOutOfDomain);
  }
  ManifoldFilter ekf(drivingCamera(0.1, Vec<3>::Zero()), P0);
  ekf.setLinearizationPoint(LinearizationPoint::kIdeal);
  sylva_test::requireRejected(ekf, ErrorCode::kOutOfDomain, "unit norm", [&] { ekf.setIdealRobot(off); });
  Vec<13> nan = off;
  nan[4] = std::nan("");
  sylva_test::requireRejected(ekf, ErrorCode::kNonFinite, "not finite", [&] { ekf.setIdealRobot(nan); });
  // A covariance of the wrong kind is refused as for any robot.
  Mat<12, 12> asymmetric = P0;
  asymmetric(0, 5) = 1.0;
  CHECK_THROWS_WITH(ManifoldFilter(drivingCamera(0.1, Vec<3>::Zero()), asymmetric), Contains("symmetric"));
}

TEST_CASE("manifold robot: the camera pose NEES through minus", "[filter][manifold][consistency]") {
  const Vec<13> estimate = drivingCamera(1.2, Vec<3>(3.0, -1.0, 1.5));
  const Vec<12> d = (Vec<12>() << 0.1, -0.05, 0.02, 0.01, -0.03, 0.02, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0).finished();
  const Vec<13> truth = Camera::plus(estimate, d);
  Mat<12, 12> P = Mat<12, 12>::Identity() * 0.01;
  P(0, 4) = P(4, 0) = 0.002;
  const CameraPoseError err = cameraPoseErrorOnManifold(estimate, P, truth);
  CHECK((err.e - d.head<6>()).cwiseAbs().maxCoeff() < 1e-12);
  CHECK(cameraPoseNeesOnManifold(estimate, P, truth) == Approx(d.head<6>().dot(P.topLeftCorner<6, 6>().ldlt().solve(d.head<6>()))));
  // The same rotation with the other sign of the quaternion, and a truth off the estimate's
  // hemisphere, give the same error.
  Vec<13> flipped = truth;
  flipped.segment<4>(3) *= -1.0;
  CHECK(cameraPoseNeesOnManifold(estimate, P, flipped) == Approx(cameraPoseNeesOnManifold(estimate, P, truth)));
  // The quaternion filter's NEES of the same error, with the covariance carried to its 13
  // entries through plusJacobian, agrees to first order.
  const Mat<13, 12> E = Camera::plusJacobian(estimate);
  const Mat<13, 13> P13 = E * P * E.transpose();
  CHECK(cameraPoseNees(estimate, P13, truth) == Approx(cameraPoseNeesOnManifold(estimate, P, truth)).epsilon(0.02));
}
