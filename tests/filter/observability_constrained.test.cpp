// LinearizationPoint::kObservabilityConstrained: the gauge directions of every monocular
// state type (core/gauge.hpp), that every camera model is blind to them, and the filter's
// covariance transport, against a dense reference written here and against the property it
// exists for: an update adds no information along the unobservable directions.

#include <cmath>
#include <string>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <sylva/core/quaternion.hpp>
#include <sylva/diff/numeric_diff.hpp>
#include <sylva/filter/ekf.hpp>
#include <sylva/slam/tree_life_cycle.hpp>
#include <sylva/landmarks/inverse_depth.hpp>
#include <sylva/landmarks/inverse_depth_radius.hpp>
#include <sylva/landmarks/point2.hpp>
#include <sylva/landmarks/point3.hpp>
#include <sylva/landmarks/tree_xyzr.hpp>
#include <sylva/measurements/inverse_depth_tree_width.hpp>
#include <sylva/measurements/pinhole_point.hpp>
#include <sylva/measurements/tree_width.hpp>
#include <sylva/motion/constant_velocity_3d.hpp>
#include <sylva/motion/unicycle_2d.hpp>
#include <sylva/sim/forest_trajectory.hpp>

#include "../copy_init.hpp"
#include "../filter_snapshot.hpp"
#include "sylva_catch.hpp"

using namespace sylva;

namespace unity_observability_constrained {

using GaugeVec = Vec<kGaugeDim>;  // [translation (3), rotation about world z, log scale]

/// The gauge transformation g(theta): p -> exp(s) R_z(psi) p + t.
Mat<3, 3> yawMatrix(double psi) { return Eigen::AngleAxisd(psi, Vec<3>::UnitZ()).toRotationMatrix(); }
Vec<3> gaugeMovePoint(const GaugeVec& g, const Vec<3>& p) { return std::exp(g[4]) * (yawMatrix(g[3]) * p) + g.head<3>(); }

/// The azimuth and elevation of a unit direction, as InverseDepth stores them.
Vec<2> rayAngles(const Vec<3>& m) { return Vec<2>(std::atan2(m.y(), m.x()), std::atan2(m.z(), m.head<2>().norm())); }

Vec<3> movedPoint3(const GaugeVec& g, const Vec<3>& p) { return gaugeMovePoint(g, p); }
Vec<4> movedTree(const GaugeVec& g, const Vec<4>& l) {
  Vec<4> out;
  out << gaugeMovePoint(g, l.head<3>()), std::exp(g[4]) * l[3];
  return out;
}
Vec<6> movedInverseDepth(const GaugeVec& g, const Vec<6>& l) {
  const Vec<3> m = yawMatrix(g[3]) * InverseDepth::direction<double>(l[3], l[4]);
  Vec<6> out;
  out << gaugeMovePoint(g, l.head<3>()), rayAngles(m), l[5] * std::exp(-g[4]);
  return out;
}
Vec<7> movedInverseDepthRadius(const GaugeVec& g, const Vec<7>& l) {
  Vec<7> out;
  out << movedInverseDepth(g, l.head<6>()), l[6];
  return out;
}
Vec<13> movedCamera(const GaugeVec& g, const Vec<13>& x, ConstantVelocity3D::VelocityFrame frame) {
  const Eigen::Quaterniond turn(Eigen::AngleAxisd(g[3], Vec<3>::UnitZ()));
  const Vec<4> q = quaternionProduct<double>(Vec<4>(turn.w(), turn.x(), turn.y(), turn.z()), Vec<4>(x.segment<4>(3)));
  Vec<3> v = std::exp(g[4]) * x.segment<3>(7);
  if (frame == ConstantVelocity3D::VelocityFrame::kWorld) v = yawMatrix(g[3]) * v;
  Vec<13> out;
  out << gaugeMovePoint(g, x.head<3>()), q, v, x.tail<3>();
  return out;
}

/// d/dg of moved(g, x) at g = 0, with `difference` for the output.
template <int D, typename Moved, typename Difference>
Mat<D, kGaugeDim> numericGaugeDirections(Moved&& moved, Difference&& difference) {
  return numericJacobian<D, kGaugeDim>(moved, GaugeVec(GaugeVec::Zero()), difference);
}

Vec<13> gaugeTestCamera(const Vec<3>& r, const Vec<3>& rotation, const Vec<3>& v, const Vec<3>& omega) {
  Vec<13> x;
  x << r, quaternionFromRotationVector<double>(rotation), v, omega;
  return x;
}

/// A camera looking along its direction of travel `heading` (about world z), pitched down by
/// 15 degrees as the forest simulator's, driving forward at 1 m/s.
Vec<13> forwardLookingCamera(double heading, const Vec<3>& position) {
  const Eigen::Quaterniond q(sim::cameraOrientation(Vec<2>(std::cos(heading), std::sin(heading)), 15.0 * kRadPerDeg));
  Vec<13> x;
  x << position, q.w(), q.x(), q.y(), q.z(), std::cos(heading), std::sin(heading), 0.0, 0.0, 0.02, -0.1;
  return x;
}

}  // namespace unity_observability_constrained

using namespace unity_observability_constrained;

TEST_CASE("observability constrained: gauge directions match differentiating the transformation", "[filter][gauge]") {
  const auto plain = [](const auto& a, const auto& b) { return (a - b).eval(); };
  SECTION("Point3 and TreeXYZR") {
    for (const Vec<3>& p : {Vec<3>(3.0, -2.0, 0.5), Vec<3>(0.0, 0.0, 0.0), Vec<3>(-40.0, 1e3, -2.0)}) {
      INFO("p = " << p.transpose());
      const Mat<3, kGaugeDim> numeric = numericGaugeDirections<3>([&](const GaugeVec& g) { return movedPoint3(g, p); }, plain);
      CHECK((Point3::gaugeDirections(p) - numeric).cwiseAbs().maxCoeff() < 1e-6 * std::max(1.0, p.norm()));
      const Vec<4> tree(p.x(), p.y(), p.z(), 0.25);
      const Mat<4, kGaugeDim> numeric_tree = numericGaugeDirections<4>([&](const GaugeVec& g) { return movedTree(g, tree); }, plain);
      CHECK((TreeXYZR::gaugeDirections(tree) - numeric_tree).cwiseAbs().maxCoeff() < 1e-6 * std::max(1.0, p.norm()));
    }
  }
  SECTION("InverseDepth and InverseDepthRadius, the azimuth at the seam and a steep elevation") {
    const Vec<6> cases[] = {(Vec<6>() << 1.0, 2.0, 1.5, 0.4, -0.1, 0.1).finished(),
                            (Vec<6>() << -3.0, 0.5, 1.5, 3.14159, 0.05, 0.5).finished(),   // azimuth at +-pi
                            (Vec<6>() << 0.0, 0.0, 0.0, -1.0, 1.45, 0.02).finished(),     // nearly vertical ray
                            (Vec<6>() << 10.0, -7.0, 2.0, 2.0, -0.3, -0.05).finished()};  // rho < 0 (settling)
    for (const Vec<6>& l : cases) {
      INFO("l = " << l.transpose());
      const Mat<6, kGaugeDim> numeric = numericGaugeDirections<6>(
          [&](const GaugeVec& g) { return movedInverseDepth(g, l); }, [](const Vec<6>& a, const Vec<6>& b) { return InverseDepth::difference(a, b); });
      CHECK((InverseDepth::gaugeDirections(l) - numeric).cwiseAbs().maxCoeff() < 1e-6 * std::max(1.0, l.head<3>().norm()));
      Vec<7> idr;
      idr << l, 0.03;
      const Mat<7, kGaugeDim> numeric_idr = numericGaugeDirections<7>([&](const GaugeVec& g) { return movedInverseDepthRadius(g, idr); },
                                                            [](const Vec<7>& a, const Vec<7>& b) { return InverseDepthRadius::difference(a, b); });
      CHECK((InverseDepthRadius::gaugeDirections(idr) - numeric_idr).cwiseAbs().maxCoeff() < 1e-6 * std::max(1.0, l.head<3>().norm()));
      // The moved parametrization is the moved point: the action above is the right one.
      if (l[5] > 0.0) {
        const GaugeVec g = (GaugeVec() << 0.3, -1.0, 0.2, 0.7, 0.1).finished();
        CHECK((InverseDepth::point<double>(movedInverseDepth(g, l)) - gaugeMovePoint(g, InverseDepth::point<double>(l))).norm() < 1e-9);
      }
    }
  }
  SECTION("ConstantVelocity3D, velocity in either frame, moving or at rest") {
    using Frame = ConstantVelocity3D::VelocityFrame;
    const Vec<13> cases[] = {gaugeTestCamera(Vec<3>(1.0, -2.0, 1.5), Vec<3>(0.3, -1.2, 0.4), Vec<3>(0.8, 0.4, -0.1), Vec<3>(0.05, -0.3, 0.02)),
                             gaugeTestCamera(Vec<3>::Zero(), Vec<3>(0.0, 3.1, 0.0), Vec<3>::Zero(), Vec<3>(1.0, 2.0, -0.5))};
    for (const Frame frame : {Frame::kWorld, Frame::kCamera})
      for (const Vec<13>& x : cases) {
        INFO("x = " << x.transpose() << (frame == Frame::kCamera ? ", camera frame" : ", world frame"));
        const Mat<13, kGaugeDim> numeric = numericGaugeDirections<13>([&](const GaugeVec& g) { return movedCamera(g, x, frame); }, plain);
        CHECK((ConstantVelocity3D{frame}.gaugeDirections(x) - numeric).cwiseAbs().maxCoeff() < 1e-6 * std::max(1.0, x.head<3>().norm()));
      }
  }
}

TEST_CASE("observability constrained: every camera model is blind to the gauge, and the width model to no tilt",
          "[filter][gauge]") {
  const PinholeCamera camera{500.0, 500.0, 320.0, 240.0, 640, 480};
  const PinholePoint<Point3> xyz(camera);
  const PinholePoint<InverseDepth> id(camera);
  const TreeWidth width(camera);
  const InverseDepthTreeWidth idr_width(camera);
  const ConstantVelocity3D motion;
  // Ordinary geometry, and a camera far from the origin turned past the azimuth seam.
  for (const Vec<13>& x : {forwardLookingCamera(0.2, Vec<3>(0.5, -0.3, 1.5)), forwardLookingCamera(3.1, Vec<3>(-250.0, 80.0, 1.7))}) {
    const Mat<13, kGaugeDim> N_x = motion.gaugeDirections(x);
    const Vec<3> forward = Vec<3>(x[7], x[8], 0.0).normalized();
    const Vec<3> base = x.head<3>() + 8.0 * forward + Vec<3>(0.0, 0.0, -1.5) + 1.2 * Vec<3>(-forward.y(), forward.x(), 0.0);
    INFO("camera at " << x.head<3>().transpose() << ", tree at " << base.transpose());
    Mat<2, 13> H2x;
    Mat<3, 13> H3x;
    {
      Mat<2, 3> H_l;
      detail::evaluateOn<ConstantVelocity3D>(xyz, x, base, H2x, H_l);
      CHECK((H2x * N_x + H_l * Point3::gaugeDirections(base)).cwiseAbs().maxCoeff() < 1e-9 * H_l.norm() * base.norm());
    }
    {
      // The inverse-depth point first seen from 2 m behind, through the point `base`.
      const Vec<3> anchor = x.head<3>() - 2.0 * x.segment<3>(7).normalized();
      const Vec<3> ray = base - anchor;
      Vec<6> l;
      l << anchor, rayAngles(ray.normalized()), 1.0 / ray.norm();
      Mat<2, 6> H_l;
      detail::evaluateOn<ConstantVelocity3D>(id, x, l, H2x, H_l);
      CHECK((H2x * N_x + H_l * InverseDepth::gaugeDirections(l)).cwiseAbs().maxCoeff() < 1e-9 * H_l.norm() * anchor.norm());
    }
    {
      const Vec<4> tree(base.x(), base.y(), base.z(), 0.2);
      Mat<3, 4> H_l;
      detail::evaluateOn<ConstantVelocity3D>(width, x, tree, H3x, H_l);
      CHECK((H3x * N_x + H_l * TreeXYZR::gaugeDirections(tree)).cwiseAbs().maxCoeff() < 1e-9 * H_l.norm() * base.norm());
      // Tilting the world about the horizontal axis across the view is no part of the gauge: a
      // vertical trunk's width seen by a pitched camera changes with it. (For a camera whose
      // optical axis is horizontal the change is of second order.)
      const Vec<3> across(-forward.y(), forward.x(), 0.0);
      Vec<13> tilt_x = Vec<13>::Zero();
      tilt_x.head<3>() = across.cross(Vec<3>(x.head<3>()));
      tilt_x.segment<4>(3) = 0.5 * quaternionProduct<double>(Vec<4>(0.0, across.x(), across.y(), across.z()), Vec<4>(x.segment<4>(3)));
      tilt_x.segment<3>(7) = across.cross(Vec<3>(x.segment<3>(7)));
      Vec<4> tilt_l = Vec<4>::Zero();
      tilt_l.head<3>() = across.cross(Vec<3>(tree.head<3>()));
      CHECK(std::abs((H3x * tilt_x + H_l * tilt_l)[2]) > 1e-3);
    }
    {
      const Vec<3> anchor = x.head<3>() - 2.0 * x.segment<3>(7).normalized();
      const Vec<3> ray = base - anchor;
      Vec<7> l;
      l << anchor, rayAngles(ray.normalized()), 1.0 / ray.norm(), 0.2 / ray.norm();
      Mat<3, 7> H_l;
      detail::evaluateOn<ConstantVelocity3D>(idr_width, x, l, H3x, H_l);
      CHECK((H3x * N_x + H_l * InverseDepthRadius::gaugeDirections(l)).cwiseAbs().maxCoeff() < 1e-8 * H_l.norm() * anchor.norm());
    }
  }
}

namespace unity_observability_constrained {

/// A toy of monocular SLAM without quaternions: a robot with a heading psi about world z and
/// a world velocity, state [r (3), psi, v (3)], noise [a (3), heading rate]; it sees the
/// azimuth and elevation of a world point in its own frame, which moving, turning about z
/// and scaling the world leave unchanged.
struct HeadingRobot {
  static constexpr int kDim = 7;
  static constexpr int kControlDim = 0;
  static constexpr int kNoiseDim = 4;
  static constexpr const char* kName = "HeadingRobot";
  using State = Vec<7>;
  using Control = Vec<0>;
  State operator()(const State& x, const Control&, double dt, JacobianRef<7, 7> J_x = {}, JacobianRef<7, 4> J_n = {}) const {
    State next = x;
    next.head<3>() += dt * x.tail<3>();
    if (J_x) {
      (*J_x).setIdentity();
      (*J_x).block<3, 3>(0, 4) = dt * Mat<3, 3>::Identity();
    }
    if (J_n) {
      (*J_n).setZero();
      (*J_n).block<3, 3>(0, 0) = dt * dt * Mat<3, 3>::Identity();
      (*J_n).block<3, 3>(4, 0) = dt * Mat<3, 3>::Identity();
      (*J_n)(3, 3) = dt;
    }
    return next;
  }
  Mat<7, kGaugeDim> gaugeDirections(const State& x) const {
    Mat<7, kGaugeDim> N = Mat<7, kGaugeDim>::Zero();
    N.topLeftCorner<3, 3>().setIdentity();
    N.block<3, 1>(0, 3) << -x[1], x[0], 0.0;
    N(3, 3) = 1.0;
    N.block<3, 1>(4, 3) << -x[5], x[4], 0.0;
    N.block<3, 1>(0, 4) = x.head<3>();
    N.block<3, 1>(4, 4) = x.tail<3>();
    return N;
  }
};

/// Azimuth and elevation of a world point in the robot's frame (automatic differentiation).
struct BodyBearing {
  using Robot = HeadingRobot;
  using Landmark = Point3;
  static constexpr int kDim = 2;
  static constexpr const char* kName = "BodyBearing";
  template <typename T>
  Vec<2, T> predict(const Vec<7, T>& x, const Vec<3, T>& p) const {
    using std::atan2;
    using std::cos;
    using std::sin;
    using std::sqrt;
    const Vec<3, T> d = p - x.template head<3>();
    const T c = cos(x[3]), s = sin(x[3]);
    const T dx = c * d[0] + s * d[1], dy = -s * d[0] + c * d[1];
    return Vec<2, T>(atan2Generic(dy, dx), atan2Generic(d[2], T(sqrt(dx * dx + dy * dy))));
  }
};

const Vec<3> kToyPoints[] = {{6.0, 1.0, 0.5}, {4.0, -3.0, -0.5}, {8.0, 4.0, 1.0}, {-2.0, 5.0, 0.2}};

/// A filter with a correlated prior over the robot and four points.
template <typename Filter>
Filter toyGaugeFilter() {
  Vec<7> x0;
  x0 << 0.2, -0.1, 0.0, 0.1, 1.0, 0.2, 0.0;
  Mat<7, 7> P0 = Mat<7, 7>::Identity() * 0.01;
  P0(3, 3) = 0.004;
  P0(0, 4) = P0(4, 0) = 0.003;
  Filter ekf(x0, P0);
  for (int i = 0; i < 4; ++i) ekf.add(i, sylva_test::CopyInit<HeadingRobot, Point3>{}, kToyPoints[i], Gaussian<3>::sigmas(Vec<3>(0.5, 0.4, 0.3)));
  // Correlate the map with the robot: a few textbook updates.
  for (int i = 0; i < 4; ++i) ekf.update(BodyBearing{}, i, BodyBearing{}.predict<double>(ekf.robotMean(), kToyPoints[i]) + Vec<2>(0.01, -0.02),
                                         Gaussian<2>::sigmas(Vec<2>(0.02, 0.02)));
  return ekf;
}

template <typename Filter>
Eigen::MatrixXd toyGaugeOf(const Filter& ekf, const Eigen::VectorXd& mean) {
  Eigen::MatrixXd N(mean.size(), kGaugeDim);
  N.topRows<7>() = HeadingRobot{}.gaugeDirections(mean.head<7>());
  for (const auto& s : ekf.slots()) N.middleRows<3>(s.offset) = Point3::gaugeDirections(mean.segment<3>(s.offset));
  return N;
}

/// N^T P^-1 N: the information the covariance holds along the gauge.
Mat<kGaugeDim, kGaugeDim> gaugeInformation(const Eigen::MatrixXd& P, const Eigen::MatrixXd& N) {
  return N.transpose() * P.llt().solve(N);
}

}  // namespace unity_observability_constrained

TEMPLATE_TEST_CASE("observability constrained: the covariance is carried by T = I + dN A, A N = I",
                   "[filter][gauge]", (Ekf<HeadingRobot, Point3>), (JosephEkf<HeadingRobot, Point3>)) {
  const auto noise = Gaussian<2>::sigmas(Vec<2>(0.02, 0.03));
  const std::vector<Observation<BodyBearing>> batch = {
      {0, Vec<2>(0.12, 0.06), noise}, {2, Vec<2>(0.41, 0.09), noise}, {3, Vec<2>(1.92, 0.03), noise}};
  for (const GaugeInverse inverse : {GaugeInverse::kRobot, GaugeInverse::kWholeState})
  for (const bool batched : {false, true}) {
    INFO((batched ? "batched update" : "single update") << (inverse == GaugeInverse::kRobot ? ", robot's inverse" : ", whole state's inverse"));
    TestType textbook = toyGaugeFilter<TestType>();
    TestType constrained = textbook;
    constrained.setLinearizationPoint(LinearizationPoint::kObservabilityConstrained);
    constrained.setGaugeInverse(inverse);
    const Eigen::VectorXd prior = textbook.mean();
    if (batched) {
      textbook.update(BodyBearing{}, batch);
      constrained.update(BodyBearing{}, batch);
    } else {
      textbook.update(BodyBearing{}, 1, Vec<2>(-0.45, -0.04), noise);
      constrained.update(BodyBearing{}, 1, Vec<2>(-0.45, -0.04), noise);
    }
    // The same mean; the covariance carried as the dense reference says.
    CHECK((constrained.mean() - textbook.mean()).cwiseAbs().maxCoeff() == 0.0);
    const Eigen::MatrixXd N = toyGaugeOf(textbook, prior);
    const Eigen::MatrixXd dN = toyGaugeOf(textbook, textbook.mean()) - N;
    const Eigen::MatrixXd N_r = N.topRows<7>();
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(kGaugeDim, N.rows());
    if (inverse == GaugeInverse::kRobot)
      A.leftCols<7>() = (N_r.transpose() * N_r).inverse() * N_r.transpose();
    else
      A = (N.transpose() * N).inverse() * N.transpose();
    const Eigen::MatrixXd T = Eigen::MatrixXd::Identity(N.rows(), N.rows()) + dN * A;
    CHECK((T * N - (N + dN)).cwiseAbs().maxCoeff() < 1e-12);
    const Eigen::MatrixXd expected = T * textbook.covariance() * T.transpose();
    CHECK((constrained.covariance() - expected).cwiseAbs().maxCoeff() < 1e-12 * expected.cwiseAbs().maxCoeff());
    // The update left the information along the gauge where the prior had it.
    const TestType before = toyGaugeFilter<TestType>();
    const Mat<kGaugeDim, kGaugeDim> prior_information = gaugeInformation(before.covariance(), N);
    const Mat<kGaugeDim, kGaugeDim> kept = gaugeInformation(constrained.covariance(), N + dN);
    const Mat<kGaugeDim, kGaugeDim> gained = gaugeInformation(textbook.covariance(), N + dN);
    INFO("prior information along the gauge\n" << prior_information << "\nconstrained\n" << kept << "\ntextbook\n" << gained);
    CHECK((kept - prior_information).norm() < 1e-9 * prior_information.norm());
    CHECK((gained - prior_information).norm() > 1e-5 * prior_information.norm());
  }
}

TEST_CASE("observability constrained: over a drive, the information along the gauge never grows", "[filter][gauge]") {
  // No process noise, so nothing but the updates can change the information along the gauge:
  // the prediction's textbook Jacobian carries N(x) into N(f(x)) exactly.
  using ToyFilter = Ekf<HeadingRobot, Point3>;
  ToyFilter textbook = toyGaugeFilter<ToyFilter>();
  ToyFilter constrained = textbook;
  constrained.setLinearizationPoint(LinearizationPoint::kObservabilityConstrained);
  const Mat<kGaugeDim, kGaugeDim> start = gaugeInformation(constrained.covariance(), toyGaugeOf(constrained, constrained.mean()));
  const auto none = Gaussian<4>::sigmas(Vec<4>::Constant(1e-12));
  const auto noise = Gaussian<2>::sigmas(Vec<2>(0.02, 0.02));
  Vec<7> truth = constrained.robotMean();
  double textbook_growth = 0.0, constrained_growth = 0.0;
  for (int k = 0; k < 40; ++k) {
    truth.head<3>() += 0.1 * truth.tail<3>();
    for (ToyFilter* f : {&textbook, &constrained}) {
      f->predict(Vec<0>(), 0.1, none);
      for (int i = 0; i < 4; ++i) {
        const Vec<2> z = BodyBearing{}.predict<double>(truth, kToyPoints[i]) + Vec<2>(0.01 * std::sin(k + i), 0.01 * std::cos(3 * k + i));
        f->update(BodyBearing{}, i, z, noise);
      }
    }
    const auto growth = [&](const ToyFilter& f) {
      return (gaugeInformation(f.covariance(), toyGaugeOf(f, f.mean())) - start).norm() / start.norm();
    };
    textbook_growth = std::max(textbook_growth, growth(textbook));
    constrained_growth = std::max(constrained_growth, growth(constrained));
  }
  INFO("largest relative change of N^T P^-1 N: textbook " << textbook_growth << ", constrained " << constrained_growth);
  CHECK(constrained_growth < 1e-5);
  CHECK(textbook_growth > 1e-2);
}

TEST_CASE("observability constrained: refused where a type declares no gauge, and bad input leaves the filter as it was",
          "[filter][gauge][errors]") {
  Ekf<Unicycle2D, Point2> planar(Vec<3>::Zero(), Mat<3, 3>::Identity());
  try {
    planar.setLinearizationPoint(LinearizationPoint::kObservabilityConstrained);
    FAIL("not refused");
  } catch (const Error& e) {
    CHECK(e.code() == ErrorCode::kInvalidArgument);
    CHECK(std::string(e.what()).find("gaugeDirections") != std::string::npos);
    CHECK(std::string(e.what()).find("Unicycle2D") != std::string::npos);
  }
  CHECK(planar.linearizationPoint() == LinearizationPoint::kCurrentEstimate);

  auto ekf = toyGaugeFilter<Ekf<HeadingRobot, Point3>>();
  ekf.setLinearizationPoint(LinearizationPoint::kObservabilityConstrained);
  const auto noise = Gaussian<2>::sigmas(Vec<2>(0.02, 0.02));
  sylva_test::requireRejected(ekf, ErrorCode::kNonFinite, "not finite",
                              [&] { ekf.update(BodyBearing{}, 0, Vec<2>(std::nan(""), 0.0), noise); });
  sylva_test::requireRejected(ekf, ErrorCode::kUnknownId, "17", [&] { ekf.update(BodyBearing{}, 17, Vec<2>(0.1, 0.0), noise); });
}

TEST_CASE("landmarkCovarianceGivenRobot is the Schur complement of the robot block", "[filter][gauge]") {
  auto ekf = toyGaugeFilter<Ekf<HeadingRobot, Point3>>();
  const Eigen::MatrixXd P = ekf.covariance();
  const auto& slot = ekf.slots()[2];
  const Eigen::MatrixXd P_xx = P.topLeftCorner<7, 7>();
  const Eigen::MatrixXd P_xl = P.block(0, slot.offset, 7, 3);
  const Eigen::MatrixXd expected = P.block(slot.offset, slot.offset, 3, 3) - P_xl.transpose() * P_xx.inverse() * P_xl;
  const Mat<3, 3> given = landmarkCovarianceGivenRobot<Point3>(ekf, slot.id);
  CHECK((given - expected).cwiseAbs().maxCoeff() < 1e-12);
  CHECK(given.trace() < ekf.landmarkCovariance<Point3>(slot.id).trace());
}
