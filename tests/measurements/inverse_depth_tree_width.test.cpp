// InverseDepthTreeWidth and InverseDepthRadiusInitialization: the IDR model equals TreeWidth
// of the equivalent XYZ-R tree over thousands of random configurations (anchors at, near
// and far from the camera; near and far trees); its analytic Jacobians against central
// differences and automatic differentiation at ordinary and awkward geometry (a tree 500 m
// away, at infinity, beyond infinity, looked at steeply from above, azimuth at the seam);
// rejected input; the initialization (width reproduced exactly, centre approximately, kappa
// independent of the prior depth, Jacobians, bad input); and the filter: add, updates and
// the switch to XYZ-R against the dense reference EKF, and a tree estimated from a moving
// camera.

#include "autodiff_check.hpp"
#include "camera_pose.hpp"
#include "tree_width_geometries.hpp"
#include "sylva_catch.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include <sylva/diff/auto_diff.hpp>
#include <sylva/filter/ekf.hpp>
#include <sylva/landmarks/inverse_depth.hpp>
#include <sylva/landmarks/inverse_depth_radius.hpp>
#include <sylva/landmarks/tree_xyzr.hpp>
#include <sylva/measurements/inverse_depth_initialization.hpp>
#include <sylva/measurements/inverse_depth_tree_width.hpp>
#include <sylva/measurements/tree_width.hpp>
#include <sylva/motion/constant_velocity_3d.hpp>
#include <sylva/sim/random.hpp>
#include <sylva/testing/check_jacobians.hpp>
#include <sylva/testing/dense_reference_ekf.hpp>

#include "error_helpers.hpp"

// Own namespace: the tests of a folder are compiled as one unity translation unit.
namespace unity_measurements_inverse_depth_tree_width {

using namespace sylva;
using sylva_test::lookAt;
using sylva_test::lookAtPose;
using sylva::sim::Rng;
using sylva_test::throwsCode;
using ToTree = InverseDepthRadiusToTree<Pose3D>;

namespace {

constexpr double kPiD = 3.14159265358979323846;
const PinholeCamera kCamera{500.0, 480.0, 320.0, 240.0, 640, 480};
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The IDR landmark, anchored at `anchor`, of the XYZ-R tree `tree`.
Vec<7> idrOf(const Vec<4>& tree, const Vec<3>& anchor) {
  const Vec<3> d = tree.head<3>() - anchor;
  const double depth = d.norm();
  Vec<7> l;
  l << anchor, std::atan2(d[1], d[0]), std::atan2(d[2], std::hypot(d[0], d[1])), 1.0 / depth,
      tree[3] / depth;
  return l;
}

// Relative error of two [u, v, w]: the width against itself, the centre against the larger
// of its own magnitude and the width (a centre near pixel 0 has no relative error of its own).
double relativeError(const Vec<3>& a, const Vec<3>& b) {
  const double w = std::abs(b[2]);
  return std::max({std::abs(a[0] - b[0]) / std::max({std::abs(b[0]), w, 1.0}),
                   std::abs(a[1] - b[1]) / std::max({std::abs(b[1]), w, 1.0}),
                   std::abs(a[2] - b[2]) / w});
}

struct Config {
  Vec<7> camera;
  Vec<4> tree;
  Vec<3> z;  // TreeWidth of the tree
};

// A random camera/tree pair valid for TreeWidth: the tree `range` metres away horizontally,
// the camera `height` above its base plane, aimed near the tree (anywhere in the image),
// rolled, with a quaternion of norm 0.5-2.
bool randomConfig(Rng& rng, double range, double height, Config& out) {
  const Vec<4> tree(rng.uniform(-5.0, 5.0),
                    rng.uniform(-5.0, 5.0),
                    rng.uniform(-1.0, 1.0),
                    rng.uniform(0.05, 0.8));
  const double bearing = rng.uniform(-kPiD, kPiD);
  const Vec<3> position =
      tree.head<3>() + Vec<3>(range * std::cos(bearing), range * std::sin(bearing), height);
  const double spread = 0.1 * range;  // keeps the tree in the image, near or far
  const Vec<3> target = tree.head<3>() + Vec<3>(rng.uniform(-spread, spread),
                                                rng.uniform(-spread, spread),
                                                rng.uniform(-0.5 * spread, 0.5 * spread));
  const Vec<7> camera = lookAtPose(position, target, rng.uniform(-0.5, 0.5), rng.uniform(0.5, 2.0));
  try {
    out = Config{camera, tree, TreeWidth(kCamera)(camera, tree)};
  } catch (const Error&) {
    return false;
  }
  return true;
}

}  // namespace

TEST_CASE("InverseDepthTreeWidth declares its types and dimensions", "[measurements][idr]") {
  STATIC_REQUIRE(InverseDepthTreeWidth::kDim == 3);
  STATIC_REQUIRE(std::is_same_v<InverseDepthTreeWidth::Robot, Pose3D>);
  STATIC_REQUIRE(std::is_same_v<InverseDepthTreeWidth::Landmark, InverseDepthRadius>);
  STATIC_REQUIRE(detail::HasAnalyticJacobians<InverseDepthTreeWidth>::value);
  CHECK(std::string(InverseDepthTreeWidth::kName) == "InverseDepthTreeWidth");
  const InverseDepthTreeWidth model(kCamera);
  CHECK(model.camera().fx == kCamera.fx);
  CHECK(throwsCode(
      [] {
        InverseDepthTreeWidth bad(PinholeCamera{0.0, 1.0, 0.0, 0.0, 10, 10});
      },
      ErrorCode::kInvalidArgument));
}

TEST_CASE("InverseDepthTreeWidth equals TreeWidth of the equivalent XYZ-R tree",
          "[measurements][idr]") {
  const InverseDepthTreeWidth model(kCamera);
  const TreeWidth xyzr(kCamera);
  Rng rng(20260417);
  struct Band {
    const char* name;
    double range_lo, range_hi;
  };
  for (const Band& band :
       {Band{"trees 1-25 m away", 1.0, 25.0}, Band{"trees 50-400 m away", 50.0, 400.0}}) {
    int tested = 0;
    int anchors_far = 0;
    double worst = 0.0;
    for (int trial = 0; trial < 6000 && tested < 1200; ++trial) {
      // Heights well off the base plane: within ~1 cm of it both models lose digits to the
      // same cancellation (tree_width.test.cpp), which is not what is compared here.
      const double height = (rng.uniform01() < 0.5 ? -1.0 : 1.0) * rng.uniform(0.2, 3.0);
      Config c;
      if (!randomConfig(rng, rng.uniform(band.range_lo, band.range_hi), height, c)) continue;
      // Anchor: at the camera (a tree just initialized), near it (a few metres of travel
      // since), or far from it (hundreds of metres of travel since).
      Vec<3> anchor = c.camera.head<3>();
      const int kind = trial % 3;
      if (kind == 1) anchor += Vec<3>(rng.uniform(-5, 5), rng.uniform(-5, 5), rng.uniform(-1, 1));
      if (kind == 2) {
        const double distance = std::exp(rng.uniform(std::log(100.0), std::log(1000.0)));
        const double azimuth = rng.uniform(-kPiD, kPiD);
        anchor += Vec<3>(
            distance * std::cos(azimuth), distance * std::sin(azimuth), rng.uniform(-10, 10));
        ++anchors_far;
      }
      const Vec<7> l = idrOf(c.tree, anchor);
      // The conversion recovers the tree (the comparison below is of the two models).
      const Vec<4> tree = ToTree{}(c.camera, l);
      const Vec<3> z_xyzr = xyzr(c.camera, tree);
      Vec<3> z_idr;
      try {
        z_idr = model(c.camera, l);
      } catch (const Error& e) {
        FAIL("a valid configuration was rejected: " << e.what());
      }
      const double e = relativeError(z_idr, z_xyzr);
      worst = std::max(worst, e);
      if (!(e <= 1e-9)) {
        INFO(band.name << ", trial " << trial << ": IDR " << z_idr.transpose() << " XYZ-R "
                       << z_xyzr.transpose() << " (anchor kind " << kind
                       << ", l = " << l.transpose() << ")");
        CHECK(e <= 1e-9);
      }
      ++tested;
    }
    INFO(band.name << ": " << tested << " configurations (" << anchors_far
                   << " with the anchor 100-1000 m away), worst relative error " << worst);
    CHECK(tested == 1200);
    CHECK(anchors_far >= 300);
    CHECK(worst <= 1e-9);
  }
}

namespace {

struct Geometry {
  const char* name;
  Vec<7> camera;
  Vec<7> l;
  double tolerance = 1e-6;
};

Vec<7> idr(const Vec<3>& anchor, double theta, double phi, double rho, double kappa) {
  Vec<7> l;
  l << anchor, theta, phi, rho, kappa;
  return l;
}

std::vector<Geometry> jacobianGeometries() {
  const Vec<3> eye(1.0, -2.0, 1.6);
  const Vec<4> tree(6.0, 1.0, 0.2, 0.3);
  // A tree 500 m away (rho = 0.002) seen from 3 m beside its anchor.
  const Vec<3> far_anchor(0.0, 0.0, 1.5);
  const Vec<7> far = idr(far_anchor, 0.3, -0.002, 0.002, 0.6 * 0.002);
  const Vec<3> far_point = InverseDepth::point<double>(Vec<6>(far.head<6>()));
  // At infinity (rho = 0): only the direction and the angular size kappa remain.
  const Vec<7> infinity = idr(Vec<3>(0.0, 0.0, 1.5), -0.4, -0.01, 0.0, 0.01);
  const Vec<3> infinity_dir = InverseDepth::direction<double>(infinity[3], infinity[4]);
  // Azimuth at the seam: the tree is in the -x direction from its anchor.
  const Vec<7> seam_below = idr(Vec<3>(10.0, 0.0, 1.5), kPiD - 1e-7, -0.2, 1.0 / 6.0, 0.3 / 6.0);
  const Vec<7> seam_above = idr(Vec<3>(10.0, 0.0, 1.5), -kPiD + 1e-7, -0.2, 1.0 / 6.0, 0.3 / 6.0);
  const Vec<3> seam_point = ToTree{}(Vec<7>::Zero(), seam_below).head<3>();
  return {
      {"ordinary, anchor at an earlier camera position",
       lookAtPose(eye, Vec<3>(6.0, 1.0, 0.5)),
       idrOf(tree, Vec<3>(0.0, -3.0, 1.5))},
      {"anchor at the camera (just initialized)",
       lookAtPose(eye, Vec<3>(6.0, 1.0, 0.5)),
       idrOf(tree, eye)},
      {"camera 30 m from the anchor",
       lookAtPose(eye, Vec<3>(6.0, 1.0, 0.5)),
       idrOf(tree, Vec<3>(-20.0, -20.0, 1.0))},
      {"tree 500 m away, rho = 0.002", lookAtPose(far_anchor + Vec<3>(0.0, 3.0, 0.2), far_point), far},
      {"tree at infinity, rho = 0",
       lookAtPose(Vec<3>(5.0, -1.0, 1.7), Vec<3>(5.0, -1.0, 1.7) + infinity_dir),
       infinity},
      {"beyond infinity, rho = -0.01",
       lookAtPose(Vec<3>(5.0, -1.0, 1.7), Vec<3>(5.0, -1.0, 1.7) + infinity_dir),
       idr(Vec<3>(0.0, 0.0, 1.5), -0.4, -0.01, -0.01, 0.01)},
      {"looking steeply down on the tree",
       lookAtPose(Vec<3>(2.0, 0.0, 5.0), Vec<3>(2.0, 1e-3, 0.0)),
       idrOf(Vec<4>(2.0, 1.0, 0.0, 0.4), Vec<3>(1.0, -0.5, 5.2))},
      {"looking straight down, anchor above the tree",
       lookAtPose(Vec<3>(2.5, 1.5, 6.0), Vec<3>(2.5, 1.5, 0.0)),
       idrOf(Vec<4>(2.0, 1.0, 0.0, 0.4), Vec<3>(2.0, 1.5, 5.0))},
      {"azimuth just below pi", lookAtPose(Vec<3>(12.0, 1.0, 1.6), seam_point), seam_below},
      {"azimuth just above -pi", lookAtPose(Vec<3>(12.0, 1.0, 1.6), seam_point), seam_above},
      {"camera rolled 90 deg",
       lookAtPose(eye, Vec<3>(6.0, 1.0, 0.5), kPiD / 2),
       idrOf(tree, Vec<3>(0.0, -3.0, 1.5))},
      {"quaternion not unit (norm 1.7)",
       lookAtPose(eye, Vec<3>(6.0, 1.0, 0.5), 0.4, 1.7),
       idrOf(tree, Vec<3>(0.0, -3.0, 1.5))},
      {"quaternion not unit (norm 0.3)",
       lookAtPose(eye, Vec<3>(6.0, 1.0, 0.5), -0.4, 0.3),
       idrOf(tree, Vec<3>(0.0, -3.0, 1.5))},
      {"far from the origin",
       lookAtPose(Vec<3>(500.0, -300.0, 20.0), Vec<3>(510.0, -295.0, 18.0)),
       idrOf(Vec<4>(510.0, -295.0, 18.0, 0.5), Vec<3>(498.0, -301.0, 20.5))},
      {"camera within 1 mm of the base plane",
       lookAtPose(Vec<3>(0.0, 0.0, 0.201), Vec<3>(5.0, 0.5, 0.3)),
       idrOf(Vec<4>(5.0, 0.5, 0.2, 0.25), Vec<3>(-1.0, 0.5, 0.3))},
  };
}

}  // namespace

TEST_CASE("InverseDepthTreeWidth Jacobians match numerical differentiation",
          "[measurements][idr][jacobian]") {
  const InverseDepthTreeWidth model(kCamera);
  for (const Geometry& g : jacobianGeometries()) {
    INFO(g.name);
    const auto report = testing::checkMeasurementJacobians(model, g.camera, g.l, g.tolerance);
    INFO(report.message());
    CHECK(report.ok);
    Mat<3, 7> J_z_x;
    Mat<3, 7> J_z_l;
    const Vec<3> z = model(g.camera, g.l, J_z_x, J_z_l);
    CHECK(z == model.predict<double>(g.camera, g.l));
    CHECK(z == model(g.camera, g.l));
    // The model normalizes the quaternion, so scaling q changes nothing: J q = 0.
    CHECK((J_z_x.middleCols<4>(3) * g.camera.segment<4>(3)).norm() <=
          1e-9 * J_z_x.middleCols<4>(3).norm() * g.camera.segment<4>(3).norm());
    // Only one of the two Jacobians asked for: the same values.
    Mat<3, 7> J_x_only;
    Mat<3, 7> J_l_only;
    model(g.camera, g.l, J_x_only, skip);
    model(g.camera, g.l, skip, J_l_only);
    CHECK(J_x_only == J_z_x);
    CHECK(J_l_only == J_z_l);
    if (g.l[5] > 0.0) {
      // The same measurement as TreeWidth of the Euclidean tree.
      CHECK(relativeError(z, TreeWidth(kCamera)(g.camera, ToTree{}(g.camera, g.l))) <= 1e-9);
    }
  }
}

TEST_CASE("InverseDepthTreeWidth analytic Jacobians equal automatic differentiation",
          "[measurements][idr][jacobian]") {
  const InverseDepthTreeWidth model(kCamera);
  for (const Geometry& g : jacobianGeometries()) {
    INFO(g.name);
    // Entry by entry, relative to each entry's own scale, and the values (tests/autodiff_check.hpp).
    sylva_test::checkMeasurementAgainstAutoDiff(model, g.camera, g.l);
  }
}

TEST_CASE("InverseDepthTreeWidth: a tree at infinity has a finite image, continuous in rho",
          "[measurements][idr]") {
  const InverseDepthTreeWidth model(kCamera);
  const Vec<7> l = idr(Vec<3>(0.0, 0.0, 1.5), 0.2, -0.02, 0.0, 0.02);
  const Vec<3> m = InverseDepth::direction<double>(l[3], l[4]);
  const Vec<7> x = lookAtPose(Vec<3>(3.0, -2.0, 1.6), Vec<3>(3.0, -2.0, 1.6) + m, 0.2);
  Mat<3, 7> J_z_x;
  Mat<3, 7> J_z_l;
  const Vec<3> z = model(x, l, J_z_x, J_z_l);
  REQUIRE(z.allFinite());
  // The width of a trunk of angular radius kappa: about 2 fx kappa when seen near the image
  // centre (exactly 2 fx tan(asin(kappa)) edge-on at the principal point).
  CHECK(z[2] == Approx(2.0 * kCamera.fx * l[6]).epsilon(0.05));
  // At infinity the camera position does not matter: zero position columns, and moving the
  // camera changes nothing.
  CHECK(J_z_x.leftCols<3>().isZero(0.0));
  Vec<7> moved = x;
  moved.head<3>() += Vec<3>(40.0, -7.0, 3.0);
  CHECK((model(moved, l) - z).norm() <= 1e-12 * z.norm());
  // Continuous through rho = 0: from both sides of infinity the image tends to this one (at
  // rho = 1e-9 the parallax of the camera's 3.6 m from the anchor is about 2e-6 px).
  for (const double rho : {1e-9, -1e-9}) {
    Vec<7> l_near = l;
    l_near[5] = rho;
    CHECK((model(x, l_near) - z).cwiseAbs().maxCoeff() < 1e-5);
  }
  // ... and a large but finite depth through TreeWidth of the Euclidean tree is close to it
  // (1000 km: the parallax of the camera's 3.6 m from the anchor is 2e-3 px).
  Vec<7> l_far = l;
  l_far[5] = 1e-6;
  CHECK((TreeWidth(kCamera)(x, ToTree{}(x, l_far)) - z).cwiseAbs().maxCoeff() < 1e-2);
}

TEST_CASE("InverseDepthTreeWidth rejects degenerate geometry and bad input with a reason",
          "[measurements][idr][errors]") {
  const InverseDepthTreeWidth model(kCamera);
  const AutoDiff<InverseDepthTreeWidth> automatic(model);
  const Vec<7> camera = lookAtPose(Vec<3>(0.0, 0.0, 1.5), Vec<3>(10.0, 0.0, 0.0));
  const Vec<7> l = idrOf(Vec<4>(10.0, 0.0, 0.0, 0.3), Vec<3>(-2.0, 1.0, 1.5));
  REQUIRE_NOTHROW(model(camera, l));

  // The code and message of what `f` throws, {kMalformedData, "no throw"} if nothing.
  auto thrown = [](auto&& f) -> std::pair<ErrorCode, std::string> {
    try {
      f();
    } catch (const Error& e) {
      return {e.code(), e.what()};
    }
    return {ErrorCode::kMalformedData, "no throw"};
  };
  // Rejected by operator() (with and without Jacobians, which stay untouched), predict<double>
  // and AutoDiff, with `code` and a message naming this model and containing `words`.
  auto expectRejected =
      [&](const Vec<7>& x, const Vec<7>& ll, ErrorCode code, const std::string& words) {
        Mat<3, 7> J_x = Mat<3, 7>::Constant(7.0);
        Mat<3, 7> J_l = Mat<3, 7>::Constant(7.0);
        const auto [c, what] = thrown([&] { model(x, ll, J_x, J_l); });
        INFO(what);
        CHECK(c == code);
        CHECK(what.find(std::string(toString(code)) + ": InverseDepthTreeWidth: ") !=
              std::string::npos);
        CHECK(what.find(words) != std::string::npos);
        CHECK(J_x == Mat<3, 7>::Constant(7.0));
        CHECK(J_l == Mat<3, 7>::Constant(7.0));
        CHECK(thrown([&] { model(x, ll); }).first == code);
        CHECK(thrown([&] { model.predict<double>(x, ll); }).first == code);
        CHECK(thrown([&] { automatic(x, ll, J_x, J_l); }).first == code);
      };

  SECTION("negative inverse depth with the tree in front of the camera") {
    // The Euclidean tree anchor + m / rho = (10, 0, 0) lies 10 m behind its anchor along m,
    // in front of the camera: scaled by rho < 0 it is reflected behind the camera.
    const Vec<7> behind_anchor = idr(Vec<3>(20.0, 0.0, 0.0), 0.0, 0.0, -0.1, 0.03);
    CHECK((InverseDepth::point<double>(Vec<6>(behind_anchor.head<6>())) - Vec<3>(10.0, 0.0, 0.0))
              .norm() < 1e-12);
    expectRejected(camera, behind_anchor, ErrorCode::kDegenerateGeometry, "behind its anchor");
    expectRejected(camera,
                   behind_anchor,
                   ErrorCode::kDegenerateGeometry,
                   "not entirely in front of the camera");
  }
  SECTION("the tree behind the camera") {
    expectRejected(camera,
                   idrOf(Vec<4>(-10.0, 0.0, 0.0, 0.3), Vec<3>(-2.0, 1.0, 1.5)),
                   ErrorCode::kDegenerateGeometry,
                   "in front of the camera");
  }
  SECTION("camera inside the trunk") {
    const Vec<7> inside = lookAtPose(Vec<3>(10.1, 0.0, 3.0), Vec<3>(10.1, 0.01, 0.0));
    expectRejected(inside, l, ErrorCode::kDegenerateGeometry, "inside the trunk");
  }
  SECTION("kappa zero or negative") {
    for (const double kappa : {0.0, -0.01}) {
      Vec<7> bad = l;
      bad[6] = kappa;
      expectRejected(camera, bad, ErrorCode::kDegenerateGeometry, "kappa");
    }
  }
  SECTION("zero quaternion") {
    Vec<7> x = camera;
    x.segment<4>(3).setZero();
    expectRejected(x, l, ErrorCode::kDegenerateGeometry, "quaternion");
  }
  SECTION("non-finite input") {
    for (const double bad : {kNaN, std::numeric_limits<double>::infinity()}) {
      for (int i = 0; i < 7; ++i) {
        Vec<7> x = camera;
        x[i] = bad;
        INFO("camera entry " << i << " = " << bad);
        expectRejected(x, l, ErrorCode::kNonFinite, "camera state is not finite");
      }
      for (int i = 0; i < 7; ++i) {
        Vec<7> ll = l;
        ll[i] = bad;
        INFO("landmark entry " << i << " = " << bad);
        expectRejected(camera, ll, ErrorCode::kNonFinite, "landmark is not finite");
      }
    }
  }
}

// ---------------------------------------------------------------------------------------
// The initialization.

TEST_CASE("InverseDepthRadiusInitialization: construction and helpers",
          "[measurements][idr][idr_init]") {
  STATIC_REQUIRE(InverseDepthRadiusInitialization::kMeasurementDim == 4);
  STATIC_REQUIRE(std::is_same_v<InverseDepthRadiusInitialization::Robot, Pose3D>);
  STATIC_REQUIRE(std::is_same_v<InverseDepthRadiusInitialization::Landmark, InverseDepthRadius>);
  CHECK(std::string(InverseDepthRadiusInitialization::kName) == "InverseDepthRadiusInitialization");

  const InverseDepthRadiusInitialization init(kCamera);
  CHECK(init.initialInverseDepth() == 0.1);  // Civera et al.'s defaults
  CHECK(init.inverseDepthSigma() == 0.5);
  CHECK(init.camera().fy == kCamera.fy);
  CHECK(init.measurement(Vec<3>(12.5, 300.25, 17.0)) == Vec<4>(12.5, 300.25, 17.0, 0.1));
  Mat<3, 3> uvw_cov;
  uvw_cov << 2.0, 0.5, 0.1,  //
      0.5, 1.0, 0.0,         //
      0.1, 0.0, 0.7;
  const Mat<4, 4> R = init.noise(Gaussian<3>::covariance(uvw_cov)).covariance();
  CHECK(R.topLeftCorner<3, 3>() == uvw_cov);
  CHECK(R(3, 3) == 0.25);
  CHECK(R.col(3).head<3>().isZero(0.0));
  CHECK(R.row(3).head<3>().isZero(0.0));
  const InverseDepthRadiusInitialization custom(kCamera, 0.05, 0.2);
  CHECK(custom.measurement(Vec<3>(1, 2, 3))[3] == 0.05);
  CHECK(custom.noise(Gaussian<3>::sigmas(Vec<3>(1, 1, 1))).covariance()(3, 3) ==
        Approx(0.04).epsilon(1e-15));

  auto rejects = [](const PinholeCamera& camera, double rho0, double sigma, ErrorCode code) {
    try {
      InverseDepthRadiusInitialization bad(camera, rho0, sigma);
    } catch (const Error& e) {
      INFO(e.what());
      CHECK(std::string(e.what()).find("InverseDepthRadiusInitialization: ") != std::string::npos);
      return e.code() == code;
    }
    return false;
  };
  CHECK(rejects(kCamera, 0.0, 0.5, ErrorCode::kInvalidArgument));
  CHECK(rejects(kCamera, -0.1, 0.5, ErrorCode::kInvalidArgument));
  CHECK(rejects(kCamera, 0.1, 0.0, ErrorCode::kInvalidArgument));
  CHECK(rejects(kCamera, kNaN, 0.5, ErrorCode::kNonFinite));
  CHECK(rejects(kCamera, 0.1, std::numeric_limits<double>::infinity(), ErrorCode::kNonFinite));
  CHECK(rejects({0.0, 1.0, 0.0, 0.0, 10, 10}, 0.1, 0.5, ErrorCode::kInvalidArgument));
  CHECK(rejects({1.0, 1.0, kNaN, 0.0, 10, 10}, 0.1, 0.5, ErrorCode::kNonFinite));
}

TEST_CASE(
    "InverseDepthRadiusInitialization: the new tree reproduces the width exactly, the centre "
    "approximately",
    "[measurements][idr][idr_init]") {
  const InverseDepthRadiusInitialization init(kCamera);
  const InverseDepthInitialization ray(kCamera);
  const InverseDepthTreeWidth model(kCamera);

  SECTION("a 0.25 m trunk 5 m ahead") {
    // The ray is taken through the measured (u, v), the centre of the image ellipse; but the
    // centre of an ellipse is not the image of the base circle's centre (perspective moves
    // it by an amount of second order in radius / depth, tree_width.hpp), so the new tree's
    // base centre lies on a slightly different ray, and its predicted ellipse centre is off
    // the measured one by about that amount: up to half a pixel here (fx kappa^2 = 1.25 px),
    // and nothing with the camera level with the base looking straight at it, where the
    // segment-shaped image is symmetric about the centre's. The width is reproduced exactly,
    // because kappa is solved on the new tree's own ray.
    for (const double height : {0.0, 0.5, 1.5, 3.0, -1.0}) {
      for (const double roll : {0.0, 0.4, -1.2}) {
        for (const Vec<3>& aim :
             {Vec<3>(5.0, 0.0, 0.0), Vec<3>(5.0, 1.5, -0.5), Vec<3>(4.0, -1.0, 1.0)}) {
          const Vec<4> tree(5.0, 0.0, 0.0, 0.25);
          const Vec<7> x = lookAtPose(Vec<3>(0.0, 0.0, height), aim, roll);
          const Vec<3> z = TreeWidth(kCamera)(x, tree);
          const Vec<7> l = init(x, init.measurement(z));
          const Vec<3> z_hat = model(x, l);
          INFO("height " << height << " roll " << roll << " aim " << aim.transpose() << ": z "
                         << z.transpose() << ", predicted " << z_hat.transpose());
          CHECK(std::abs(z_hat[2] - z[2]) <= 1e-9 * z[2]);
          CHECK((z_hat.head<2>() - z.head<2>()).norm() < 1.0);
          // kappa is close to the true radius / distance (0.05 here): the ray is off the
          // centre's by a small angle only (the worst seen is 0.15% off).
          const double kappa_true = tree[3] / (tree.head<3>() - x.head<3>()).norm();
          CHECK(l[6] == Approx(kappa_true).epsilon(5e-3));
        }
      }
    }
  }
  SECTION("random configurations") {
    Rng rng(4711);
    int tested = 0;
    double worst_w = 0.0;
    double worst_uv_ratio = 0.0;
    for (int trial = 0; trial < 4000 && tested < 1000; ++trial) {
      Config c;
      const double height = (rng.uniform01() < 0.5 ? -1.0 : 1.0) * rng.uniform(0.1, 3.0);
      if (!randomConfig(rng, rng.uniform(1.0, 25.0), height, c)) continue;
      const double rho0 = trial % 4 == 0 ? 0.0 : rng.uniform(0.01, 2.0);
      const Vec<4> zi(c.z[0], c.z[1], c.z[2], rho0);
      Vec<7> l;
      try {
        l = init(c.camera, zi);
      } catch (const Error& e) {
        FAIL("a valid measurement was rejected: " << e.what());
      }
      // The ray part is exactly InverseDepthInitialization's.
      CHECK(l.head<6>() == ray(c.camera, Vec<3>(c.z[0], c.z[1], rho0)));
      const Vec<3> z_hat = model(c.camera, l);
      worst_w = std::max(worst_w, std::abs(z_hat[2] - c.z[2]) / c.z[2]);
      // The centre's offset is second order in kappa: below fx kappa^2 (the worst seen is
      // about two thirds of it).
      const double ratio = (z_hat.head<2>() - c.z.head<2>()).norm() / (kCamera.fx * l[6] * l[6]);
      worst_uv_ratio = std::max(worst_uv_ratio, ratio);
      ++tested;
    }
    INFO(tested << " configurations: worst relative width error " << worst_w
                << ", worst centre offset / (fx kappa^2) " << worst_uv_ratio);
    CHECK(tested == 1000);
    CHECK(worst_w <= 1e-9);
    CHECK(worst_uv_ratio < 1.0);
  }
}

TEST_CASE("InverseDepthRadiusInitialization: kappa does not depend on the prior depth",
          "[measurements][idr][idr_init]") {
  const Vec<7> x = lookAtPose(Vec<3>(1.0, -2.0, 1.5), Vec<3>(6.0, 1.0, 0.0), 0.3);
  const Vec<3> z = TreeWidth(kCamera)(x, Vec<4>(6.0, 1.0, 0.0, 0.35));
  const InverseDepthRadiusInitialization init(kCamera);
  const Vec<7> l0 = init(x, Vec<4>(z[0], z[1], z[2], 0.0));
  Mat<7, 4> J_l_z;
  for (const double rho0 : {1e-3, 0.1, 0.5, 2.0, 50.0}) {
    const Vec<7> l = init(x, Vec<4>(z[0], z[1], z[2], rho0), skip, J_l_z);
    INFO("rho0 " << rho0);
    CHECK(l[6] == l0[6]);
    CHECK(l.head<5>() == l0.head<5>());
    CHECK(l[5] == rho0);
    CHECK(J_l_z(6, 3) == 0.0);
    CHECK(J_l_z.col(3) == (Vec<7>() << 0, 0, 0, 0, 0, 1, 0).finished());
  }
  // A different prior from the constructor changes only rho.
  const InverseDepthRadiusInitialization other(kCamera, 0.7, 0.3);
  const Vec<7> l = other(x, other.measurement(z));
  CHECK(l[6] == l0[6]);
  CHECK(l[5] == 0.7);
}

namespace {

void requireInitJacobians(const InverseDepthRadiusInitialization& init,
                          const Vec<7>& x,
                          const Vec<4>& z,
                          double tolerance = 1e-6) {
  const testing::JacobianReport report = testing::checkInverseJacobians(init, x, z, tolerance);
  INFO(report.message());
  CHECK(report.ok);
  // The structure: the ray part is InverseDepthInitialization's, kappa depends on neither
  // the camera position nor rho0.
  Mat<7, 7> J_l_x;
  Mat<7, 4> J_l_z;
  init(x, z, J_l_x, J_l_z);
  Mat<6, 7> J6_x;
  Mat<6, 3> J6_z;
  InverseDepthInitialization(init.camera())(x, Vec<3>(z[0], z[1], z[3]), J6_x, J6_z);
  CHECK(J_l_x.topRows<6>() == J6_x);
  CHECK(J_l_z.block<6, 2>(0, 0) == J6_z.leftCols<2>());
  CHECK(J_l_z.block<6, 1>(0, 3) == J6_z.col(2));
  CHECK(J_l_z.block<6, 1>(0, 2).isZero(0.0));
  CHECK(J_l_x.block<1, 3>(6, 0).isZero(0.0));
  CHECK(J_l_z(6, 3) == 0.0);
  CHECK(J_l_z(6, 2) > 0.0);  // a wider image, a thicker trunk
  // The quaternion's scale does not matter. Bounded by the size of the whole quaternion block:
  // for a thin far tree kappa's row is itself at round-off level (about 1e-13), and a bound
  // relative to that row alone would ask round-off to cancel exactly.
  CHECK(std::abs(J_l_x.block<1, 4>(6, 3).dot(x.segment<4>(3))) <=
        1e-9 * J_l_x.middleCols<4>(3).norm() * x.segment<4>(3).norm());
}

}  // namespace

TEST_CASE("InverseDepthRadiusInitialization Jacobians match numerical differentiation",
          "[measurements][idr][idr_init][jacobian]") {
  const InverseDepthRadiusInitialization init(kCamera);

  SECTION("random configurations, quaternion scales 0.5-2, trees anywhere in the image") {
    Rng rng(8103);
    int tested = 0;
    for (int trial = 0; trial < 1000 && tested < 200; ++trial) {
      Config c;
      const double height = (rng.uniform01() < 0.5 ? -1.0 : 1.0) * rng.uniform(0.1, 3.0);
      if (!randomConfig(rng, rng.uniform(1.0, 25.0), height, c)) continue;
      INFO("trial " << trial);
      requireInitJacobians(init, c.camera, Vec<4>(c.z[0], c.z[1], c.z[2], rng.uniform(0.01, 2.0)));
      ++tested;
    }
    CHECK(tested == 200);
  }
  SECTION("awkward geometry") {
    // The shared TreeWidth geometries, but for the azimuth seam: 1e-9 rad from pi, central
    // differences would straddle theta's 2 pi jump (atan2) and see it, not the derivative, so
    // the seam is tried 3e-3 rad away instead (the autodiff checks take the 1e-9 cases).
    std::vector<sylva_test::TreeWidthGeometry> cases;
    for (const auto& g : sylva_test::treeWidthGeometries())
      if (std::string(g.name).find("azimuth near") == std::string::npos) cases.push_back(g);
    cases.push_back({"tree in the -x direction (azimuth 3e-3 rad from pi)",
                     lookAtPose(Vec<3>(10.0, 0.0, 1.5), Vec<3>(4.0, 3e-3, 0.0)),
                     Vec<4>(4.0, 3e-3, 0.0, 0.3)});
    for (const sylva_test::TreeWidthGeometry& c : cases) {
      INFO(c.name);
      const Vec<3> z = TreeWidth(kCamera)(c.camera, c.tree);
      requireInitJacobians(init, c.camera, Vec<4>(z[0], z[1], z[2], 0.1));
      requireInitJacobians(init, c.camera, Vec<4>(z[0], z[1], z[2], 0.02));
    }
  }
}

TEST_CASE("InverseDepthRadiusInitialization rejects bad input before writing anything",
          "[measurements][idr][idr_init][errors]") {
  const InverseDepthRadiusInitialization init(kCamera);
  const Vec<7> x = lookAtPose(Vec<3>(1.0, -2.0, 1.5), Vec<3>(6.0, 1.0, 0.0));
  const Vec<3> uvw = TreeWidth(kCamera)(x, Vec<4>(6.0, 1.0, 0.0, 0.3));
  const Vec<4> z = init.measurement(uvw);
  REQUIRE_NOTHROW(init(x, z));

  auto expectRejected =
      [&](const Vec<7>& xx, const Vec<4>& zz, ErrorCode code, const std::string& words) {
        Mat<7, 7> J_x = Mat<7, 7>::Constant(7.0);
        Mat<7, 4> J_z = Mat<7, 4>::Constant(7.0);
        std::string what = "no throw";
        ErrorCode thrown = ErrorCode::kMalformedData;
        try {
          init(xx, zz, J_x, J_z);
        } catch (const Error& e) {
          what = e.what();
          thrown = e.code();
        }
        INFO(what);
        CHECK(thrown == code);
        CHECK(what.find(std::string(toString(code)) + ": InverseDepthRadiusInitialization: ") !=
              std::string::npos);
        CHECK(what.find(words) != std::string::npos);
        CHECK(J_x == Mat<7, 7>::Constant(7.0));
        CHECK(J_z == Mat<7, 4>::Constant(7.0));
        CHECK(throwsCode([&] { init(xx, zz); }, code));
      };

  SECTION("non-positive width") {
    expectRejected(
        x, Vec<4>(z[0], z[1], 0.0, z[3]), ErrorCode::kDegenerateGeometry, "width must be > 0");
    expectRejected(
        x, Vec<4>(z[0], z[1], -3.0, z[3]), ErrorCode::kDegenerateGeometry, "width must be > 0");
  }
  SECTION("negative prior inverse depth") {
    expectRejected(
        x, Vec<4>(z[0], z[1], z[2], -0.1), ErrorCode::kDegenerateGeometry, "prior inverse depth");
  }
  SECTION("non-finite measurement or camera") {
    for (const double bad : {kNaN, std::numeric_limits<double>::infinity()}) {
      for (int i = 0; i < 4; ++i) {
        Vec<4> zb = z;
        zb[i] = bad;
        INFO("z entry " << i);
        expectRejected(x, zb, ErrorCode::kNonFinite, "not finite");
      }
      for (int i : {0, 4, 6}) {
        Vec<7> xb = x;
        xb[i] = bad;
        INFO("camera entry " << i);
        expectRejected(xb, z, ErrorCode::kNonFinite, "not finite");
      }
    }
  }
  SECTION("zero quaternion") {
    Vec<7> xb = x;
    xb.segment<4>(3).setZero();
    expectRejected(xb, z, ErrorCode::kDegenerateGeometry, "quaternion");
  }
  SECTION("a vertical ray") {
    const Vec<7> down = lookAtPose(Vec<3>(0.5, 0.5, 3.0), Vec<3>(0.5, 0.5, 0.0));
    expectRejected(down,
                   Vec<4>(kCamera.cx, kCamera.cy, 20.0, 0.1),
                   ErrorCode::kDegenerateGeometry,
                   "vertical");
  }
  SECTION("a width no trunk in front of the camera can have") {
    // 5000 px wide at the image centre: the trunk would have to reach behind the camera,
    // or enclose it.
    expectRejected(x, Vec<4>(z[0], z[1], 5000.0, z[3]), ErrorCode::kDegenerateGeometry, "kappa");
  }
}

// ---------------------------------------------------------------------------------------
// The filter.

namespace {

using TreeEkf = Ekf<ConstantVelocity3D, InverseDepthRadius, TreeXYZR>;
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

TEST_CASE("IDR EKF: add, width updates and the switch to XYZ-R equal the dense reference",
          "[measurements][idr][filter]") {
  const InverseDepthRadiusInitialization init(kCamera);
  const InverseDepthTreeWidth idr_model(kCamera);
  const TreeWidth xyzr_model(kCamera);
  const Gaussian<6> process =
      Gaussian<6>::sigmas((Vec<6>() << Vec<3>::Constant(0.05), Vec<3>::Constant(0.02)).finished());
  const Gaussian<3> width_noise = Gaussian<3>::sigmas(Vec<3>(1.0, 1.5, 0.8));
  const double dt = 0.1;

  const Vec<13> camera = startCamera();
  TreeEkf ekf(camera, startCovariance());
  Reference ref{ConstantVelocity3D{}, camera, startCovariance()};
  const Vec<4> z1 = init.measurement(TreeWidth(kCamera)(ConstantVelocity3D::pose(camera), Vec<4>(7.0, 1.0, 0.0, 0.3)));
  const Vec<4> z2 = init.measurement(TreeWidth(kCamera)(ConstantVelocity3D::pose(camera), Vec<4>(9.0, -2.5, 0.3, 0.2)));
  ekf.add(1, init, z1, init.noise(width_noise));
  ref.add(init, z1, init.noise(width_noise).covariance());
  ekf.add(2, init, z2, init.noise(width_noise));
  ref.add(init, z2, init.noise(width_noise).covariance());
  REQUIRE(ekf.holds<InverseDepthRadius>(1));
  CHECK((ekf.mean() - ref.x).cwiseAbs().maxCoeff() < 1e-14);
  CHECK((ekf.covariance() - ref.P).cwiseAbs().maxCoeff() < 1e-14);
  // From the first frame: the depth is the prior's, the angular size is the width's.
  const Mat<7, 7> P1 = ekf.landmarkCovariance<InverseDepthRadius>(1);
  CHECK(std::sqrt(P1(5, 5)) == Approx(0.5).epsilon(1e-3));
  CHECK(std::sqrt(P1(6, 6)) < 0.1 * ekf.landmarkMean<InverseDepthRadius>(1)[6]);

  // Predictions and width updates of both trees, with measurements a little off.
  for (int k = 0; k < 3; ++k) {
    ekf.predict(Vec<0>(), dt, process);
    ref.predict(Vec<0>(), dt, process.covariance());
    for (Id id : {Id(1), Id(2)}) {
      const int offset = ekf.slot(id).offset;
      const Vec<3> z = idr_model(ConstantVelocity3D::pose(ekf.robotMean()), ekf.landmarkMean<InverseDepthRadius>(id)) +
                       Vec<3>(1.5, -2.0, 0.7);
      ekf.update(idr_model, id, z, width_noise);
      ref.update(idr_model, offset, z, width_noise.covariance());
      ref.renormalizeRobot();
    }
  }
  CHECK((ekf.mean() - ref.x).cwiseAbs().maxCoeff() < 1e-10);
  CHECK((ekf.covariance() - ref.P).cwiseAbs().maxCoeff() < 1e-10);

  // Tree 1 to XYZ-R: its block moves to the end of the state, with the conversion's mean
  // and covariance J P J^T (J = [J_to_x, J_to_l] over the robot and the tree's blocks).
  const int offset1 = ekf.slot(1).offset;
  const Vec<7> l1 = ekf.landmarkMean<InverseDepthRadius>(1);
  const Eigen::MatrixXd P_before = ekf.covariance();
  Mat<4, 13> J_x;
  Mat<4, 7> J_l;
  const Vec<4> tree1 = InverseDepthRadiusToTree<ConstantVelocity3D>{}(ekf.robotMean(), l1, J_x, J_l);
  Mat<20, 20> P_joint;
  P_joint << P_before.topLeftCorner<13, 13>(), P_before.block<13, 7>(0, offset1),
      P_before.block<7, 13>(offset1, 0), P_before.block<7, 7>(offset1, offset1);
  Mat<4, 20> J;
  J << J_x, J_l;
  const Mat<4, 4> P_tree = J * P_joint * J.transpose();
  const Mat<4, 13> P_tree_robot =
      J_x * P_before.topLeftCorner<13, 13>() + J_l * P_before.block<7, 13>(offset1, 0);

  ekf.reparametrize(1, InverseDepthRadiusToTree<ConstantVelocity3D>{});
  ref.reparametrize(offset1, InverseDepthRadiusToTree<ConstantVelocity3D>{});
  REQUIRE(ekf.holds<TreeXYZR>(1));
  CHECK((ekf.landmarkMean<TreeXYZR>(1) - tree1).norm() <= 1e-14 * tree1.norm());
  CHECK(tree1[3] == Approx(l1[6] / l1[5]).epsilon(1e-14));
  CHECK((ekf.landmarkCovariance<TreeXYZR>(1) - P_tree).cwiseAbs().maxCoeff() <=
        1e-12 * P_tree.cwiseAbs().maxCoeff());
  CHECK(
      (ekf.robotLandmarkCovariance<TreeXYZR>(1).transpose() - P_tree_robot).cwiseAbs().maxCoeff() <=
      1e-15);
  CHECK((ekf.mean() - ref.x).cwiseAbs().maxCoeff() < 1e-10);
  CHECK((ekf.covariance() - ref.P).cwiseAbs().maxCoeff() < 1e-10);

  // One more update of each: tree 1 through TreeWidth, tree 2 still through the IDR model.
  const int offset1_xyzr = ekf.slot(1).offset;
  REQUIRE(offset1_xyzr == ref.dim() - 4);
  const Vec<3> z1_next =
      xyzr_model(ConstantVelocity3D::pose(ekf.robotMean()), ekf.landmarkMean<TreeXYZR>(1)) + Vec<3>(-1.0, 0.5, -0.4);
  ekf.update(xyzr_model, 1, z1_next, width_noise);
  ref.update(xyzr_model, offset1_xyzr, z1_next, width_noise.covariance());
  ref.renormalizeRobot();
  const int offset2 = ekf.slot(2).offset;
  const Vec<3> z2_next =
      idr_model(ConstantVelocity3D::pose(ekf.robotMean()), ekf.landmarkMean<InverseDepthRadius>(2)) + Vec<3>(0.5, 0.5, 0.3);
  ekf.update(idr_model, 2, z2_next, width_noise);
  ref.update(idr_model, offset2, z2_next, width_noise.covariance());
  ref.renormalizeRobot();
  CHECK((ekf.mean() - ref.x).cwiseAbs().maxCoeff() < 1e-10);
  CHECK((ekf.covariance() - ref.P).cwiseAbs().maxCoeff() < 1e-10);
}

TEST_CASE("IDR EKF: a tree's position and radius from a moving camera, then XYZ-R",
          "[measurements][idr][filter]") {
  const InverseDepthRadiusInitialization init(kCamera);
  const InverseDepthTreeWidth idr_model(kCamera);
  const TreeWidth xyzr_model(kCamera);
  const ConstantVelocity3D motion;
  const Gaussian<6> process =
      Gaussian<6>::sigmas((Vec<6>() << Vec<3>::Constant(1e-3), Vec<3>::Constant(1e-3)).finished());
  const double sigma_px = 0.5;
  const Gaussian<3> width_noise = Gaussian<3>::sigmas(Vec<3>(sigma_px, sigma_px, sigma_px));
  const double dt = 0.1;
  const Vec<4> truth(6.0, 1.0, 0.0, 0.25);

  Rng rng(8202);
  Vec<13> camera = startCamera();
  TreeEkf ekf(camera, startCovariance());
  auto observe = [&] {
    return Vec<3>(xyzr_model(ConstantVelocity3D::pose(camera), truth) + Vec<3>(sigma_px * rng.normal(),
                                                     sigma_px * rng.normal(),
                                                     sigma_px * rng.normal()));
  };

  const Id id = 3;
  ekf.add(id, init, init.measurement(observe()), init.noise(width_noise));
  REQUIRE(ekf.holds<InverseDepthRadius>(id));
  const Vec<7> l0 = ekf.landmarkMean<InverseDepthRadius>(id);
  const double kappa_true = truth[3] / (truth.head<3>() - camera.head<3>()).norm();
  // The first frame already knows the angular size to a few per cent.
  CHECK(l0[6] == Approx(kappa_true).epsilon(0.05));

  int steps = 0;
  double linearity = INFINITY;
  for (; steps < 60 && linearity >= 0.1; ++steps) {
    camera = motion(camera, Vec<0>(), dt);
    ekf.predict(Vec<0>(), dt, process);
    ekf.update(idr_model, id, observe(), width_noise);
    const double sigma_rho = std::sqrt(ekf.landmarkCovariance<InverseDepthRadius>(id)(5, 5));
    linearity = inverseDepthRadiusLinearityIndex(
        ekf.robotMean().head<3>(), ekf.landmarkMean<InverseDepthRadius>(id), sigma_rho);
  }
  INFO("steps in IDR: " << steps << ", linearity index " << linearity);
  CHECK(steps > 3);
  CHECK(linearity < 0.1);

  ekf.reparametrize(id, InverseDepthRadiusToTree<ConstantVelocity3D>{});
  REQUIRE(ekf.holds<TreeXYZR>(id));
  for (int k = 0; k < 40; ++k) {
    camera = motion(camera, Vec<0>(), dt);
    ekf.predict(Vec<0>(), dt, process);
    ekf.update(xyzr_model, id, observe(), width_noise);
  }
  const Vec<4> tree = ekf.landmarkMean<TreeXYZR>(id);
  const Mat<4, 4> P = ekf.landmarkCovariance<TreeXYZR>(id);
  const double nees = (tree - truth).dot(P.ldlt().solve(tree - truth));
  INFO("tree " << tree.transpose() << ", truth " << truth.transpose() << ", sigma "
               << P.diagonal().cwiseSqrt().transpose() << ", NEES " << nees);
  CHECK((tree.head<3>() - truth.head<3>()).norm() < 0.15);
  CHECK(std::abs(tree[3] - truth[3]) < 0.01);
  CHECK(nees < 18.47);  // chi-square(4) 99.9%
}

}  // namespace unity_measurements_inverse_depth_tree_width
