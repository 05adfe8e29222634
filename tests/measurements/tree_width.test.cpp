// TreeWidth, TreeXYZR and PinholeCamera: the model against a brute-force projection of the
// base circle over many random configurations, its analytic Jacobians against central
// differences and automatic differentiation at ordinary and awkward geometry, degenerate
// and invalid input.

#include "autodiff_check.hpp"
#include "camera_pose.hpp"
#include "sylva_catch.hpp"
#include "tree_width_geometries.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include <sylva/diff/auto_diff.hpp>
#include <sylva/filter/ekf.hpp>
#include <sylva/measurements/inverse_depth_tree_width.hpp>
#include <sylva/landmarks/tree_xyzr.hpp>
#include <sylva/measurements/pinhole_camera.hpp>
#include <sylva/measurements/tree_width.hpp>
#include <sylva/motion/constant_velocity_3d.hpp>
#include <sylva/sim/random.hpp>
#include <sylva/testing/check_jacobians.hpp>

#include "copy_init.hpp"
#include "error_helpers.hpp"
#include "filter_snapshot.hpp"

// Own namespace: the tests of a folder are compiled as one unity translation unit.
namespace unity_measurements_tree_width {

using namespace sylva;
using sylva_test::lookAt;
using sylva_test::lookAtPose;

namespace {

constexpr double kPiD = 3.14159265358979323846;
const PinholeCamera kCamera{500.0, 480.0, 320.0, 240.0, 640, 480};

Vec<4> treeAt(double x, double y, double z, double r) { return Vec<4>(x, y, z, r); }

// Brute-force image of the base circle: the point at angle theta, c + r (cos, sin, 0) in the
// world, in the camera frame (= centre + cos(theta) a + sin(theta) b with a = r R^T e1,
// b = r R^T e2), projected with the pinhole model.
struct CircleImage {
  Vec<3> centre, a, b;

  CircleImage(const Vec<7>& camera, const Vec<3>& c, double r) {
    const Mat<3, 3> Rt = rotationMatrix<double>(Vec<4>(camera.segment<4>(3))).transpose();
    centre = Rt * (c - camera.head<3>());
    a = r * Rt.col(0);
    b = r * Rt.col(1);
  }
  Vec<3> cameraPoint(double theta) const {
    return centre + std::cos(theta) * a + std::sin(theta) * b;
  }
  Vec<2> pixel(double theta) const { return kCamera.project<double>(cameraPoint(theta)); }
};

// Maximum of f near the sample theta0 of a grid with spacing h, by golden-section search on
// [theta0 - h, theta0 + h]. The grid maximum lies within one spacing of the true maximum of a
// smooth unimodal peak, so the bracket contains it; 60 golden steps shrink it by 0.618^60 ~
// 3e-13, far below the sqrt(eps) ~ 1e-8 rad at which a quadratic peak becomes flat in double,
// so the refined value is the true maximum to round-off (~1e-15 relative).
template <typename F>
double refineMax(F&& f, double theta0, double h) {
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  double a = theta0 - h;
  double b = theta0 + h;
  double x1 = b - g * (b - a);
  double x2 = a + g * (b - a);
  double f1 = f(x1);
  double f2 = f(x2);
  for (int i = 0; i < 60; ++i) {
    if (f1 < f2) {
      a = x1;
      x1 = x2;
      f1 = f2;
      x2 = a + g * (b - a);
      f2 = f(x2);
    } else {
      b = x2;
      x2 = x1;
      f2 = f1;
      x1 = b - g * (b - a);
      f1 = f(x1);
    }
  }
  return std::max({f1, f2, f(theta0)});
}

struct BruteForce {
  double u_min, u_max, v_min, v_max, min_depth;
};

// 3,600 points of the base circle, then each extreme refined around its best sample. The bare
// samples would only give max u - min u to ~ (2 pi / 3600)^2 / 8 ~ 4e-7 of the extent near a
// peak (worse on a thin ellipse), too coarse for a 1e-6 comparison to mean anything.
BruteForce bruteForce(const CircleImage& image) {
  constexpr int kSamples = 3600;
  const double h = 2.0 * kPiD / kSamples;
  int iu_min = 0, iu_max = 0, iv_min = 0, iv_max = 0;
  BruteForce b{INFINITY, -INFINITY, INFINITY, -INFINITY, INFINITY};
  for (int k = 0; k < kSamples; ++k) {
    const Vec<3> p = image.cameraPoint(k * h);
    b.min_depth = std::min(b.min_depth, p[2]);
    const Vec<2> px = kCamera.project<double>(p);
    if (px[0] < b.u_min) b.u_min = px[0], iu_min = k;
    if (px[0] > b.u_max) b.u_max = px[0], iu_max = k;
    if (px[1] < b.v_min) b.v_min = px[1], iv_min = k;
    if (px[1] > b.v_max) b.v_max = px[1], iv_max = k;
  }
  if (!(b.min_depth > 0.0)) return b;
  b.u_max = refineMax([&](double th) { return image.pixel(th)[0]; }, iu_max * h, h);
  b.u_min = -refineMax([&](double th) { return -image.pixel(th)[0]; }, iu_min * h, h);
  b.v_max = refineMax([&](double th) { return image.pixel(th)[1]; }, iv_max * h, h);
  b.v_min = -refineMax([&](double th) { return -image.pixel(th)[1]; }, iv_min * h, h);
  return b;
}

}  // namespace

TEST_CASE("PinholeCamera validates its intrinsics and projects", "[measurements][pinhole]") {
  CHECK_NOTHROW(kCamera.validate());
  const Vec<2> px = kCamera.project<double>(Vec<3>(1.0, -0.5, 2.0));
  CHECK(px[0] == Approx(320.0 + 500.0 * 0.5));
  CHECK(px[1] == Approx(240.0 - 480.0 * 0.25));
  CHECK(kCamera.contains(0.0, 0.0));
  CHECK(kCamera.contains(640.0, 480.0));
  CHECK_FALSE(kCamera.contains(-0.1, 10.0));
  CHECK_FALSE(kCamera.contains(10.0, 480.1));
  CHECK(kCamera.matrix()(0, 2) == 320.0);
  using sylva_test::throwsCode;
  auto rejects = [](const PinholeCamera& camera, ErrorCode code) {
    return throwsCode([&] { camera.validate(); }, code) &&
           throwsCode([&] { TreeWidth model(camera); }, code);
  };
  CHECK(rejects({0.0, 1.0, 0.0, 0.0, 10, 10}, ErrorCode::kInvalidArgument));
  CHECK(rejects({1.0, -1.0, 0.0, 0.0, 10, 10}, ErrorCode::kInvalidArgument));
  CHECK(rejects({1.0, 1.0, 0.0, 0.0, 0, 10}, ErrorCode::kInvalidArgument));
  CHECK(rejects({1.0, 1.0, 0.0, 0.0, 10, -3}, ErrorCode::kInvalidArgument));
  CHECK(rejects({NAN, 1.0, 0.0, 0.0, 10, 10}, ErrorCode::kNonFinite));
  CHECK(rejects({1.0, 1.0, INFINITY, 0.0, 10, 10}, ErrorCode::kNonFinite));
}

TEST_CASE("TreeXYZR and TreeWidth declare their dimensions", "[measurements][tree_width]") {
  STATIC_REQUIRE(TreeXYZR::kDim == 4);
  STATIC_REQUIRE(TreeWidth::kDim == 3);
  STATIC_REQUIRE(TreeWidth::Robot::kDim == 7);
  STATIC_REQUIRE(TreeWidth::Landmark::kDim == 4);
  CHECK(std::string(TreeXYZR::kName) == "TreeXYZR");
  CHECK(std::string(TreeWidth::kName) == "TreeWidth");
}

TEST_CASE("TreeWidth: a tree straight ahead at eye level gives the closed-form width",
          "[measurements][tree_width]") {
  // Camera at the height of the base plane looking along +x at the trunk: the circle is seen
  // edge-on, its image a horizontal segment through the principal point whose ends are the
  // tangent rays, at angles +-asin(r / d): w = 2 fx tan(asin(r / d)).
  const TreeWidth model(kCamera);
  const double d = 5.0;
  const double r = 0.4;
  const Vec<3> z = model(lookAtPose(Vec<3>(0.0, 0.0, 1.0), Vec<3>(d, 0.0, 1.0)), treeAt(d, 0, 1, r));
  CHECK(z[0] == Approx(kCamera.cx).margin(1e-9));
  CHECK(z[1] == Approx(kCamera.cy).margin(1e-9));
  CHECK(z[2] == Approx(2.0 * kCamera.fx * std::tan(std::asin(r / d))).epsilon(1e-12));
}

TEST_CASE("TreeWidth matches a brute-force projection of the base circle",
          "[measurements][tree_width][slow]") {
  const TreeWidth model(kCamera);
  sim::Rng rng(20260301);
  int accepted = 0;
  int accepted_near_plane = 0;
  int discarded = 0;
  int failures = 0;
  double worst[2] = {0.0, 0.0};  // worst relative error: [ordinary, within 1 cm of the plane]
  for (int trial = 0; trial < 10600; ++trial) {
    const double r = std::exp(rng.uniform(std::log(0.02), std::log(1.5)));
    const Vec<3> c(rng.uniform(-20.0, 20.0), rng.uniform(-20.0, 20.0), rng.uniform(-2.0, 2.0));
    const bool near_plane = trial % 5 == 0;
    const double height = near_plane ? rng.uniform(-0.01, 0.01) : rng.uniform(-4.0, 4.0);
    const double distance = r + std::exp(rng.uniform(std::log(0.3), std::log(25.0)));
    const double azimuth = rng.uniform(-kPiD, kPiD);
    const Vec<3> t = c + Vec<3>(distance * std::cos(azimuth), distance * std::sin(azimuth), height);
    // Aim somewhere at the trunk, off by up to ~0.4 rad, with any roll about the optical axis
    // (mostly small, a quarter of the time anywhere in (-pi, pi)).
    const Vec<3> aim =
        c + Vec<3>(rng.uniform(-1.0, 1.0) * r, rng.uniform(-1.0, 1.0) * r, rng.uniform(-1.5, 1.5));
    const Vec<3> off =
        0.4 * (aim - t).norm() *
        Vec<3>(rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0));
    const double roll = trial % 4 == 0 ? rng.uniform(-kPiD, kPiD) : rng.uniform(-0.3, 0.3);
    const Vec<7> x = lookAtPose(t, aim + off, roll);

    const BruteForce b = bruteForce(CircleImage(x, c, r));
    // Keep configurations with the whole circle at least 5 cm in front of the camera; nearer
    // the image plane the ellipse grows without bound and neither side is well conditioned.
    if (!(b.min_depth > 0.05)) {
      ++discarded;
      continue;
    }
    ++accepted;
    if (near_plane) ++accepted_near_plane;
    const Vec<3> z = model(x, Vec<4>(c.x(), c.y(), c.z(), r));
    const double w_b = b.u_max - b.u_min;
    const double u_b = 0.5 * (b.u_min + b.u_max);
    const double v_b = 0.5 * (b.v_min + b.v_max);
    // Relative errors: the width against itself, the centre against the larger of its own
    // magnitude and the width (a centre near pixel 0 has no meaningful relative error of its
    // own).
    const double e_w = std::abs(z[2] - w_b) / w_b;
    const double e_u = std::abs(z[0] - u_b) / std::max({std::abs(u_b), w_b, 1.0});
    const double e_v = std::abs(z[1] - v_b) / std::max({std::abs(v_b), w_b, 1.0});
    const double e = std::max({e_w, e_u, e_v});
    // Widths below a pixel (an edge-on circle with the horizon nearly vertical) lose digits in
    // the model's sqrt(d13^2 - d11 d33): the discriminant cancels, so the absolute error of w is
    // ~ eps u^2 / w (1e-9 px at w = 1e-3 px), relative ~1e-6. Irrelevant in pixels, so the
    // worst-case statistics below leave them out; the tolerance check above does not.
    if (w_b >= 1.0) worst[near_plane ? 1 : 0] = std::max(worst[near_plane ? 1 : 0], e);
    const double tolerance = std::abs(height) <= 0.01 ? 1e-4 : 1e-6;
    if (!(e <= tolerance)) {
      ++failures;
      if (failures <= 5) {
        INFO("trial " << trial << ": model " << z.transpose() << " brute force " << u_b << " "
                      << v_b << " " << w_b << " (r " << r << ", distance " << distance
                      << ", height " << height << ", errors " << e_u << " " << e_v << " " << e_w
                      << ")");
        CHECK(e <= tolerance);
      }
    }
  }
  INFO("accepted " << accepted << " (" << accepted_near_plane << " within 1 cm of the plane), "
                   << "discarded " << discarded << "; worst relative error (w >= 1 px) " << worst[0]
                   << " ordinary, " << worst[1] << " near the plane");
  CHECK(failures == 0);
  CHECK(accepted >= 10000);
  CHECK(accepted_near_plane >= 1500);
  // Not only within tolerance: for widths of a pixel or more the near-plane cases are as
  // accurate as the others (the dual-conic formulas do not degrade there).
  CHECK(worst[0] <= 1e-8);
  CHECK(worst[1] <= 1e-8);
}


TEST_CASE("TreeWidth Jacobians match numerical differentiation", "[measurements][jacobian]") {
  const TreeWidth model(kCamera);
  for (const sylva_test::TreeWidthGeometry& g : sylva_test::treeWidthGeometries()) {
    INFO(g.name);
    const auto report = testing::checkMeasurementJacobians(model, g.camera, g.tree);
    INFO(report.message());
    CHECK(report.ok);
    Mat<3, 7> J_z_x;
    Mat<3, 4> J_z_l;
    const Vec<3> z = model(g.camera, g.tree, J_z_x, J_z_l);
    CHECK(z == model.predict<double>(g.camera, g.tree));
    // The model normalizes the quaternion, so scaling q changes nothing: J q = 0.
    CHECK((J_z_x.middleCols<4>(3) * g.camera.segment<4>(3)).norm() <=
          1e-9 * J_z_x.middleCols<4>(3).norm() * g.camera.segment<4>(3).norm());
  }
}

TEST_CASE("TreeWidth analytic Jacobians equal automatic differentiation",
          "[measurements][jacobian]") {
  const TreeWidth model(kCamera);
  for (const sylva_test::TreeWidthGeometry& g : sylva_test::treeWidthGeometries()) {
    INFO(g.name);
    // Entry by entry, relative to each entry's own scale, and the values (tests/autodiff_check.hpp).
    sylva_test::checkMeasurementAgainstAutoDiff(model, g.camera, g.tree);
  }
}

TEST_CASE("TreeWidth rejects degenerate geometry and bad input with a reason",
          "[measurements][tree_width][errors]") {
  const TreeWidth model(kCamera);
  const Vec<7> camera = lookAtPose(Vec<3>(0.0, 0.0, 1.5), Vec<3>(5.0, 0.0, 0.5));
  const Vec<4> tree = treeAt(5.0, 0.0, 0.0, 0.3);
  REQUIRE_NOTHROW(model(camera, tree));

  auto reason = [&](const Vec<7>& x, const Vec<4>& l) -> std::pair<ErrorCode, std::string> {
    try {
      model(x, l);
    } catch (const Error& e) {
      return {e.code(), e.what()};
    }
    return {ErrorCode::kMalformedData, "no throw"};
  };
  auto expectDegenerate = [&](const Vec<7>& x, const Vec<4>& l, const std::string& words) {
    const auto [code, what] = reason(x, l);
    INFO(what);
    CHECK(code == ErrorCode::kDegenerateGeometry);
    CHECK(what.find(words) != std::string::npos);
    // predict<double> (what AutoDiff and NumericDiff use) rejects it the same way.
    CHECK(sylva_test::throwsCode([&] { model.predict<double>(x, l); },
                                 ErrorCode::kDegenerateGeometry));
  };

  SECTION("trunk base behind the camera") {
    expectDegenerate(camera, treeAt(-5.0, 0.0, 0.0, 0.3), "in front of the camera");
  }
  SECTION("trunk base crossing the image plane") {
    // Looking along +x from x = 0; the circle around x = 0.1 reaches x = -0.2.
    const Vec<7> level = lookAtPose(Vec<3>(0.0, -1.0, 1.5), Vec<3>(1.0, -1.0, 1.5));
    expectDegenerate(level, treeAt(0.1, 0.0, 0.0, 0.3), "in front of the camera");
  }
  SECTION("camera inside the trunk") {
    const Vec<7> inside = lookAtPose(Vec<3>(5.1, 0.0, 3.0), Vec<3>(5.1, 0.01, 0.0));
    expectDegenerate(inside, tree, "inside the trunk");
  }
  SECTION("camera on the trunk surface") {
    const Vec<7> on = lookAtPose(Vec<3>(5.0 - 0.3, 0.0, 3.0), Vec<3>(5.0, 0.0, 0.0));
    expectDegenerate(on, tree, "inside the trunk");
  }
  SECTION("radius zero or negative") {
    expectDegenerate(camera, treeAt(5.0, 0.0, 0.0, 0.0), "radius");
    expectDegenerate(camera, treeAt(5.0, 0.0, 0.0, -0.2), "radius");
  }
  SECTION("zero quaternion") {
    Vec<7> x = camera;
    x.segment<4>(3).setZero();
    expectDegenerate(x, tree, "quaternion");
  }
  SECTION("non-finite input") {
    for (int i = 0; i < 7; ++i) {
      Vec<7> x = camera;
      x[i] = std::numeric_limits<double>::quiet_NaN();
      INFO("camera entry " << i);
      CHECK(sylva_test::throwsCode([&] { model(x, tree); }, ErrorCode::kNonFinite));
    }
    for (int i = 0; i < 4; ++i) {
      Vec<4> l = tree;
      l[i] = std::numeric_limits<double>::infinity();
      INFO("tree entry " << i);
      CHECK(sylva_test::throwsCode([&] { model(camera, l); }, ErrorCode::kNonFinite));
    }
  }
  SECTION("AutoDiff rejects the same input") {
    const AutoDiff<TreeWidth> automatic(model);
    Mat<3, 7> J_z_x;
    CHECK(sylva_test::throwsCode([&] { automatic(camera, treeAt(-5.0, 0.0, 0.0, 0.3), J_z_x); },
                                 ErrorCode::kDegenerateGeometry));
  }
}

}  // namespace unity_measurements_tree_width

TEST_CASE("the filter refuses a measured width that is not positive, as InverseTreeWidth does",
          "[measurements][tree_width][errors]") {
  using namespace unity_measurements_tree_width;
  const TreeWidth model(kCamera);
  const Vec<13> camera = lookAt(Vec<3>(0.0, 0.0, 1.5), Vec<3>(5.0, 0.0, 0.5));
  Ekf<ConstantVelocity3D, TreeXYZR, InverseDepthRadius> ekf(camera, Mat<13, 13>::Identity() * 1e-6);
  ekf.add(1, sylva_test::CopyInit<ConstantVelocity3D, TreeXYZR>{}, treeAt(5.0, 0.0, 0.0, 0.3),
          Gaussian<4>::sigmas(Vec<4>::Constant(0.1)));
  const Gaussian<3> noise = Gaussian<3>::sigmas(Vec<3>::Constant(1.0));
  const Vec<3> z = model(ConstantVelocity3D::pose(camera), treeAt(5.0, 0.0, 0.0, 0.3));
  for (const double width : {0.0, -3.0}) {
    const Vec<3> bad(z[0], z[1], width);
    sylva_test::requireRejected(ekf, ErrorCode::kDegenerateGeometry, "the measured width must be > 0",
                                [&] { ekf.update(model, 1, bad, noise); });
    sylva_test::requireRejected(ekf, ErrorCode::kDegenerateGeometry, "the measured width must be > 0",
                                [&] { (void)ekf.innovation(model, 1, bad, noise); });
    const std::vector<Observation<TreeWidth>> batch{{1, z, noise}, {1, bad, noise}};
    sylva_test::requireRejected(ekf, ErrorCode::kDegenerateGeometry, "measurement 1",
                                [&] { ekf.update(model, batch); });
    sylva_test::requireRejected(ekf, ErrorCode::kDegenerateGeometry, "the measured width must be > 0",
                                [&] { ekf.update(model, batch, Fusion::kSequential); });
  }
  // The inverse-depth width model measures the same width.
  CHECK(InverseDepthTreeWidth::measurementViolation(Vec<3>(300.0, 200.0, -1.0)) != nullptr);
  CHECK(InverseDepthTreeWidth::measurementViolation(Vec<3>(300.0, 200.0, 4.0)) == nullptr);
  REQUIRE_NOTHROW(ekf.update(model, 1, z, noise));
}
