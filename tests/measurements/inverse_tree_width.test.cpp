// InverseTreeWidth: the radius from a width inverts TreeWidth exactly over many random
// configurations (ordinary, within 1 cm of the base plane, looking straight down), its
// Jacobian (eq. 3.27-3.32) against central differences and against automatic
// differentiation of the closed form, and degenerate or invalid input.

#include "camera_pose.hpp"
#include "sylva_catch.hpp"

#include <cmath>
#include <string>

#include <Eigen/Geometry>
#include <unsupported/Eigen/AutoDiff>

#include <sylva/measurements/inverse_tree_width.hpp>
#include <sylva/measurements/tree_width.hpp>
#include <sylva/sim/random.hpp>
#include <sylva/testing/check_jacobians.hpp>

#include "error_helpers.hpp"

// Own namespace: the tests of a folder are compiled as one unity translation unit.
namespace unity_measurements_inverse_tree_width {

using namespace sylva;
using sylva_test::lookAtPose;
using sylva::sim::Rng;

namespace {

const PinholeCamera kCamera{500.0, 480.0, 320.0, 240.0, 640, 480};

struct Config {
  Vec<7> camera;
  Vec<4> tree;
  Vec<3> z;
};

// A random camera/tree pair whose forward model is valid; `height_m` is the camera's height
// above the base plane (negative: below it).
bool randomConfig(Rng& rng, double height_m, Config& out) {
  const Vec<4> tree(rng.uniform(-5.0, 5.0), rng.uniform(-5.0, 5.0), rng.uniform(-1.0, 1.0),
                    rng.uniform(0.05, 0.6));
  const double range = rng.uniform(1.0, 25.0);
  const double bearing = rng.uniform(-3.14159, 3.14159);
  const Vec<3> position = tree.head<3>() + Vec<3>(range * std::cos(bearing), range * std::sin(bearing), height_m);
  // Aim near the tree so it lands anywhere in the image.
  const Vec<3> target = tree.head<3>() + Vec<3>(rng.uniform(-1.5, 1.5), rng.uniform(-1.5, 1.5), rng.uniform(-1.0, 1.0));
  const Vec<7> camera = lookAtPose(position, target, rng.uniform(-0.5, 0.5), rng.uniform(0.5, 2.0));
  try {
    out = Config{camera, tree, TreeWidth(kCamera)(camera, tree)};
  } catch (const Error&) {
    return false;
  }
  return true;
}

}  // namespace

TEST_CASE("InverseTreeWidth recovers the radius TreeWidth was given", "[inverse_tree_width]") {
  const InverseTreeWidth inverse(kCamera);
  Rng rng(20261122);
  struct Band {
    const char* name;
    double lo, hi;
    double tolerance;
  };
  // Near the base plane d33 ~ -C3^2 and the width is a small difference of large terms: the
  // tolerance is looser there, as for the forward model's brute-force check.
  for (const Band& band : {Band{"ordinary", 0.2, 3.0, 1e-9}, Band{"within 1 cm of the base plane", -0.01, 0.01, 1e-6}}) {
    int tested = 0;
    double worst = 0.0;
    for (int i = 0; i < 4000 && tested < 1000; ++i) {
      Config c;
      if (!randomConfig(rng, rng.uniform(band.lo, band.hi), c)) continue;
      Vec<4> l;
      try {
        l = inverse(c.camera, c.tree.head<3>(), c.z);
      } catch (const Error& e) {
        FAIL("a valid configuration was rejected: " << e.what());
      }
      worst = std::max(worst, std::abs(l[3] - c.tree[3]) / c.tree[3]);
      CHECK(l.head<3>() == c.tree.head<3>());
      ++tested;
    }
    INFO(band.name << ": " << tested << " configurations, worst relative radius error " << worst);
    CHECK(tested == 1000);
    CHECK(worst < band.tolerance);
  }
}

TEST_CASE("InverseTreeWidth handles a camera looking straight down", "[inverse_tree_width]") {
  // n = (0, 0, -1) in the camera frame: the quadratic's leading coefficient vanishes.
  const Vec<4> tree(1.0, 2.0, 0.0, 0.3);
  for (const Vec<3>& offset : {Vec<3>(-1.2, 0.3, 4.0), Vec<3>(0.7, -0.4, 4.0)}) {
    const Vec<7> camera = lookAtPose(tree.head<3>() + offset, tree.head<3>() + Vec<3>(offset.x(), offset.y(), 0.0));
    const Vec<3> z = TreeWidth(kCamera)(camera, tree);
    const Vec<4> l = InverseTreeWidth(kCamera)(camera, tree.head<3>(), z);
    CHECK(l[3] == Approx(0.3).epsilon(1e-12));
    const auto report = testing::checkMeasuredConversionJacobians(InverseTreeWidth(kCamera), camera,
                                                                  Vec<3>(tree.head<3>()), z, 1e-6);
    INFO(report.message());
    CHECK(report.ok);
  }
}

TEST_CASE("InverseTreeWidth Jacobians match central differences", "[inverse_tree_width][jacobian]") {
  const InverseTreeWidth inverse(kCamera);
  Rng rng(7);
  struct Band {
    const char* name;
    double lo, hi;
  };
  for (const Band& band : {Band{"ordinary", 0.3, 3.0}, Band{"near the base plane", 0.01, 0.05}, Band{"below the plane", -2.0, -0.3}}) {
    int tested = 0;
    double worst = 0.0;
    for (int i = 0; i < 2000 && tested < 200; ++i) {
      Config c;
      if (!randomConfig(rng, rng.uniform(band.lo, band.hi), c)) continue;
      const auto report =
          testing::checkMeasuredConversionJacobians(inverse, c.camera, Vec<3>(c.tree.head<3>()), c.z);
      INFO(band.name << ": " << report.message());
      REQUIRE(report.ok);
      worst = std::max(worst, report.max_error);
      ++tested;
    }
    INFO(band.name);
    CHECK(tested == 200);
    WARN(band.name << ": worst Jacobian error " << worst << " of the checker's bound over " << tested << " configurations");
  }
}

TEST_CASE("InverseTreeWidth's implicit Jacobian equals autodiff of the closed form", "[inverse_tree_width][jacobian]") {
  using Dual = Eigen::AutoDiffScalar<Vec<11>>;
  const InverseTreeWidth inverse(kCamera);
  Rng rng(11);
  int tested = 0;
  for (int i = 0; i < 200 && tested < 50; ++i) {
    Config c;
    if (!randomConfig(rng, rng.uniform(0.2, 3.0), c)) continue;
    Vec<7, Dual> x;
    Vec<3, Dual> base;
    for (int k = 0; k < 7; ++k) x[k] = Dual(c.camera[k], 11, k);
    for (int k = 0; k < 3; ++k) base[k] = Dual(c.tree[k], 11, 7 + k);
    const Dual w(c.z[2], 11, 10);
    const Dual r = inverse.radius<Dual>(x, base, w);
    Mat<4, 7> J_x;
    Mat<4, 3> J_l;
    Mat<4, 3> J_z;
    inverse(c.camera, c.tree.head<3>(), c.z, J_x, J_l, J_z);
    const Vec<11> analytic = (Vec<11>() << J_x.row(3).transpose(), J_l.row(3).transpose(), J_z(3, 2)).finished();
    const double scale = std::max(1.0, r.derivatives().cwiseAbs().maxCoeff());
    CHECK((analytic - r.derivatives()).cwiseAbs().maxCoeff() / scale < 1e-8);
    CHECK(J_z(3, 0) == 0.0);
    CHECK(J_z(3, 1) == 0.0);
    ++tested;
  }
  CHECK(tested == 50);
}

TEST_CASE("InverseTreeWidth rejects invalid and degenerate input with a reason", "[inverse_tree_width][errors]") {
  using sylva_test::throwsCode;
  const InverseTreeWidth inverse(kCamera);
  const Vec<4> tree(0.0, 0.0, 0.0, 0.3);
  const Vec<7> camera = lookAtPose(Vec<3>(-6.0, 0.5, 1.5), Vec<3>(0.0, 0.0, 0.0));
  const Vec<3> z = TreeWidth(kCamera)(camera, tree);
  const Vec<3> base = tree.head<3>();

  CHECK(throwsCode([&] { inverse(camera, base, Vec<3>(z[0], z[1], 0.0)); }, ErrorCode::kDegenerateGeometry));
  CHECK(throwsCode([&] { inverse(camera, base, Vec<3>(z[0], z[1], -3.0)); }, ErrorCode::kDegenerateGeometry));
  CHECK(throwsCode([&] { inverse(camera, base, Vec<3>(z[0], z[1], NAN)); }, ErrorCode::kNonFinite));
  Vec<7> bad = camera;
  bad[4] = INFINITY;
  CHECK(throwsCode([&] { inverse(bad, base, z); }, ErrorCode::kNonFinite));
  CHECK(throwsCode([&] { inverse(camera, Vec<3>(NAN, 0.0, 0.0), z); }, ErrorCode::kNonFinite));
  bad = camera;
  bad.segment<4>(3).setZero();
  CHECK(throwsCode([&] { inverse(bad, base, z); }, ErrorCode::kDegenerateGeometry));
  // The tree behind the camera.
  const Vec<7> away = lookAtPose(Vec<3>(-6.0, 0.5, 1.5), Vec<3>(-12.0, 1.0, 0.0));
  CHECK(throwsCode([&] { inverse(away, base, z); }, ErrorCode::kDegenerateGeometry));
}

}  // namespace unity_measurements_inverse_tree_width
