// TreeLifeCycle (Fig. 3.3): the default rules fire when they should and not before, the
// conversions equal doing them by hand, user-written rules plug in, bad calls are refused.

#include "camera_pose.hpp"
#include "sylva_catch.hpp"

#include <cmath>

#include <Eigen/Geometry>

#include <sylva/filter/ekf.hpp>
#include <sylva/slam/tree_life_cycle.hpp>
#include <sylva/measurements/tree_width.hpp>

#include "copy_init.hpp"
#include "error_helpers.hpp"

// Own namespace: the tests of a folder are compiled as one unity translation unit.
namespace unity_filter_tree_life_cycle {

using namespace sylva;
using sylva_test::lookAt;
using sylva_test::throwsCode;

namespace {

const PinholeCamera kCamera{500.0, 500.0, 320.0, 240.0, 640, 480};
using Filter = Ekf<ConstantVelocity3D, InverseDepth, Point3, TreeXYZR>;

// Test-only initializations that copy a landmark (an inverse-depth point, an IDR tree) into the state.
using CopyInverseDepth = sylva_test::CopyInit<ConstantVelocity3D, InverseDepth>;
using CopyIdr = sylva_test::CopyInit<ConstantVelocity3D, InverseDepthRadius>;

// Inverse-depth point from the camera position towards `target`, with the given rho.
Vec<6> rayTowards(const Vec<3>& anchor, const Vec<3>& target, double rho) {
  const Vec<3> d = (target - anchor).normalized();
  Vec<6> l;
  l << anchor, std::atan2(d.y(), d.x()), std::asin(d.z()), rho;
  return l;
}

Gaussian<6> inverseDepthNoise(double sigma_rho) {
  Vec<6> sigmas;
  sigmas << 0.01, 0.01, 0.01, 0.002, 0.002, sigma_rho;
  return Gaussian<6>::sigmas(sigmas);
}

}  // namespace

TEST_CASE("inverse depth becomes XYZ when its linearity index falls below the threshold", "[life_cycle]") {
  const Vec<3> tree(10.0, 0.0, 0.0);
  Filter ekf(lookAt(Vec<3>(0.0, 0.0, 1.5), tree, 0.0, 1.0, Vec<6>::Zero()), Mat<13, 13>::Identity() * 1e-6);
  // Id 1: depth well known (sigma_rho 0.001 at rho ~0.1: L ~ 0.04). Id 2: vague (L >> 0.1).
  ekf.add(1, CopyInverseDepth{}, rayTowards(Vec<3>(0.0, 0.0, 1.5), tree, 1.0 / 10.1), inverseDepthNoise(0.001));
  ekf.add(2, CopyInverseDepth{}, rayTowards(Vec<3>(0.0, 0.0, 1.5), Vec<3>(8.0, 3.0, 0.0), 0.1), inverseDepthNoise(0.5));
  Filter by_hand = ekf;

  const TreeLifeCycle<> life(kCamera);
  const std::vector<Id> converted = life.convertInverseDepth(ekf);
  REQUIRE(converted == std::vector<Id>{1});
  CHECK(ekf.holds<Point3>(1));
  CHECK(ekf.holds<InverseDepth>(2));
  by_hand.reparametrize(1, InverseDepthToPoint3<ConstantVelocity3D>{});
  CHECK(ekf.mean() == by_hand.mean());
  CHECK(ekf.covariance() == by_hand.covariance());

  // A stricter threshold keeps it as inverse depth; a landmark at infinity is never ready.
  Filter strict(lookAt(Vec<3>(0.0, 0.0, 1.5), tree, 0.0, 1.0, Vec<6>::Zero()), Mat<13, 13>::Identity() * 1e-6);
  strict.add(1, CopyInverseDepth{}, rayTowards(Vec<3>(0.0, 0.0, 1.5), tree, 1.0 / 10.1), inverseDepthNoise(0.001));
  strict.add(3, CopyInverseDepth{}, rayTowards(Vec<3>(0.0, 0.0, 1.5), tree, 0.0), inverseDepthNoise(1e-6));
  CHECK(TreeLifeCycle<>(kCamera, LinearityIndexBelow{0.01}).convertInverseDepth(strict).empty());
  CHECK(TreeLifeCycle<>(kCamera, LinearityIndexBelow{0.1}).convertInverseDepth(strict) == std::vector<Id>{1});
  CHECK(strict.holds<InverseDepth>(3));
}

TEST_CASE("an IDR tree becomes XYZ-R by the same linearity rule, inverse-depth points are left alone", "[life_cycle]") {
  using WithIdr = Ekf<ConstantVelocity3D, InverseDepth, Point3, TreeXYZR, InverseDepthRadius>;
  const Vec<3> tree(10.0, 0.0, 0.0);
  const Vec<3> anchor(0.0, 0.0, 1.5);
  WithIdr ekf(lookAt(anchor, tree, 0.0, 1.0, Vec<6>::Zero()), Mat<13, 13>::Identity() * 1e-6);
  // Ids 1 and 2 as in the inverse-depth case, now as IDR trees (kappa = 0.25 m * rho);
  // id 3, a well-known inverse-depth point, is for convertInverseDepth, not for this call.
  const auto idr = [&](const Vec<3>& target, double rho) {
    Vec<7> l;
    l << rayTowards(anchor, target, rho), 0.25 * rho;
    return l;
  };
  const auto idrNoise = [](double sigma_rho) {
    Vec<7> sigmas;
    sigmas << 0.01, 0.01, 0.01, 0.002, 0.002, sigma_rho, 0.001;
    return Gaussian<7>::sigmas(sigmas);
  };
  ekf.add(1, CopyIdr{}, idr(tree, 1.0 / 10.1), idrNoise(0.001));
  ekf.add(2, CopyIdr{}, idr(Vec<3>(8.0, 3.0, 0.0), 0.1), idrNoise(0.5));
  ekf.add(3, CopyInverseDepth{}, rayTowards(anchor, tree, 1.0 / 10.1), inverseDepthNoise(0.001));
  WithIdr by_hand = ekf;

  const TreeLifeCycle<> life(kCamera);
  REQUIRE(life.convertInverseDepthRadius(ekf) == std::vector<Id>{1});
  CHECK(ekf.holds<TreeXYZR>(1));
  CHECK(ekf.holds<InverseDepthRadius>(2));
  CHECK(ekf.holds<InverseDepth>(3));
  by_hand.reparametrize(1, InverseDepthRadiusToTree<ConstantVelocity3D>{});
  CHECK(ekf.mean() == by_hand.mean());
  CHECK(ekf.covariance() == by_hand.covariance());
  CHECK(ekf.landmarkMean<TreeXYZR>(1)[3] == Approx(0.25));
  // And convertInverseDepth converts the point only.
  REQUIRE(life.convertInverseDepth(ekf) == std::vector<Id>{3});
  CHECK(ekf.holds<InverseDepthRadius>(2));
}

TEST_CASE("XYZ becomes XYZ-R once its position is certain enough", "[life_cycle]") {
  const Vec<4> truth(10.0, 0.0, 0.0, 0.3);
  const Vec<13> camera = lookAt(Vec<3>(0.0, 0.5, 1.5), truth.head<3>(), 0.0, 1.0, Vec<6>::Zero());
  Filter ekf(camera, Mat<13, 13>::Identity() * 1e-6);
  ekf.add(1, CopyInverseDepth{}, rayTowards(camera.head<3>(), truth.head<3>(), 1.0 / (truth.head<3>() - camera.head<3>()).norm()),
          inverseDepthNoise(0.002));
  const TreeLifeCycle<> life(kCamera);
  REQUIRE(life.convertInverseDepth(ekf) == std::vector<Id>{1});
  const Vec<3> z = TreeWidth(kCamera)(ConstantVelocity3D::pose(camera), truth);
  const Gaussian<3> noise = Gaussian<3>::sigmas(Vec<3>(1.0, 1.0, 1.0));

  // Depth sigma ~ 0.002 / rho^2 ~ 0.2 m: not yet.
  CHECK_FALSE(life.convertToTree(ekf, 1, z, noise));
  CHECK(ekf.holds<Point3>(1));
  // A looser rule converts it, with the radius from the width.
  const TreeLifeCycle<> loose(kCamera, LinearityIndexBelow{}, PositionSigmaBelow{1.0});
  CHECK(loose.convertToTree(ekf, 1, z, noise));
  REQUIRE(ekf.holds<TreeXYZR>(1));
  CHECK(ekf.landmarkMean<TreeXYZR>(1)[3] == Approx(0.3).epsilon(1e-6));
  // Already XYZ-R: nothing to do.
  CHECK_FALSE(loose.convertToTree(ekf, 1, z, noise));
  CHECK(throwsCode([&] { loose.convertToTree(ekf, 42, z, noise); }, ErrorCode::kUnknownId));
}

namespace {
// A user-written rule: convert after a given number of calls for that landmark (here simply
// "is the id even"), to show that any callable with the documented signature plugs in.
struct EvenIdsOnly {
  template <typename F>
  bool operator()(const F&, Id id) const {
    return id % 2 == 0;
  }
};
}  // namespace

TEST_CASE("user-written switching rules plug into the life cycle", "[life_cycle]") {
  Filter ekf(lookAt(Vec<3>(0.0, 0.0, 1.5), Vec<3>(10.0, 0.0, 0.0), 0.0, 1.0, Vec<6>::Zero()), Mat<13, 13>::Identity() * 1e-6);
  for (Id id = 1; id <= 4; ++id)
    ekf.add(id, CopyInverseDepth{}, rayTowards(Vec<3>(0.0, 0.0, 1.5), Vec<3>(10.0, id - 2.0, 0.0), 0.1), inverseDepthNoise(0.5));
  const TreeLifeCycle<EvenIdsOnly, EvenIdsOnly> life(kCamera);
  CHECK(life.convertInverseDepth(ekf) == std::vector<Id>{2, 4});
  CHECK(ekf.holds<InverseDepth>(1));
  CHECK(ekf.holds<Point3>(4));
}

}  // namespace unity_filter_tree_life_cycle
