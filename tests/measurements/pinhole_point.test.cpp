// PinholePoint<Point3> and PinholePoint<InverseDepth>: values against a direct projection,
// analytic Jacobians against central differences and automatic differentiation at ordinary
// and awkward geometry (oblique rays, far points, tiny and zero inverse depth, arbitrary
// rotations, unnormalized quaternions), predict<double> against operator(), and the
// rejection of degenerate and non-finite input, and that the analytic evaluation allocates
// nothing (counted with a replaced global operator new and EIGEN_RUNTIME_NO_MALLOC).

#include "eigen_allocation_hook.hpp"
#include "replaced_operator_new.hpp"

#include "sylva_catch.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <new>
#include <string>
#include <type_traits>

#include <Eigen/Geometry>

#include <sylva/diff/auto_diff.hpp>
#include <sylva/landmarks/inverse_depth.hpp>
#include <sylva/landmarks/point3.hpp>
#include <sylva/measurements/pinhole_camera.hpp>
#include <sylva/measurements/pinhole_point.hpp>
#include <sylva/sim/random.hpp>
#include <sylva/testing/check_jacobians.hpp>

#include "autodiff_check.hpp"
#include "camera_pose.hpp"
#include "error_helpers.hpp"

using sylva_test::g_allocations;

using namespace sylva;
using sylva_test::lookAtPose;
using sylva_test::throwsCode;

namespace {

constexpr double kPiD = 3.14159265358979323846;
const PinholeCamera kCamera{500.0, 480.0, 320.0, 240.0, 640, 480};
using PointModel = PinholePoint<Point3>;
using InverseDepthModel = PinholePoint<InverseDepth>;

// A camera at a random position with a uniformly random orientation and a random quaternion
// scale in [0.2, 5].
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

// The world point whose camera-frame coordinates are p_C.
Vec<3> worldPoint(const Vec<7>& x, const Vec<3>& p_C) {
  return x.head<3>() + cameraToWorld(x) * p_C;
}

// The inverse-depth landmark of the world point p with the given anchor.
Vec<6> inverseDepthOf(const Vec<3>& anchor, const Vec<3>& p) {
  const Vec<3> d = p - anchor;
  Vec<6> l;
  l << anchor, std::atan2(d[1], d[0]), std::atan2(d[2], std::hypot(d[0], d[1])), 1.0 / d.norm();
  return l;
}

template <typename Model>
void requireJacobians(const Model& model,
                      const Vec<7>& x,
                      const Vec<Model::Landmark::kDim>& l,
                      double tolerance = 1e-6) {
  const testing::JacobianReport report = testing::checkMeasurementJacobians(model, x, l, tolerance);
  INFO(report.message());
  CHECK(report.ok);
}

// Analytic against forward-mode automatic differentiation of predict<T>, entry by entry
// relative to each entry's own scale (tests/autodiff_check.hpp); and AutoDiff<Model>, which
// the filter uses for a model without analytic Jacobians, gives the same prediction.
template <typename Model>
void requireMatchesAutoDiff(const Model& model, const Vec<7>& x, const Vec<Model::Landmark::kDim>& l) {
  sylva_test::checkMeasurementAgainstAutoDiff(model, x, l);
  const Vec<2> z = model(x, l);
  const Vec<2> z_auto = AutoDiff<Model>(model)(x, l);
  CHECK((z - z_auto).cwiseAbs().maxCoeff() <= 1e-12 * (1.0 + z.cwiseAbs().maxCoeff()));
}

}  // namespace

TEST_CASE("PinholePoint declares its types and dimensions", "[measurements][pinhole_point]") {
  STATIC_REQUIRE(PointModel::kDim == 2);
  STATIC_REQUIRE(InverseDepthModel::kDim == 2);
  STATIC_REQUIRE(std::is_same_v<PointModel::Robot, Pose3D>);
  STATIC_REQUIRE(std::is_same_v<InverseDepthModel::Robot, Pose3D>);
  STATIC_REQUIRE(std::is_same_v<PointModel::Landmark, Point3>);
  STATIC_REQUIRE(std::is_same_v<InverseDepthModel::Landmark, InverseDepth>);
  STATIC_REQUIRE(detail::HasAnalyticJacobians<PointModel>::value);
  STATIC_REQUIRE(detail::HasAnalyticJacobians<InverseDepthModel>::value);
  CHECK(std::string(PointModel::kName) == "PinholePoint<Point3>");
  CHECK(std::string(InverseDepthModel::kName) == "PinholePoint<InverseDepth>");
  CHECK(PointModel(kCamera).camera().fx == kCamera.fx);
  CHECK(InverseDepthModel(kCamera).camera().cy == kCamera.cy);
}

TEST_CASE("PinholePoint validates the camera", "[measurements][pinhole_point][errors]") {
  auto rejects = [](const PinholeCamera& camera, ErrorCode code) {
    return throwsCode([&] { PointModel model(camera); }, code) &&
           throwsCode([&] { InverseDepthModel model(camera); }, code);
  };
  CHECK(rejects({0.0, 1.0, 0.0, 0.0, 10, 10}, ErrorCode::kInvalidArgument));
  CHECK(rejects({1.0, -2.0, 0.0, 0.0, 10, 10}, ErrorCode::kInvalidArgument));
  CHECK(rejects({1.0, 1.0, 0.0, 0.0, 10, 0}, ErrorCode::kInvalidArgument));
  CHECK(rejects({NAN, 1.0, 0.0, 0.0, 10, 10}, ErrorCode::kNonFinite));
  CHECK(rejects({1.0, 1.0, 0.0, INFINITY, 10, 10}, ErrorCode::kNonFinite));
}

TEST_CASE("PinholePoint projects world points and inverse-depth points",
          "[measurements][pinhole_point]") {
  const PointModel point_model(kCamera);
  const InverseDepthModel id_model(kCamera);
  // Camera at (0, 0, 1) looking along world +x: camera x = world -y, camera y = world -z.
  const Vec<7> x = lookAtPose(Vec<3>(0, 0, 1), Vec<3>(10, 0, 1));
  const Vec<3> p(4.0, -1.0, 0.5);  // camera frame (1, 0.5, 4)
  const Vec<2> z = point_model(x, p);
  CHECK(z[0] == Approx(320.0 + 500.0 * 1.0 / 4.0).epsilon(1e-14));
  CHECK(z[1] == Approx(240.0 + 480.0 * 0.5 / 4.0).epsilon(1e-14));
  // The same point as an inverse-depth landmark anchored elsewhere, and at other depths along
  // the same ray from that anchor (rho changes the pixel, the direction alone does not).
  const Vec<3> anchor(-1.0, 2.0, 0.3);
  const Vec<6> l = inverseDepthOf(anchor, p);
  const Vec<2> z_id = id_model(x, l);
  CHECK((z_id - z).norm() < 1e-10);
  // From the anchor itself every depth along the ray projects to the same pixel.
  const Vec<7> x_anchor = lookAtPose(anchor, p);
  Vec<6> l_far = l;
  l_far[5] = 0.0;  // the point at infinity along the ray
  CHECK((id_model(x_anchor, l_far) - Vec<2>(kCamera.cx, kCamera.cy)).norm() < 1e-9);
  CHECK((id_model(x_anchor, l) - Vec<2>(kCamera.cx, kCamera.cy)).norm() < 1e-9);
  // A point outside the image is projected, not rejected (visibility is the caller's call).
  const Vec<3> outside = worldPoint(x, Vec<3>(3.0, -2.0, 1.0));
  const Vec<2> z_out = point_model(x, outside);
  CHECK(z_out[0] == Approx(320.0 + 1500.0));
  CHECK_FALSE(kCamera.contains(z_out[0], z_out[1]));
}

TEST_CASE("PinholePoint: predict<double> equals operator() and AutoDiff works",
          "[measurements][pinhole_point][autodiff]") {
  const PointModel point_model(kCamera);
  const InverseDepthModel id_model(kCamera);
  sim::Rng rng(7101);
  for (int trial = 0; trial < 200; ++trial) {
    const Vec<7> x = randomCamera(rng);
    const Vec<3> p_C(rng.uniform(-3, 3), rng.uniform(-3, 3), rng.uniform(0.5, 20));
    const Vec<3> p = worldPoint(x, p_C);
    const Vec<3> anchor(rng.uniform(-5, 5), rng.uniform(-5, 5), rng.uniform(-2, 2));
    const Vec<6> l = inverseDepthOf(anchor, p);
    Mat<2, 7> J_x;
    Mat<2, 3> J_p;
    Mat<2, 6> J_l;
    // Bit for bit: the two share the arithmetic, and the Jacobians do not change the value.
    CHECK(point_model.predict<double>(x, p) == point_model(x, p));
    CHECK(point_model.predict<double>(x, p) == point_model(x, p, J_x, J_p));
    CHECK(id_model.predict<double>(x, l) == id_model(x, l));
    CHECK(id_model.predict<double>(x, l) == id_model(x, l, J_x, J_l));
    if (trial % 10 == 0) {
      requireMatchesAutoDiff(point_model, x, p);
      requireMatchesAutoDiff(id_model, x, l);
    }
  }
}

TEST_CASE("PinholePoint Jacobians match numerical differentiation at ordinary geometry",
          "[measurements][pinhole_point][jacobian]") {
  const PointModel point_model(kCamera);
  const InverseDepthModel id_model(kCamera);
  sim::Rng rng(7102);
  for (int trial = 0; trial < 300; ++trial) {
    const Vec<7> x = randomCamera(rng);  // arbitrary rotation, quaternion scale 0.2-5
    // Within ~50 degrees of the optical axis, 0.5 to 30 m away.
    const Vec<3> p_C(rng.uniform(-1.2, 1.2), rng.uniform(-1.2, 1.2), 1.0);
    const Vec<3> p = worldPoint(x, p_C * rng.uniform(0.5, 30.0));
    const Vec<3> anchor(rng.uniform(-5, 5), rng.uniform(-5, 5), rng.uniform(-2, 2));
    INFO("trial " << trial);
    requireJacobians(point_model, x, p);
    requireJacobians(id_model, x, inverseDepthOf(anchor, p));
  }
}

TEST_CASE("PinholePoint Jacobians at awkward geometry", "[measurements][pinhole_point][jacobian]") {
  const PointModel point_model(kCamera);
  const InverseDepthModel id_model(kCamera);
  const Vec<7> x = lookAtPose(Vec<3>(1.0, -2.0, 1.5), Vec<3>(5.0, 3.0, 0.5));
  const Vec<3> anchor(-3.0, 1.0, 2.0);

  SECTION("at the image corners") {
    for (const Vec<2>& pixel : {Vec<2>(0.5, 0.5), Vec<2>(639.5, 479.5), Vec<2>(0.5, 479.5)}) {
      const Vec<3> p_C(
          (pixel[0] - kCamera.cx) / kCamera.fx, (pixel[1] - kCamera.cy) / kCamera.fy, 1.0);
      const Vec<3> p = worldPoint(x, 7.0 * p_C);
      CHECK((point_model(x, p) - pixel).norm() < 1e-9);
      requireJacobians(point_model, x, p);
      requireJacobians(id_model, x, inverseDepthOf(anchor, p));
    }
  }
  SECTION("very oblique: 85 and 89 degrees off the optical axis") {
    for (double angle_deg : {85.0, 89.0}) {
      const double a = angle_deg * kPiD / 180.0;
      const Vec<3> p =
          worldPoint(x, 3.0 * Vec<3>(std::sin(a) * 0.6, std::sin(a) * 0.8, std::cos(a)));
      // The pixel is far outside the image and the derivatives are large; the checker's
      // bound is relative to each entry, with the central differences' own error estimated.
      requireJacobians(point_model, x, p);
      requireJacobians(id_model, x, inverseDepthOf(anchor, p));
      requireMatchesAutoDiff(point_model, x, p);
      requireMatchesAutoDiff(id_model, x, inverseDepthOf(anchor, p));
    }
  }
  SECTION("far away: 10 km, and inverse depth 1e-5 1/m") {
    const Vec<3> p = worldPoint(x, Vec<3>(200.0, -300.0, 1e4));
    requireJacobians(point_model, x, p);
    requireJacobians(id_model, x, inverseDepthOf(anchor, p));
    Vec<6> l = inverseDepthOf(anchor, worldPoint(x, Vec<3>(0.1, 0.2, 1.0)));
    l[5] = 1e-5;
    requireJacobians(id_model, x, l);
    requireMatchesAutoDiff(id_model, x, l);
  }
  SECTION("a point at infinity, rho = 0 (central differences would step to rho < 0)") {
    Vec<6> l = inverseDepthOf(anchor, worldPoint(x, Vec<3>(0.3, -0.2, 1.0)));
    l[5] = 0.0;
    requireMatchesAutoDiff(id_model, x, l);
    // One-sided difference in rho instead.
    Mat<2, 6> J_l;
    id_model(x, l, {}, J_l);
    Vec<6> l_plus = l;
    l_plus[5] = 1e-7;
    const Vec<2> slope = (id_model(x, l_plus) - id_model(x, l)) / 1e-7;
    CHECK((slope - J_l.col(5)).norm() < 1e-4 * (1.0 + J_l.col(5).norm()));
  }
  SECTION("the camera at the anchor") {
    const Vec<7> x_anchor = lookAtPose(anchor, Vec<3>(2.0, 0.0, 0.0));
    const Vec<6> l = inverseDepthOf(anchor, Vec<3>(2.5, 0.7, -0.4));
    requireJacobians(id_model, x_anchor, l);
  }
  SECTION("an inverse-depth direction near the zenith, seen by a camera looking up") {
    const Vec<7> x_up = lookAtPose(Vec<3>(0.0, 0.0, 0.0), Vec<3>(0.01, 0.02, 10.0));
    Vec<6> l;
    l << 0.3, -0.2, 0.1, 0.7, kPiD / 2 - 1e-4, 0.2;
    requireJacobians(id_model, x_up, l);
    requireMatchesAutoDiff(id_model, x_up, l);
  }
  SECTION("quaternion far from unit norm") {
    for (double scale : {1e-3, 0.2, 7.0, 1e3}) {
      const Vec<7> xs = lookAtPose(Vec<3>(1.0, -2.0, 1.5), Vec<3>(5.0, 3.0, 0.5), 0.0, scale);
      const Vec<3> p = worldPoint(xs, Vec<3>(0.5, -0.4, 4.0));
      CHECK((point_model(xs, p) - point_model(x, p)).norm() < 1e-9);
      // The checker's step is 1e-6 absolute for |q_i| < 1, a relative step of 1e-3 on a
      // quaternion of norm 1e-3, too coarse there: that case is checked by autodiff only.
      if (scale > 0.01) {
        requireJacobians(point_model, xs, p);
        requireJacobians(id_model, xs, inverseDepthOf(anchor, p));
      }
      requireMatchesAutoDiff(point_model, xs, p);
      requireMatchesAutoDiff(id_model, xs, inverseDepthOf(anchor, p));
      // h does not change along q: J_z_q q = 0.
      Mat<2, 7> J_x;
      point_model(xs, p, J_x);
      CHECK((J_x.middleCols<4>(3) * xs.segment<4>(3)).norm() < 1e-9 * (1.0 + J_x.norm()));
    }
  }
}

TEST_CASE("PinholePoint rejects degenerate geometry and non-finite input",
          "[measurements][pinhole_point][errors]") {
  const PointModel point_model(kCamera);
  const InverseDepthModel id_model(kCamera);
  const Vec<7> x = lookAtPose(Vec<3>(0, 0, 1), Vec<3>(10, 0, 1));
  const Vec<3> anchor(-2.0, 1.0, 1.0);
  const Vec<3> p = worldPoint(x, Vec<3>(0.2, 0.1, 5.0));
  const Vec<6> l = inverseDepthOf(anchor, p);
  const auto degenerate = ErrorCode::kDegenerateGeometry;
  const auto non_finite = ErrorCode::kNonFinite;
  Mat<2, 7> J_x;
  Mat<2, 3> J_p;
  Mat<2, 6> J_l;
  auto both_point = [&](const Vec<7>& xx, const Vec<3>& pp, ErrorCode code) {
    return throwsCode([&] { point_model(xx, pp); }, code) &&
           throwsCode([&] { point_model(xx, pp, J_x, J_p); }, code) &&
           throwsCode([&] { point_model.predict<double>(xx, pp); }, code);
  };
  auto both_id = [&](const Vec<7>& xx, const Vec<6>& ll, ErrorCode code) {
    return throwsCode([&] { id_model(xx, ll); }, code) &&
           throwsCode([&] { id_model(xx, ll, J_x, J_l); }, code) &&
           throwsCode([&] { id_model.predict<double>(xx, ll); }, code);
  };

  // Behind the camera, on the plane through the centre, at the centre.
  CHECK(both_point(x, worldPoint(x, Vec<3>(0.2, 0.1, -5.0)), degenerate));
  CHECK(both_point(x, worldPoint(x, Vec<3>(1.0, 0.0, 0.0)), degenerate));
  CHECK(both_point(x, worldPoint(x, Vec<3>(1.0, 0.0, 1e-8)), degenerate));
  CHECK(both_point(x, x.head<3>(), degenerate));
  CHECK_NOTHROW(point_model(x, worldPoint(x, Vec<3>(1.0, 0.0, 1e-4))));
  // The inverse-depth ray behind the camera: the point behind, and the point at infinity in
  // a direction behind the camera.
  CHECK(both_id(x, inverseDepthOf(anchor, worldPoint(x, Vec<3>(0.2, 0.1, -5.0))), degenerate));
  Vec<6> l_inf = l;
  l_inf[3] += kPiD;  // direction reversed in azimuth: the camera looks along +x
  l_inf[5] = 0.0;
  CHECK(both_id(x, l_inf, degenerate));
  // rho < 0 (an estimate that crossed zero) is predicted like any other, as long as the ray
  // h = R^T (rho (a - t) + m) is in front of the camera; rho = 0 is valid too.
  Vec<6> l_neg = l;
  l_neg[5] = -1e-3;
  CHECK_NOTHROW(id_model(x, l_neg, J_x, J_l));
  CHECK((id_model(x, l_neg) - id_model.predict<double>(x, l_neg)).cwiseAbs().maxCoeff() == 0.0);
  Vec<6> l_zero = l;
  l_zero[5] = 0.0;
  CHECK_NOTHROW(id_model(x, l_zero, J_x, J_l));
  CHECK(J_x.leftCols<3>().isZero(0.0));  // a point at infinity does not move with t
  // A (near) zero quaternion.
  Vec<7> x_zero = x;
  x_zero.segment<4>(3).setZero();
  CHECK(both_point(x_zero, p, degenerate));
  CHECK(both_id(x_zero, l, degenerate));
  x_zero.segment<4>(3) = Vec<4>(1e-13, 0.0, 0.0, 0.0);
  CHECK(both_point(x_zero, p, degenerate));
  x_zero.segment<4>(3) = Vec<4>(1e200, 1e200, 0.0, 0.0);  // finite, but its norm overflows
  CHECK(both_point(x_zero, p, non_finite));
  CHECK(both_id(x_zero, l, non_finite));
  // NaN and Inf.
  for (double bad : {NAN, INFINITY, -INFINITY}) {
    for (int i : {0, 4, 6}) {
      Vec<7> xb = x;
      xb[i] = bad;
      CHECK(both_point(xb, p, non_finite));
      CHECK(both_id(xb, l, non_finite));
    }
    for (int i = 0; i < 6; ++i) {
      Vec<6> lb = l;
      lb[i] = bad;
      CHECK(both_id(x, lb, non_finite));
      if (i < 3) {
        Vec<3> pb = p;
        pb[i] = bad;
        CHECK(both_point(x, pb, non_finite));
      }
    }
  }
  // Huge but finite coordinates are fine; a camera-frame point that overflows is not.
  CHECK_NOTHROW(point_model(x, worldPoint(x, Vec<3>(1e300, 1e300, 1e300))));
  Vec<7> x_far = x;
  x_far[0] = -1e308;
  CHECK(both_point(x_far, Vec<3>(1e308, 0.0, 0.0), non_finite));
}

TEST_CASE("PinholePoint evaluates with Jacobians without allocating",
          "[measurements][pinhole_point][allocation]") {
  const PointModel point_model(kCamera);
  const InverseDepthModel id_model(kCamera);
  const Vec<7> x = lookAtPose(Vec<3>(1.0, -2.0, 1.5), Vec<3>(5.0, 3.0, 0.5), 0.0, 1.3);
  const Vec<3> p = worldPoint(x, Vec<3>(0.5, -0.4, 4.0));
  const Vec<6> l = inverseDepthOf(Vec<3>(-3.0, 1.0, 2.0), p);
  Mat<2, 7> J_x;
  Mat<2, 3> J_p;
  Mat<2, 6> J_l;
  Eigen::Matrix<double, 2, Eigen::Dynamic> H =
      Eigen::Matrix<double, 2, Eigen::Dynamic>::Zero(2, 40);
  Vec<2> sum = Vec<2>::Zero();
  const long before = g_allocations.load();
  Eigen::internal::set_is_malloc_allowed(false);
  for (int k = 0; k < 100; ++k) {
    sum += point_model(x, p, J_x, J_p);
    sum += id_model(x, l, J_x, J_l);
    // Into blocks of a larger matrix, as the filter passes them.
    sum += id_model(x, l, H.leftCols<7>(), H.middleCols<6>(20));
    sum += point_model.predict<double>(x, p) + id_model.predict<double>(x, l);
  }
  Eigen::internal::set_is_malloc_allowed(true);
  CHECK(g_allocations.load() - before == 0);
  // The counter does see allocations.
  const long after = g_allocations.load();
  const std::string probe(100, 'x');
  CHECK(g_allocations.load() > after);
  CHECK(probe.size() == 100);
  CHECK(sum.allFinite());
  CHECK(H.middleCols<6>(20) == J_l);
}
