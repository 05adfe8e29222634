// Ideal linearization (LinearizationPoint::kIdeal), the simulation diagnostic: predict and
// update linearized about the true state the caller hands over, refusals when it did not, and
// bad input leaving the filter unchanged.

#include <cmath>
#include <string>

#include <sylva/filter/ekf.hpp>
#include <sylva/landmarks.hpp>
#include <sylva/measurements.hpp>
#include <sylva/motion/unicycle_2d.hpp>

#include "filter/planar_scene.hpp"
#include "filter_snapshot.hpp"
#include "sylva_catch.hpp"

using namespace sylva;

namespace unity_filter_ideal_linearization {

using Filter = Ekf<Unicycle2D, Point2>;

using sylva_test::planarControlNoise;
using sylva_test::planarSensorNoise;

/// An ideal filter that has seen landmark 7 and whose estimate differs from the truth.
struct IdealScene {
  Filter ekf = sylva_test::filterWithLandmark7(Vec<3>(0.2, -0.1, 0.05), LinearizationPoint::kIdeal);
  Vec<3> robot_truth{0.0, 0.0, 0.0};
  Vec<2> landmark_truth{4.0, 2.0};
  IdealScene() {
    ekf.setIdealRobot(robot_truth);
    ekf.setIdealLandmark<Point2>(7, landmark_truth);
  }
};

}  // namespace unity_filter_ideal_linearization

using namespace unity_filter_ideal_linearization;
using sylva_test::requireRejected;

TEST_CASE("ideal linearization: the measurement is linearized about the true state") {
  IdealScene scene;
  const Vec<3> robot = scene.ekf.robotMean();
  const Vec<2> landmark = scene.ekf.landmarkMean<Point2>(7);
  REQUIRE((robot - scene.robot_truth).norm() > 0.1);
  REQUIRE((landmark - scene.landmark_truth).norm() > 0.1);
  const Linearization<RangeBearing> lin = scene.ekf.linearize(RangeBearing(), 7);
  Mat<2, 3> J_x;
  Mat<2, 2> J_l;
  const Vec<2> z_true = RangeBearing()(scene.robot_truth, scene.landmark_truth, J_x, J_l);
  CHECK(lin.J_z_x.isApprox(J_x, 1e-12));
  CHECK(lin.J_z_l.isApprox(J_l, 1e-12));
  // h(x_true) + H (x - x_true): first order about the truth, not h at the estimate.
  const Vec<2> expected = z_true + J_x * Pose2D::difference(robot, scene.robot_truth) + J_l * (landmark - scene.landmark_truth);
  CHECK(lin.z_hat.isApprox(expected, 1e-12));
  CHECK_FALSE(lin.z_hat.isApprox(RangeBearing()(robot, landmark), 1e-4));
}

TEST_CASE("ideal linearization: the motion is linearized about the true state") {
  IdealScene scene;
  Filter& ekf = scene.ekf;
  const Eigen::MatrixXd P = ekf.covariance();
  const Vec<3> estimate = ekf.robotMean();
  const Vec<2> u(1.0, -0.3);
  const double dt = 0.5;
  Mat<3, 3> F;
  Mat<3, 2> G;
  const Vec<3> f_truth = Unicycle2D()(scene.robot_truth, u, dt, F, G);
  ekf.predict(u, dt, planarControlNoise());
  Vec<3> expected = f_truth + F * Pose2D::difference(estimate, scene.robot_truth);
  Pose2D::normalize(expected);
  CHECK(ekf.robotMean().isApprox(expected, 1e-12));
  const Mat<3, 3> expected_rr = F * P.topLeftCorner<3, 3>() * F.transpose() + G * planarControlNoise().covariance() * G.transpose();
  CHECK(ekf.robotCovariance().isApprox(expected_rr, 1e-12));
  CHECK(ekf.robotLandmarkCovariance<Point2>(7).isApprox(Mat<3, 2>(F * P.block<3, 2>(0, 3)), 1e-12));
}

TEST_CASE("ideal linearization: a true state that was not handed over is refused, the filter unchanged") {
  IdealScene scene;
  Filter& ekf = scene.ekf;
  // Each predict uses the robot's true state up: the update after it needs a new one.
  ekf.predict(Vec<2>(1.0, 0.0), 0.5, planarControlNoise());
  requireRejected(ekf, ErrorCode::kInvalidArgument, "setIdealRobot",
                  [&] { ekf.update(RangeBearing(), 7, Vec<2>(4.0, 0.4), planarSensorNoise()); });
  requireRejected(ekf, ErrorCode::kInvalidArgument, "setIdealRobot",
                  [&] { ekf.predict(Vec<2>(1.0, 0.0), 0.5, planarControlNoise()); });
  ekf.setIdealRobot(Vec<3>(0.5, 0.0, 0.0));
  CHECK_NOTHROW(ekf.update(RangeBearing(), 7, Vec<2>(4.0, 0.4), planarSensorNoise()));
  // A new landmark has no true state until one is handed over.
  ekf.add(8, InverseRangeBearing(), Vec<2>(3.0, -0.4), planarSensorNoise());
  requireRejected(ekf, ErrorCode::kInvalidArgument, "landmark 8 (setIdealLandmark)",
                  [&] { ekf.update(RangeBearing(), 8, Vec<2>(3.0, -0.4), planarSensorNoise()); });
  // Bad true states: unknown id, not finite.
  requireRejected(ekf, ErrorCode::kUnknownId, "99", [&] { ekf.setIdealLandmark<Point2>(99, Vec<2>(1.0, 1.0)); });
  requireRejected(ekf, ErrorCode::kNonFinite, "not finite", [&] { ekf.setIdealLandmark<Point2>(8, Vec<2>(NAN, 1.0)); });
  requireRejected(ekf, ErrorCode::kNonFinite, "not finite", [&] { ekf.setIdealRobot(Vec<3>(0.0, INFINITY, 0.0)); });
  ekf.setIdealLandmark<Point2>(8, Vec<2>(2.8, -1.1));
  CHECK_NOTHROW(ekf.update(RangeBearing(), 8, Vec<2>(3.0, -0.4), planarSensorNoise()));
}

TEST_CASE("ideal linearization: a wrong landmark type is refused") {
  Ekf<Unicycle2D, Point2, TreeXYR> ekf(Vec<3>::Zero(), Mat<3, 3>::Identity() * 0.01);
  ekf.add(1, InverseRangeBearing(), Vec<2>(5.0, 0.4), planarSensorNoise());
  requireRejected(ekf, ErrorCode::kWrongLandmarkType, "Point2",
                  [&] { ekf.setIdealLandmark<TreeXYR>(1, Vec<3>(1.0, 1.0, 0.2)); });
}

TEST_CASE("ideal linearization: about a true state equal to the estimate it is the textbook filter") {
  Filter ideal(Vec<3>::Zero(), Mat<3, 3>::Identity() * 0.01);
  Filter textbook(Vec<3>::Zero(), Mat<3, 3>::Identity() * 0.01);
  ideal.setLinearizationPoint(LinearizationPoint::kIdeal);
  for (Filter* f : {&ideal, &textbook}) f->add(3, InverseRangeBearing(), Vec<2>(4.0, 0.2), planarSensorNoise());
  for (int k = 0; k < 5; ++k) {
    ideal.setIdealRobot(ideal.robotMean());
    for (Filter* f : {&ideal, &textbook}) f->predict(Vec<2>(0.5, 0.1), 0.5, planarControlNoise());
    ideal.setIdealRobot(ideal.robotMean());
    ideal.setIdealLandmark<Point2>(3, ideal.landmarkMean<Point2>(3));
    const Vec<2> z(4.0 - 0.25 * k, 0.2 + 0.03 * k);
    for (Filter* f : {&ideal, &textbook}) f->update(RangeBearing(), 3, z, planarSensorNoise());
  }
  CHECK(ideal.mean().isApprox(textbook.mean(), 1e-12));
  CHECK(ideal.covariance().isApprox(textbook.covariance(), 1e-12));
}
