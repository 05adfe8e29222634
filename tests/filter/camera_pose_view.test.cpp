// The camera models are written for a Pose3D [t, q]; any robot that exposes a 3D pose view
// (`using Pose = Pose3D;` and `pose(x, J)`) reuses them, with the filter evaluating each model
// at pose(x) and chaining J_pose. Checked here for ConstantVelocity3D (its pose at the head of
// the state), OnManifold<ConstantVelocity3D>, and a robot written in this file whose pose sits
// behind two extra states:
// - every chained Jacobian (measurement, inverse and conversion models) against central
//   differences of the composed map x -> model(pose(x), ...), at ordinary and awkward geometry;
// - a filter whose extra states are independent of everything else gives the pose and the map
//   of a filter of the bare pose, on the same inputs.

#include <cmath>
#include <string>
#include <vector>

#include <sylva/detail/model_traits.hpp>
#include <sylva/diff/evaluate.hpp>
#include <sylva/diff/numeric_diff.hpp>
#include <sylva/filter/ekf.hpp>
#include <sylva/landmarks/inverse_depth.hpp>
#include <sylva/landmarks/inverse_depth_radius.hpp>
#include <sylva/landmarks/point3.hpp>
#include <sylva/landmarks/tree_xyzr.hpp>
#include <sylva/measurements/inverse_depth_initialization.hpp>
#include <sylva/measurements/inverse_depth_tree_width.hpp>
#include <sylva/measurements/inverse_tree_width.hpp>
#include <sylva/measurements/pinhole_point.hpp>
#include <sylva/measurements/tree_width.hpp>
#include <sylva/motion/constant_velocity_3d.hpp>
#include <sylva/motion/on_manifold.hpp>
#include <sylva/motion/pose_3d.hpp>

#include "../camera_pose.hpp"
#include "sylva_catch.hpp"

using namespace sylva;

namespace unity_filter_camera_pose_view {

/// d q / d theta for a small rotation theta applied on the right, q' = q (x) [1, theta / 2]:
/// 0.5 R_left(q) [0; I].
Mat<4, 3> quaternionRotationJacobian(const Vec<4>& q) {
  Mat<4, 3> J;
  J << -q[1], -q[2], -q[3],  //
      q[0], -q[3], q[2],     //
      q[3], q[0], -q[1],     //
      -q[2], q[1], q[0];
  return 0.5 * J;
}

/// A camera held still up to a random walk of its pose, x = [t (3), q (4)]: a Pose3D itself,
/// so every camera model fits it directly.
struct StillCamera : Pose3D {
  static constexpr int kControlDim = 0;
  static constexpr int kNoiseDim = 6;  ///< [position (3), rotation (3)] rates
  static constexpr const char* kName = "StillCamera";
  using Control = Vec<0>;
  State operator()(const State& x, const Control&, double dt, JacobianRef<7, 7> J_x = {},
                   JacobianRef<7, 6> J_n = {}) const {
    if (J_x) (*J_x).setIdentity();
    if (J_n) {
      (*J_n).setZero();
      (*J_n).topLeftCorner<3, 3>() = dt * Mat<3, 3>::Identity();
      (*J_n).bottomRightCorner<4, 3>() = dt * quaternionRotationJacobian(x.tail<4>());
    }
    return x;
  }
};

/// The same camera with two extra states in front of its pose, x = [b (2), t (3), q (4)] (a
/// clock offset and a scale of some other sensor, say), each a random walk of its own.
struct StillCameraWithBiases {
  static constexpr int kDim = 9;
  static constexpr int kControlDim = 0;
  static constexpr int kNoiseDim = 8;  ///< [biases (2), position (3), rotation (3)] rates
  static constexpr const char* kName = "StillCameraWithBiases";
  using State = Vec<9>;
  using Control = Vec<0>;
  using Pose = Pose3D;
  static Vec<7> pose(const State& x, JacobianRef<7, 9> J = {}) {
    if (J) {
      (*J).setZero();
      (*J).rightCols<7>().setIdentity();
    }
    return x.tail<7>();
  }
  State operator()(const State& x, const Control&, double dt, JacobianRef<9, 9> J_x = {},
                   JacobianRef<9, 8> J_n = {}) const {
    if (J_x) (*J_x).setIdentity();
    if (J_n) {
      (*J_n).setZero();
      (*J_n).topLeftCorner<5, 5>() = dt * Mat<5, 5>::Identity();
      (*J_n).bottomRightCorner<4, 3>() = dt * quaternionRotationJacobian(x.tail<4>());
    }
    return x;
  }
};

const PinholeCamera kCamera{500.0, 480.0, 320.0, 240.0, 640, 480};

/// A state of `Robot` whose pose is `pose`, its other entries set to values that must not enter
/// any measurement.
template <typename Robot>
Vec<Robot::kDim> withPose(const Vec<7>& pose) {
  Vec<Robot::kDim> x;
  if constexpr (Robot::kDim == 13) {
    x << pose, 0.3, -0.2, 0.1, 0.05, 0.1, -0.2;
  } else if constexpr (Robot::kDim == 9) {
    x << 0.7, -1.3, pose;
  } else {
    x = pose;
  }
  return x;
}

/// |a - n| <= tol max(|a|, |n|, floor) entrywise, with the floor scaled to the matrix.
template <typename A, typename B>
bool close(const A& analytic, const B& numeric, double tol) {
  const double floor = 1e-6 * std::max(1.0, numeric.cwiseAbs().maxCoeff());
  for (int i = 0; i < analytic.rows(); ++i)
    for (int j = 0; j < analytic.cols(); ++j) {
      const double a = analytic(i, j), n = numeric(i, j);
      if (!(std::abs(a - n) <= tol * std::max({std::abs(a), std::abs(n), floor}))) return false;
    }
  return true;
}

struct Geometry {
  std::string name;
  Vec<7> pose;
  Vec<4> tree;  ///< base centre and radius; the points are its base centre
};

std::vector<Geometry> geometries() {
  const Vec<3> eye(0.5, -0.3, 1.6);
  return {
      {"ordinary", sylva_test::lookAtPose(eye, Vec<3>(6.0, 1.0, 0.5)), Vec<4>(6.0, 1.0, 0.0, 0.3)},
      {"quaternion scaled by 3", sylva_test::lookAtPose(eye, Vec<3>(6.0, 1.0, 0.5), 0.4, 3.0), Vec<4>(6.0, 1.0, 0.0, 0.3)},
      {"rolled 90 degrees", sylva_test::lookAtPose(eye, Vec<3>(5.0, -2.0, 0.5), 1.5707963), Vec<4>(5.0, -2.0, 0.0, 0.25)},
      {"looking almost straight down", sylva_test::lookAtPose(Vec<3>(2.0, 0.0, 5.0), Vec<3>(2.0, 0.3, 0.0)),
       Vec<4>(2.0, 0.3, 0.0, 0.2)},
      {"far from the origin, past the azimuth seam", sylva_test::lookAtPose(Vec<3>(-250.0, 80.0, 1.7), Vec<3>(-262.0, 80.5, 0.5)),
       Vec<4>(-262.0, 80.5, 0.0, 0.4)},
  };
}

/// J_z_x of `model` through the robot's view, against central differences of
/// x -> model(view(x), landmark).
template <typename Robot, typename Model>
void checkMeasurementThroughView(const Model& model, const Vec<Robot::kDim>& x, const Vec<Model::Landmark::kDim>& l) {
  Mat<Model::kDim, Robot::kDim> J_x;
  Mat<Model::kDim, Model::Landmark::kDim> J_l;
  const Vec<Model::kDim> z = detail::evaluateOn<Robot>(model, x, l, J_x, J_l);
  const auto h = [&](const Vec<Robot::kDim>& y) { return detail::evaluateOn<Robot>(model, y, l, {}, {}); };
  CHECK(z == h(x));
  const Mat<Model::kDim, Robot::kDim> N = numericJacobian<Model::kDim, Robot::kDim>(h, x);
  INFO(Model::kName << " on " << Robot::kName << "\nanalytic\n" << J_x << "\nnumeric\n" << N);
  CHECK(close(J_x, N, 1e-5));
  // The columns of states outside the pose are exactly zero.
  if constexpr (detail::HasPoseView<Robot>::value) {
    for (int c = 0; c < Robot::kDim; ++c) {
      if (Robot::pose(Vec<Robot::kDim>(x + 1e-3 * Vec<Robot::kDim>::Unit(c))) == Robot::pose(x)) CHECK(J_x.col(c).isZero(0.0));
    }
  }
}

template <typename Robot, typename Inverse>
void checkInverseThroughView(const Inverse& inverse, const Vec<Robot::kDim>& x, const Vec<Inverse::kMeasurementDim>& z) {
  constexpr int L = Inverse::Landmark::kDim;
  Mat<L, Robot::kDim> J_x;
  Mat<L, Inverse::kMeasurementDim> J_z;
  detail::initializeOn<Robot>(inverse, x, z, J_x, J_z);
  const auto g = [&](const Vec<Robot::kDim>& y) {
    Mat<L, Robot::kDim> a;
    Mat<L, Inverse::kMeasurementDim> b;
    return detail::initializeOn<Robot>(inverse, y, z, a, b);
  };
  const Mat<L, Robot::kDim> N = numericJacobian<L, Robot::kDim>(
      g, x, [](const Vec<L>& a, const Vec<L>& b) { return detail::difference<typename Inverse::Landmark>(a, b); });
  INFO(Inverse::kName << " on " << Robot::kName << "\nanalytic\n" << J_x << "\nnumeric\n" << N);
  CHECK(close(J_x, N, 1e-5));
}

template <typename Robot, typename Conversion, typename... Measurement>
void checkConversionThroughView(const Conversion& conversion, const Vec<Robot::kDim>& x,
                                const Vec<Conversion::From::kDim>& l, const Measurement&... z) {
  constexpr int T = Conversion::To::kDim;
  using ModelRobot = detail::ConversionRobotT<Conversion, Robot>;
  const auto convert = [&](const Vec<Robot::kDim>& y, Mat<T, Robot::kDim>& J_y) {
    Mat<T, Conversion::From::kDim> J_l;
    return detail::throughRobotView<ModelRobot, Robot>(y, J_y, [&](const auto& view, auto& J_view) {
      if constexpr (sizeof...(Measurement) == 0) {
        return conversion(view, l, J_view, J_l);
      } else {
        Mat<T, Conversion::kMeasurementDim> J_z;
        return conversion(view, l, z..., J_view, J_l, J_z);
      }
    });
  };
  Mat<T, Robot::kDim> J_x;
  convert(x, J_x);
  const Mat<T, Robot::kDim> N = numericJacobian<T, Robot::kDim>(
      [&](const Vec<Robot::kDim>& y) {
        Mat<T, Robot::kDim> unused;
        return convert(y, unused);
      },
      x);
  INFO(Conversion::kName << " on " << Robot::kName << "\nanalytic\n" << J_x << "\nnumeric\n" << N);
  CHECK(close(J_x, N, 1e-5));
}

template <typename Robot>
void checkEveryCameraModel() {
  const PinholePoint<Point3> point_model(kCamera);
  const PinholePoint<InverseDepth> id_model(kCamera);
  const TreeWidth width_model(kCamera);
  const InverseDepthTreeWidth idr_model(kCamera);
  const InverseDepthInitialization id_init(kCamera);
  const InverseDepthRadiusInitialization idr_init(kCamera);
  for (const Geometry& g : geometries()) {
    INFO(g.name);
    const Vec<Robot::kDim> x = withPose<Robot>(g.pose);
    const Vec<3> base = g.tree.head<3>();
    const Vec<3> uvw = width_model(g.pose, g.tree);
    const Vec<3> z_id = id_init.measurement(point_model(g.pose, base));
    const Vec<4> z_idr = idr_init.measurement(uvw);
    // Landmarks first seen from a pose 1 m to the side, so the rays have parallax.
    const Vec<7> side = (Vec<7>() << g.pose.head<3>() + Vec<3>(0.3, 0.9, 0.1), g.pose.tail<4>()).finished();
    const Vec<6> l_id = id_init(side, id_init.measurement(point_model(side, base)));
    const Vec<7> l_idr = idr_init(side, idr_init.measurement(width_model(side, g.tree)));

    checkMeasurementThroughView<Robot>(point_model, x, base);
    checkMeasurementThroughView<Robot>(id_model, x, l_id);
    checkMeasurementThroughView<Robot>(width_model, x, g.tree);
    checkMeasurementThroughView<Robot>(idr_model, x, l_idr);
    checkInverseThroughView<Robot>(id_init, x, z_id);
    checkInverseThroughView<Robot>(idr_init, x, z_idr);
    checkConversionThroughView<Robot>(InverseTreeWidth(kCamera), x, base, uvw);
    checkConversionThroughView<Robot>(InverseDepthToPoint3<Pose3D>{}, x, l_id);
    checkConversionThroughView<Robot>(InverseDepthRadiusToTree<Pose3D>{}, x, l_idr);
  }
}

}  // namespace unity_filter_camera_pose_view

using namespace unity_filter_camera_pose_view;

TEST_CASE("pose view: every camera model serves every robot that exposes a 3D pose, with its Jacobians chained",
          "[filter][pose_view][jacobian]") {
  STATIC_REQUIRE(detail::kRobotFits<Pose3D, ConstantVelocity3D>);
  STATIC_REQUIRE(detail::kRobotFits<Pose3D, OnManifold<ConstantVelocity3D>>);
  STATIC_REQUIRE(detail::kRobotFits<Pose3D, StillCamera>);
  STATIC_REQUIRE(detail::kRobotFits<Pose3D, StillCameraWithBiases>);
  STATIC_REQUIRE(detail::kRobotFitsDirectly<Pose3D, StillCamera>);
  STATIC_REQUIRE_FALSE(detail::kRobotFitsDirectly<Pose3D, StillCameraWithBiases>);
  SECTION("ConstantVelocity3D") { checkEveryCameraModel<ConstantVelocity3D>(); }
  SECTION("a robot whose state is the pose") { checkEveryCameraModel<StillCamera>(); }
  SECTION("a robot with extra states before its pose") { checkEveryCameraModel<StillCameraWithBiases>(); }
  SECTION("the pose views' own Jacobians") {
    const Vec<13> x13 = withPose<ConstantVelocity3D>(geometries()[1].pose);
    Mat<7, 13> J13;
    ConstantVelocity3D::pose(x13, J13);
    CHECK(J13 == numericJacobian<7, 13>([](const Vec<13>& y) { return ConstantVelocity3D::pose(y); }, x13));
    const Vec<9> x9 = withPose<StillCameraWithBiases>(geometries()[1].pose);
    Mat<7, 9> J9;
    StillCameraWithBiases::pose(x9, J9);
    CHECK(J9 == numericJacobian<7, 9>([](const Vec<9>& y) { return StillCameraWithBiases::pose(y); }, x9));
  }
}

TEST_CASE("pose view: extra states that nothing observes leave the pose and the map of the bare-pose filter",
          "[filter][pose_view]") {
  using Bare = Ekf<StillCamera, InverseDepth, Point3, TreeXYZR>;
  using Biased = Ekf<StillCameraWithBiases, InverseDepth, Point3, TreeXYZR>;
  const PinholePoint<Point3> point_model(kCamera);
  const PinholePoint<InverseDepth> id_model(kCamera);
  const TreeWidth width_model(kCamera);
  const InverseDepthInitialization init(kCamera);
  const Vec<7> pose0 = sylva_test::lookAtPose(Vec<3>(0.0, 0.0, 1.5), Vec<3>(10.0, 0.5, 1.0));
  Mat<7, 7> P_pose = Mat<7, 7>::Zero();
  P_pose.topLeftCorner<3, 3>() = 1e-4 * Mat<3, 3>::Identity();
  const Mat<4, 3> Jq = quaternionRotationJacobian(pose0.tail<4>());
  P_pose.bottomRightCorner<4, 4>() = Jq * (1e-5 * Mat<3, 3>::Identity()) * Jq.transpose();
  Mat<9, 9> P_biased = Mat<9, 9>::Zero();
  P_biased.topLeftCorner<2, 2>() = Vec<2>(0.5, 2.0).asDiagonal();
  P_biased.bottomRightCorner<7, 7>() = P_pose;
  Bare bare(pose0, P_pose);
  Biased biased(withPose<StillCameraWithBiases>(pose0), P_biased);
  const Gaussian<6> walk = Gaussian<6>::sigmas((Vec<6>() << Vec<3>::Constant(2.0), Vec<3>::Constant(0.05)).finished());
  const Gaussian<8> walk_biased =
      Gaussian<8>::sigmas((Vec<8>() << 0.1, 0.3, Vec<3>::Constant(2.0), Vec<3>::Constant(0.05)).finished());
  const Gaussian<2> pixel = Gaussian<2>::sigmas(Vec<2>(1.0, 1.0));
  const Gaussian<3> pixel_width = Gaussian<3>::sigmas(Vec<3>(1.0, 1.0, 0.8));
  const std::vector<Vec<4>> trees{Vec<4>(8.0, 1.0, 0.0, 0.3), Vec<4>(11.0, -2.0, 0.2, 0.25), Vec<4>(14.0, 3.0, -0.1, 0.35)};
  for (int i = 0; i < 3; ++i) {
    const Vec<3> z = init.measurement(point_model(pose0, Vec<3>(trees[i].head<3>())));
    bare.add(i, init, z, init.noise(pixel));
    biased.add(i, init, z, init.noise(pixel));
  }
  // The true camera slides sideways, 0.2 m a step, so the trees gain parallax; the filters
  // see the true images, a little off.
  Vec<7> pose_true = pose0;
  for (int k = 0; k < 6; ++k) {
    pose_true.head<3>() += Vec<3>(0.0, 0.2, 0.0);
    bare.predict(Vec<0>(), 0.1, walk);
    biased.predict(Vec<0>(), 0.1, walk_biased);
    if (k == 3) {
      bare.reparametrize(0, InverseDepthToPoint3<Pose3D>{});
      biased.reparametrize(0, InverseDepthToPoint3<Pose3D>{});
      const Vec<3> uvw = width_model(pose_true, trees[0]) + Vec<3>(0.3, -0.2, 0.1);
      bare.reparametrize(0, InverseTreeWidth(kCamera), uvw, pixel_width);
      biased.reparametrize(0, InverseTreeWidth(kCamera), uvw, pixel_width);
    }
    // Measurements a little off the prediction, the same for both filters.
    const double s = 0.3 * std::sin(1.0 + k);
    for (Id id : {Id(1), Id(2)}) {
      const Vec<2> z = point_model(pose_true, Vec<3>(trees[id].head<3>())) + Vec<2>(s, -0.7 * s);
      bare.update(id_model, id, z, pixel);
      biased.update(id_model, id, z, pixel);
    }
    if (bare.holds<TreeXYZR>(0)) {
      const Vec<3> z = width_model(pose_true, trees[0]) + Vec<3>(-s, s, 0.5 * s);
      bare.update(width_model, 0, z, pixel_width);
      biased.update(width_model, 0, z, pixel_width);
    } else {
      const Vec<2> z = point_model(pose_true, Vec<3>(trees[0].head<3>())) + Vec<2>(s, s);
      bare.update(id_model, 0, z, pixel);
      biased.update(id_model, 0, z, pixel);
    }
  }
  REQUIRE(biased.holds<TreeXYZR>(0));
  const int n = bare.dim();
  REQUIRE(biased.dim() == n + 2);
  const Eigen::VectorXd mean = biased.mean();
  const Eigen::MatrixXd P = biased.covariance();
  const double scale = bare.covariance().cwiseAbs().maxCoeff();
  CHECK((mean.tail(n) - bare.mean()).cwiseAbs().maxCoeff() < 1e-12 * std::max(1.0, bare.mean().cwiseAbs().maxCoeff()));
  CHECK((P.bottomRightCorner(n, n) - bare.covariance()).cwiseAbs().maxCoeff() < 1e-12 * scale);
  // Nothing observes the biases: they keep their prior mean, a random-walk variance, and no
  // correlation with anything.
  CHECK(mean.head<2>() == Vec<2>(0.7, -1.3));
  CHECK(P(0, 0) == Approx(0.5 + 6 * (0.1 * 0.1) * (0.1 * 0.1)).epsilon(1e-12));  // + steps dt^2 sigma^2
  CHECK(P.block(0, 2, 2, n).cwiseAbs().maxCoeff() == 0.0);
  // The pose did move: the test compares filters that did something.
  CHECK((bare.robotMean() - pose0).norm() > 1e-3);
}
