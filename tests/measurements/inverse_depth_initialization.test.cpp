// InverseDepthInitialization: construction and helpers, the direction convention (m parallel
// to the back-projected ray), round trips through PinholePoint<InverseDepth> and through
// InverseDepthToPoint3 + PinholePoint<Point3>, analytic Jacobians against central
// differences at ordinary and awkward geometry (image corners, arbitrary rotations,
// unnormalized quaternions, rays near the zenith and nadir), rejected input, and the
// monocular filter end to end: add, PinholePoint<InverseDepth> updates from a moving camera,
// the switch to XYZ, PinholePoint<Point3> updates, against the dense reference EKF.

#include "camera_pose.hpp"
#include "sylva_catch.hpp"

#include <cmath>
#include <string>
#include <type_traits>

#include <Eigen/Geometry>

#include <sylva/filter/ekf.hpp>
#include <sylva/landmarks/inverse_depth.hpp>
#include <sylva/landmarks/point3.hpp>
#include <sylva/landmarks/tree_xyzr.hpp>
#include <sylva/measurements/inverse_depth_initialization.hpp>
#include <sylva/measurements/pinhole_point.hpp>
#include <sylva/motion/constant_velocity_3d.hpp>
#include <sylva/sim/random.hpp>
#include <sylva/testing/check_jacobians.hpp>
#include <sylva/testing/dense_reference_ekf.hpp>

#include "error_helpers.hpp"

// Own namespace: the tests of a folder are compiled as one unity translation unit.
namespace unity_measurements_inverse_depth_initialization {

using namespace sylva;
using sylva_test::lookAt;
using sylva_test::lookAtPose;
using sylva_test::throwsCode;

namespace {

constexpr double kPiD = 3.14159265358979323846;
const PinholeCamera kCamera{500.0, 480.0, 320.0, 240.0, 640, 480};

Vec<7> randomCamera(sim::Rng& rng) {
  Vec<4> q(rng.normal(), rng.normal(), rng.normal(), rng.normal());
  q *= std::exp(rng.uniform(std::log(0.2), std::log(5.0))) / q.norm();
  Vec<7> x;
  x << rng.uniform(-5, 5), rng.uniform(-5, 5), rng.uniform(-2, 2), q;
  return x;
}

Mat<3, 3> cameraToWorld(const Vec<7>& x) {
  return rotationMatrix<double>(Vec<4>(x.segment<4>(3).normalized()));
}

void requireJacobians(const InverseDepthInitialization& init,
                      const Vec<7>& x,
                      const Vec<3>& z,
                      double tolerance = 1e-6) {
  const testing::JacobianReport report = testing::checkInverseJacobians(init, x, z, tolerance);
  INFO(report.message());
  CHECK(report.ok);
}

}  // namespace

TEST_CASE("InverseDepthInitialization: construction and helpers",
          "[measurements][inverse_depth_init]") {
  STATIC_REQUIRE(InverseDepthInitialization::kMeasurementDim == 3);
  STATIC_REQUIRE(std::is_same_v<InverseDepthInitialization::Robot, Pose3D>);
  STATIC_REQUIRE(std::is_same_v<InverseDepthInitialization::Landmark, InverseDepth>);
  CHECK(std::string(InverseDepthInitialization::kName) == "InverseDepthInitialization");

  const InverseDepthInitialization init(kCamera);
  CHECK(init.initialInverseDepth() == 0.1);  // Civera et al.'s defaults
  CHECK(init.inverseDepthSigma() == 0.5);
  CHECK(init.measurement(Vec<2>(12.5, 300.25)) == Vec<3>(12.5, 300.25, 0.1));
  const Mat<3, 3> R = init.noise(2.0).covariance();
  CHECK(R == Vec<3>(4.0, 4.0, 0.25).asDiagonal().toDenseMatrix());
  Mat<2, 2> pixel_cov;
  pixel_cov << 2.0, 0.5, 0.5, 1.0;
  const Mat<3, 3> R2 = init.noise(Gaussian<2>::covariance(pixel_cov)).covariance();
  CHECK(R2.topLeftCorner<2, 2>() == pixel_cov);
  CHECK(R2(2, 2) == 0.25);
  CHECK(R2.col(2).head<2>().isZero(0.0));
  const InverseDepthInitialization custom(kCamera, 0.05, 0.2);
  CHECK(custom.measurement(Vec<2>(1, 2))[2] == 0.05);
  CHECK(custom.noise(1.0).covariance()(2, 2) == Approx(0.04).epsilon(1e-15));

  auto rejects = [](const PinholeCamera& camera, double rho0, double sigma, ErrorCode code) {
    return throwsCode([&] { InverseDepthInitialization bad(camera, rho0, sigma); }, code);
  };
  CHECK(rejects(kCamera, 0.0, 0.5, ErrorCode::kInvalidArgument));
  CHECK(rejects(kCamera, -0.1, 0.5, ErrorCode::kInvalidArgument));
  CHECK(rejects(kCamera, 0.1, 0.0, ErrorCode::kInvalidArgument));
  CHECK(rejects(kCamera, 0.1, -1.0, ErrorCode::kInvalidArgument));
  CHECK(rejects(kCamera, NAN, 0.5, ErrorCode::kNonFinite));
  CHECK(rejects(kCamera, 0.1, INFINITY, ErrorCode::kNonFinite));
  CHECK(rejects({0.0, 1.0, 0.0, 0.0, 10, 10}, 0.1, 0.5, ErrorCode::kInvalidArgument));
  CHECK(rejects({1.0, 1.0, NAN, 0.0, 10, 10}, 0.1, 0.5, ErrorCode::kNonFinite));
  CHECK(throwsCode([&] { init.noise(0.0); }, ErrorCode::kNotPositiveDefinite));
}

TEST_CASE("InverseDepthInitialization: the ray and the round trips",
          "[measurements][inverse_depth_init]") {
  const InverseDepthInitialization init(kCamera);
  const PinholePoint<InverseDepth> id_model(kCamera);
  const PinholePoint<Point3> point_model(kCamera);
  const InverseDepthToPoint3<Pose3D> to_point;

  SECTION("a camera looking along world +x") {
    // The principal ray is world +x: theta = 0, phi = 0; the pixel right of centre turns the
    // ray towards world -y (theta < 0), the pixel above the centre towards +z (phi > 0).
    const Vec<7> x = lookAtPose(Vec<3>(1, 2, 3), Vec<3>(10, 2, 3));
    const Vec<6> l = init(x, init.measurement(Vec<2>(kCamera.cx, kCamera.cy)));
    CHECK(l.head<3>() == x.head<3>());
    CHECK(l[3] == Approx(0.0).margin(1e-12));
    CHECK(l[4] == Approx(0.0).margin(1e-12));
    CHECK(l[5] == 0.1);
    const Vec<6> right = init(x, init.measurement(Vec<2>(kCamera.cx + 500.0, kCamera.cy)));
    CHECK(right[3] == Approx(-kPiD / 4).epsilon(1e-12));
    const Vec<6> up = init(x, init.measurement(Vec<2>(kCamera.cx, kCamera.cy - 480.0)));
    CHECK(up[4] == Approx(kPiD / 4).epsilon(1e-12));
  }
  SECTION("random cameras and pixels, inside and outside the image") {
    sim::Rng rng(8101);
    for (int trial = 0; trial < 500; ++trial) {
      const Vec<7> x = randomCamera(rng);
      const Vec<2> pixel(rng.uniform(-200, 840), rng.uniform(-200, 680));
      const double rho0 =
          trial % 5 == 0 ? 0.0 : std::exp(rng.uniform(std::log(1e-4), std::log(10.0)));
      const Vec<3> z(pixel[0], pixel[1], rho0);
      const Vec<6> l = init(x, z);
      INFO("trial " << trial << " pixel " << pixel.transpose() << " rho0 " << rho0);
      // m(theta, phi) is the back-projected ray, normalized: parallel, same sense.
      const Vec<3> h_W =
          cameraToWorld(x) *
          Vec<3>((pixel[0] - kCamera.cx) / kCamera.fx, (pixel[1] - kCamera.cy) / kCamera.fy, 1.0);
      const Vec<3> m = InverseDepth::direction<double>(l[3], l[4]);
      CHECK((m - h_W.normalized()).norm() < 1e-14);
      CHECK(l[5] == rho0);
      // Back through the forward model from the same camera: the same pixel, exactly.
      CHECK((id_model(x, l) - pixel).cwiseAbs().maxCoeff() < 1e-9);
      if (rho0 > 0.0) {
        // The Euclidean point on the ray projects to the same pixel.
        const Vec<3> p = to_point(x, l);
        CHECK((p - x.head<3>()).norm() == Approx(1.0 / rho0).epsilon(1e-12));
        CHECK((point_model(x, p) - pixel).cwiseAbs().maxCoeff() < 1e-9);
      }
    }
  }
}

TEST_CASE("InverseDepthInitialization Jacobians match numerical differentiation",
          "[measurements][inverse_depth_init][jacobian]") {
  const InverseDepthInitialization init(kCamera);

  SECTION("arbitrary rotations, quaternion scales 0.2-5, pixels over and beyond the image") {
    sim::Rng rng(8102);
    for (int trial = 0; trial < 300; ++trial) {
      const Vec<7> x = randomCamera(rng);
      const Vec<3> z(rng.uniform(-100, 740), rng.uniform(-100, 580), rng.uniform(0.01, 2.0));
      INFO("trial " << trial);
      requireJacobians(init, x, z);
    }
  }
  SECTION("image corners and a level camera") {
    const Vec<7> x = lookAtPose(Vec<3>(1, -2, 1.5), Vec<3>(6, 1, 1.0));
    for (const Vec<2>& px :
         {Vec<2>(0, 0), Vec<2>(640, 0), Vec<2>(640, 480), Vec<2>(0, 480), Vec<2>(320, 240)})
      requireJacobians(init, x, init.measurement(px));
  }
  SECTION("quaternion far from unit norm") {
    for (double scale : {0.05, 20.0, 1e3}) {
      const Vec<7> x = lookAtPose(Vec<3>(1, -2, 1.5), Vec<3>(6, 1, 1.0), 0.0, scale);
      requireJacobians(init, x, init.measurement(Vec<2>(100, 400)));
      Mat<6, 7> J_x;
      const Vec<6> l = init(x, init.measurement(Vec<2>(100, 400)), J_x);
      const Vec<6> l_unit =
          init(lookAtPose(Vec<3>(1, -2, 1.5), Vec<3>(6, 1, 1.0)), init.measurement(Vec<2>(100, 400)));
      CHECK((l - l_unit).norm() < 1e-12);
      CHECK((J_x.middleCols<4>(3) * x.segment<4>(3)).norm() < 1e-9 * (1.0 + J_x.norm()));
      CHECK(J_x.row(5).isZero(0.0));
    }
  }
  SECTION("rays near the zenith and the nadir") {
    // A camera looking straight up (resp. down): the principal ray is vertical, and pixels a
    // few pixels from the principal point have phi within a few 1e-3 rad of +-pi/2. The
    // azimuth's Jacobian grows like 1 / cos(phi) there; it is still exact.
    for (double sign : {1.0, -1.0}) {
      const Vec<7> x =
          lookAtPose(Vec<3>(0.5, 0.5, 1.0), Vec<3>(0.5, 0.5, 1.0 + sign));
      for (double offset_px : {50.0, 5.0, 0.5}) {
        const Vec<3> z =
            init.measurement(Vec<2>(kCamera.cx + offset_px, kCamera.cy + 0.3 * offset_px));
        Mat<6, 7> J_x;
        Mat<6, 3> J_z;
        const Vec<6> l = init(x, z, J_x, J_z);
        INFO("sign " << sign << " offset " << offset_px << " px: phi = " << l[4]);
        CHECK(std::abs(l[4]) > kPiD / 2 - 1.2 * offset_px / kCamera.fy);
        CHECK(l[4] * sign > 0.0);
        // The relative error of central differences grows as the step approaches the distance
        // to the pole (the step in u is 1e-6 |u| px ~ 3e-4 px against 0.5 px): 1e-5 there.
        requireJacobians(init, x, z, offset_px < 1.0 ? 1e-5 : 1e-6);
        // |d theta / d(u, v)| ~ 1 / (distance to the pole's image in px).
        const double distance_px = std::hypot(offset_px, 0.3 * offset_px);
        CHECK(J_z.block<1, 2>(3, 0).norm() > 0.9 / distance_px);
        CHECK(J_z.block<1, 2>(3, 0).norm() < 1.1 / distance_px);
      }
      // Exactly on the vertical: the azimuth is undefined.
      CHECK(throwsCode([&] { init(x, init.measurement(Vec<2>(kCamera.cx, kCamera.cy))); },
                       ErrorCode::kDegenerateGeometry));
    }
  }
}

TEST_CASE("InverseDepthInitialization rejects bad input",
          "[measurements][inverse_depth_init][errors]") {
  const InverseDepthInitialization init(kCamera);
  const Vec<7> x = lookAtPose(Vec<3>(1, -2, 1.5), Vec<3>(6, 1, 1.0));
  const Vec<3> z = init.measurement(Vec<2>(100, 200));
  Mat<6, 7> J_x;
  Mat<6, 3> J_z;
  auto throws = [&](const Vec<7>& xx, const Vec<3>& zz, ErrorCode code) {
    return throwsCode([&] { init(xx, zz); }, code) &&
           throwsCode([&] { init(xx, zz, J_x, J_z); }, code);
  };
  for (double bad : {NAN, INFINITY}) {
    for (int i : {1, 3, 6}) {
      Vec<7> xb = x;
      xb[i] = bad;
      CHECK(throws(xb, z, ErrorCode::kNonFinite));
    }
    for (int i = 0; i < 3; ++i) {
      Vec<3> zb = z;
      zb[i] = bad;
      CHECK(throws(x, zb, ErrorCode::kNonFinite));
    }
  }
  Vec<7> x_zero = x;
  x_zero.segment<4>(3).setZero();
  CHECK(throws(x_zero, z, ErrorCode::kDegenerateGeometry));
  CHECK(throws(x, Vec<3>(100, 200, -0.1), ErrorCode::kDegenerateGeometry));
  CHECK_NOTHROW(init(x, Vec<3>(100, 200, 0.0), J_x, J_z));  // a point at infinity
}

// ---------------------------------------------------------------------------------------
// The monocular filter end to end.

namespace {

using MonoEkf = Ekf<ConstantVelocity3D, InverseDepth, Point3, TreeXYZR>;
using Reference = testing::DenseReferenceEkf<ConstantVelocity3D>;

// A camera 1.5 m above the ground looking along world +x and moving sideways along world +y
// at 0.5 m/s; its velocity is known well (the scale of a monocular map comes from it).
Vec<13> startCamera() {
  Vec<13> x = lookAt(Vec<3>(0.0, 0.0, 1.5), Vec<3>(10.0, 0.0, 1.5));
  x.segment<3>(7) = Vec<3>(0.0, 0.5, 0.0);
  x.segment<3>(10).setZero();
  return x;
}

Mat<13, 13> startCovariance() {
  Vec<13> sigma;
  sigma << 1e-3, 1e-3, 1e-3, 1e-4, 1e-4, 1e-4, 1e-4, 1e-3, 1e-3, 1e-3, 1e-3, 1e-3, 1e-3;
  return sigma.array().square().matrix().asDiagonal();
}

}  // namespace

TEST_CASE(
    "Monocular EKF: an inverse-depth point converges then switches to XYZ and keeps converging",
    "[measurements][inverse_depth_init][filter]") {
  const InverseDepthInitialization init(kCamera);
  const PinholePoint<InverseDepth> id_model(kCamera);
  const PinholePoint<Point3> point_model(kCamera);
  const ConstantVelocity3D motion;
  const Gaussian<6> process =
      Gaussian<6>::sigmas((Vec<6>() << Vec<3>::Constant(1e-3), Vec<3>::Constant(1e-3)).finished());
  const double sigma_px = 0.5;
  const Gaussian<2> pixel_noise = Gaussian<2>::sigmas(Vec<2>(sigma_px, sigma_px));
  const double dt = 0.1;
  const Vec<3> truth(6.0, 1.0, 2.0);

  sim::Rng rng(8201);
  Vec<13> camera = startCamera();
  MonoEkf ekf(camera, startCovariance());
  auto observe = [&] {
    return Vec<2>(point_model(ConstantVelocity3D::pose(camera), truth) +
                  Vec<2>(sigma_px * rng.normal(), sigma_px * rng.normal()));
  };

  const Id id = 7;
  ekf.add(id, init, init.measurement(observe()), init.noise(sigma_px));
  REQUIRE(ekf.holds<InverseDepth>(id));
  const double sigma_rho_0 = std::sqrt(ekf.landmarkCovariance<InverseDepth>(id)(5, 5));
  CHECK(sigma_rho_0 == Approx(0.5).epsilon(1e-3));  // the prior dominates
  const double error_0 =
      (InverseDepth::point<double>(ekf.landmarkMean<InverseDepth>(id)) - truth).norm();

  double sigma_rho_prev = sigma_rho_0;
  int steps = 0;
  double linearity = INFINITY;
  // Inverse-depth phase: until Civera et al.'s linearity index drops below 0.1 (at most 60
  // steps, 3 m of sideways motion).
  for (; steps < 60 && linearity >= 0.1; ++steps) {
    camera = motion(camera, Vec<0>(), dt);
    ekf.predict(Vec<0>(), dt, process);
    ekf.update(id_model, id, observe(), pixel_noise);
    const double sigma_rho = std::sqrt(ekf.landmarkCovariance<InverseDepth>(id)(5, 5));
    CHECK(sigma_rho <= sigma_rho_prev * (1.0 + 1e-9));  // the depth only gets more certain
    sigma_rho_prev = sigma_rho;
    linearity = inverseDepthLinearityIndex(
        ekf.robotMean().head<3>(), ekf.landmarkMean<InverseDepth>(id), sigma_rho);
  }
  INFO("steps in inverse depth: " << steps << ", linearity index " << linearity);
  CHECK(steps > 3);  // the first few views cannot fix the depth
  CHECK(linearity < 0.1);
  CHECK(sigma_rho_prev < 0.05 * sigma_rho_0);
  const Vec<6> l = ekf.landmarkMean<InverseDepth>(id);
  const double error_id = (InverseDepth::point<double>(l) - truth).norm();
  INFO("error at init " << error_0 << " m, after inverse-depth updates " << error_id << " m");
  CHECK(error_id < 0.3);
  CHECK(error_id < 0.1 * error_0);

  // Switch to XYZ and keep observing the point from the moving camera.
  ekf.reparametrize(id, InverseDepthToPoint3<ConstantVelocity3D>());
  REQUIRE(ekf.holds<Point3>(id));
  CHECK((ekf.landmarkMean<Point3>(id) - InverseDepth::point<double>(l)).norm() < 1e-12);
  double trace_prev = ekf.landmarkCovariance<Point3>(id).trace();
  for (int k = 0; k < 40; ++k) {
    camera = motion(camera, Vec<0>(), dt);
    ekf.predict(Vec<0>(), dt, process);
    ekf.update(point_model, id, observe(), pixel_noise);
    const double trace = ekf.landmarkCovariance<Point3>(id).trace();
    CHECK(trace <= trace_prev * (1.0 + 1e-9));
    trace_prev = trace;
  }
  const Vec<3> p = ekf.landmarkMean<Point3>(id);
  const Mat<3, 3> P = ekf.landmarkCovariance<Point3>(id);
  const double error_xyz = (p - truth).norm();
  const double nees = (p - truth).dot(P.ldlt().solve(p - truth));
  INFO("error after XYZ updates " << error_xyz << " m, NEES " << nees << ", sigma "
                                  << P.diagonal().cwiseSqrt().transpose());
  CHECK(error_xyz < 0.1);
  CHECK(nees < 16.27);  // chi-square(3) 99.9%: the estimate is consistent with its covariance
  // The camera estimate still follows the true camera.
  CHECK((ekf.robotMean().head<3>() - camera.head<3>()).norm() < 0.1);
}

TEST_CASE("Monocular EKF: add and updates and the switch to XYZ equal the dense reference",
          "[measurements][inverse_depth_init][filter]") {
  const InverseDepthInitialization init(kCamera);
  const PinholePoint<InverseDepth> id_model(kCamera);
  const PinholePoint<Point3> point_model(kCamera);
  const Gaussian<6> process =
      Gaussian<6>::sigmas((Vec<6>() << Vec<3>::Constant(0.05), Vec<3>::Constant(0.02)).finished());
  const Gaussian<2> pixel_noise = Gaussian<2>::sigmas(Vec<2>(1.0, 1.5));
  const double dt = 0.1;

  const Vec<13> camera = startCamera();
  MonoEkf ekf(camera, startCovariance());
  Reference ref{ConstantVelocity3D{}, camera, startCovariance()};
  const Vec<3> z1 = init.measurement(Vec<2>(250.0, 180.0));
  const Vec<3> z2 = init.measurement(Vec<2>(500.0, 300.0));
  ekf.add(1, init, z1, init.noise(pixel_noise));
  ref.add(init, z1, init.noise(pixel_noise).covariance());
  ekf.add(2, init, z2, init.noise(1.0));
  ref.add(init, z2, init.noise(1.0).covariance());
  CHECK((ekf.mean() - ref.x).cwiseAbs().maxCoeff() < 1e-14);
  CHECK((ekf.covariance() - ref.P).cwiseAbs().maxCoeff() < 1e-14);

  // A prediction and updates of both landmarks, with pixels a little off the predictions.
  for (int k = 0; k < 3; ++k) {
    ekf.predict(Vec<0>(), dt, process);
    ref.predict(Vec<0>(), dt, process.covariance());
    for (Id id : {Id(1), Id(2)}) {
      const int offset = ekf.slot(id).offset;
      const Vec<2> z =
          id_model(ConstantVelocity3D::pose(ekf.robotMean()), ekf.landmarkMean<InverseDepth>(id)) + Vec<2>(1.5, -2.0);
      ekf.update(id_model, id, z, pixel_noise);
      ref.update(id_model, offset, z, pixel_noise.covariance());
      ref.renormalizeRobot();
    }
  }
  CHECK((ekf.mean() - ref.x).cwiseAbs().maxCoeff() < 1e-10);
  CHECK((ekf.covariance() - ref.P).cwiseAbs().maxCoeff() < 1e-10);

  // Landmark 1 to XYZ (its block moves to the end of the state) and one more update of it.
  const int offset1 = ekf.slot(1).offset;
  ekf.reparametrize(1, InverseDepthToPoint3<ConstantVelocity3D>());
  ref.reparametrize(offset1, InverseDepthToPoint3<ConstantVelocity3D>());
  const int offset1_xyz = ekf.slot(1).offset;
  REQUIRE(offset1_xyz == ref.dim() - 3);
  const Vec<2> z = point_model(ConstantVelocity3D::pose(ekf.robotMean()), ekf.landmarkMean<Point3>(1)) + Vec<2>(-1.0, 0.5);
  ekf.update(point_model, 1, z, pixel_noise);
  ref.update(point_model, offset1_xyz, z, pixel_noise.covariance());
  ref.renormalizeRobot();
  CHECK((ekf.mean() - ref.x).cwiseAbs().maxCoeff() < 1e-10);
  CHECK((ekf.covariance() - ref.P).cwiseAbs().maxCoeff() < 1e-10);
}

}  // namespace unity_measurements_inverse_depth_initialization
