// The analytic Jacobians of the inverse (initialization) models and of the measured
// conversion XYZ -> XYZ-R against forward-mode automatic differentiation of the models' own
// Scalar-generic value functions (`initialize<T>`, `convert<T>`, which operator() returns):
// InverseRangeBearing, InverseRangeBearingDiameter, InverseDepthInitialization,
// InverseDepthRadiusInitialization and InverseTreeWidth, at ordinary and awkward geometry
// (world angles at +-pi, tiny and huge ranges, far from the origin, sensor mounts, rays near
// the zenith and the nadir, quaternions far from unit norm, a camera looking straight down,
// 1 cm above a tree's base plane). A second check beside the central differences of each
// model's own test file, exact to round-off (tests/autodiff_check.hpp).

#include "sylva_catch.hpp"

#include <cmath>
#include <type_traits>
#include <vector>

#include <sylva/core/angles.hpp>
#include <sylva/measurements/inverse_depth_initialization.hpp>
#include <sylva/measurements/inverse_depth_tree_width.hpp>
#include <sylva/measurements/inverse_tree_width.hpp>
#include <sylva/measurements/range_bearing.hpp>
#include <sylva/measurements/range_bearing_diameter.hpp>
#include <sylva/measurements/tree_width.hpp>

#include "autodiff_check.hpp"
#include "camera_pose.hpp"
#include "tree_width_geometries.hpp"

// Own namespace: the tests of a folder are compiled as one unity translation unit.
namespace unity_measurements_inverse_autodiff {

using namespace sylva;
using sylva_test::lookAtPose;

const PinholeCamera kCamera{500.0, 480.0, 320.0, 240.0, 640, 480};

using sylva_test::checkInverseAgainstAutoDiff;

TEST_CASE(
    "InverseRangeBearing and InverseRangeBearingDiameter Jacobians equal automatic differentiation",
    "[measurements][jacobian][autodiff]") {
  struct Case {
    const char* name;
    Vec<3> robot;
    Vec<2> z;  // [range, bearing]
  };
  const Case cases[] = {
      {"ordinary", Vec<3>(1.0, 2.0, 0.3), Vec<2>(5.0, 0.4)},
      {"world angle 2 pi", Vec<3>(0.0, 0.0, kPi), Vec<2>(3.0, kPi)},
      {"world angle just below +pi", Vec<3>(-2.0, 1.0, 3.0), Vec<2>(4.0, kPi - 3.0 - 1e-9)},
      {"world angle just above -pi", Vec<3>(-2.0, 1.0, -3.0), Vec<2>(4.0, -kPi + 3.0 + 1e-9)},
      {"bearing at the seam", Vec<3>(1.0, 1.0, 0.2), Vec<2>(2.0, kPi)},
      {"range 1 um", Vec<3>(1.0, -1.0, 0.7), Vec<2>(1e-6, -0.3)},
      {"range 100 km", Vec<3>(1.0, -1.0, 0.7), Vec<2>(1e5, 1.2)},
      {"robot 100 km from the origin", Vec<3>(1e5, -1e5, 1.0), Vec<2>(12.0, -0.8)},
  };
  const Vec<2> mounts[] = {Vec<2>::Zero(), Vec<2>(3.78, 0.5), Vec<2>(-1.0, 0.0)};
  for (const Vec<2>& mount : mounts) {
    const InverseRangeBearing inverse(mount);
    const InverseRangeBearingDiameter tree_inverse(mount);
    for (const Case& c : cases) {
      INFO(c.name << ", mount " << mount.transpose());
      checkInverseAgainstAutoDiff(inverse, c.robot, c.z);
      for (const double diameter : {1e-4, 0.3, 4.0}) {
        INFO("diameter " << diameter);
        checkInverseAgainstAutoDiff(tree_inverse, c.robot, Vec<3>(c.z[0], c.z[1], diameter));
      }
    }
  }
}

TEST_CASE("InverseDepthInitialization Jacobians equal automatic differentiation",
          "[measurements][inverse_depth_init][jacobian][autodiff]") {
  const InverseDepthInitialization init(kCamera);
  struct Case {
    const char* name;
    Vec<7> camera;
    Vec<2> pixel;
  };
  const Vec<3> eye(1.0, -2.0, 1.6);
  const Vec<3> far(1e5, -1e5, 50.0);
  // A pixel 1e-6 rad (in the image plane) off the principal point: looking straight up or
  // down, its ray is 1e-6 rad from the vertical, where d theta / d (u, v) is ~1e6 / fx.
  const Vec<2> near_centre(kCamera.cx + kCamera.fx * 1e-6, kCamera.cy);
  const Case cases[] = {
      {"ordinary", lookAtPose(eye, Vec<3>(6.0, 1.0, 0.5)), Vec<2>(100.0, 400.0)},
      {"image corner (0, 0)", lookAtPose(eye, Vec<3>(6.0, 1.0, 0.5), 0.4), Vec<2>(0.0, 0.0)},
      {"image corner (640, 480)",
       lookAtPose(eye, Vec<3>(6.0, 1.0, 0.5), -1.1),
       Vec<2>(640.0, 480.0)},
      {"far outside the image", lookAtPose(eye, Vec<3>(6.0, 1.0, 0.5)), Vec<2>(-3000.0, 2500.0)},
      {"quaternion norm 0.05",
       lookAtPose(eye, Vec<3>(6.0, 1.0, 0.5), 0.3, 0.05),
       Vec<2>(200.0, 100.0)},
      {"quaternion norm 1000",
       lookAtPose(eye, Vec<3>(6.0, 1.0, 0.5), 0.3, 1000.0),
       Vec<2>(200.0, 100.0)},
      {"azimuth just below +pi",
       lookAtPose(eye, eye + Vec<3>(-1.0, 1e-9, 0.0)),
       Vec<2>(kCamera.cx, kCamera.cy)},
      {"azimuth just above -pi",
       lookAtPose(eye, eye + Vec<3>(-1.0, -1e-9, 0.0)),
       Vec<2>(kCamera.cx, kCamera.cy)},
      {"ray 1e-6 rad from the zenith", lookAtPose(eye, eye + Vec<3>(0.0, 0.0, 1.0)), near_centre},
      {"ray 1e-6 rad from the nadir",
       lookAtPose(eye, eye + Vec<3>(0.0, 0.0, -1.0), 0.7),
       near_centre},
      {"camera 100 km from the origin",
       lookAtPose(far, far + Vec<3>(3.0, 4.0, -1.0), 0.2),
       Vec<2>(50.0, 300.0)},
  };
  for (const Case& c : cases) {
    for (const double rho0 : {0.1, 0.0, 3.0}) {
      INFO(c.name << ", rho0 " << rho0);
      checkInverseAgainstAutoDiff(init, c.camera, Vec<3>(c.pixel[0], c.pixel[1], rho0));
    }
  }
}

TEST_CASE("InverseDepthRadiusInitialization Jacobians equal automatic differentiation",
          "[measurements][idr][idr_init][jacobian][autodiff]") {
  const InverseDepthRadiusInitialization init(kCamera);
  for (const sylva_test::TreeWidthGeometry& c : sylva_test::treeWidthGeometries()) {
    const Vec<3> z = TreeWidth(kCamera)(c.camera, c.tree);
    for (const double rho0 : {0.1, 0.0, 2.0}) {
      INFO(c.name << ", rho0 " << rho0);
      checkInverseAgainstAutoDiff(init, c.camera, Vec<4>(z[0], z[1], z[2], rho0));
    }
  }
}

TEST_CASE("InverseTreeWidth Jacobians equal automatic differentiation at awkward geometry",
          "[measurements][inverse_tree_width][jacobian][autodiff]") {
  const InverseTreeWidth inverse(kCamera);
  for (const sylva_test::TreeWidthGeometry& c : sylva_test::treeWidthGeometries()) {
    INFO(c.name);
    const Vec<3> base = c.tree.head<3>();
    const Vec<3> z = TreeWidth(kCamera)(c.camera, c.tree);
    Mat<4, 7> J_x;
    Mat<4, 3> J_l;
    Mat<4, 3> J_z;
    const Vec<4> tree = inverse(c.camera, base, z, J_x, J_l, J_z);
    Mat<4, 13> analytic;
    analytic << J_x, J_l, J_z;
    Vec<13> v;
    v << c.camera, base, z;
    const auto f = [&](const auto& s) {
      using T = typename std::decay_t<decltype(s)>::Scalar;
      return inverse.convert<T>(Vec<7, T>(s.template head<7>()),
                                Vec<3, T>(s.template segment<3>(7)),
                                Vec<3, T>(s.template tail<3>()));
    };
    sylva_test::checkAgainstAutoDiff<4, 13>(
        "[J_to_x | J_to_l | J_to_z] of InverseTreeWidth (camera columns 0-6, base 7-9, z 10-12)",
        analytic,
        tree,
        f,
        v);
  }
}

}  // namespace unity_measurements_inverse_autodiff
