// The analytic Jacobians of the conversions that `Ekf::reparametrize` applies,
// InverseDepthToPoint3 and InverseDepthRadiusToTree, against forward-mode automatic
// differentiation of their Scalar-generic `convert<T>` (which operator() returns), at
// ordinary and awkward geometry: azimuth at +-pi, elevation near +-pi/2, far points (small
// rho) and near ones (large rho), anchors far from the origin, thin and wide trunks; for a
// Pose3D robot and for ConstantVelocity3D (J_to_x is zero for both: the conversions do not
// depend on the robot). A second check beside the central differences of
// inverse_depth.test.cpp and inverse_depth_radius.test.cpp, exact to round-off.

#include "sylva_catch.hpp"

#include <sylva/core/angles.hpp>
#include <sylva/landmarks/inverse_depth.hpp>
#include <sylva/landmarks/inverse_depth_radius.hpp>
#include <sylva/motion/constant_velocity_3d.hpp>
#include <sylva/motion/pose_3d.hpp>

#include "autodiff_check.hpp"
#include "camera_pose.hpp"

// Own namespace: the tests of a folder are compiled as one unity translation unit.
namespace unity_landmarks_conversion_autodiff {

using namespace sylva;

using sylva_test::checkConversionAgainstAutoDiff;

struct Ray {
  const char* name;
  Vec<3> anchor;
  double theta;
  double phi;
};

const Ray kRays[] = {
    {"ordinary", Vec<3>(1.0, -2.0, 1.6), 0.4, 0.2},
    {"azimuth just below +pi", Vec<3>(1.0, -2.0, 1.6), kPi - 1e-9, -0.1},
    {"azimuth just above -pi", Vec<3>(1.0, -2.0, 1.6), -kPi + 1e-9, -0.1},
    {"azimuth pi", Vec<3>(1.0, -2.0, 1.6), kPi, 0.3},
    {"elevation 1e-6 below +pi/2", Vec<3>(0.5, 0.5, 0.0), 1.1, 0.5 * kPi - 1e-6},
    {"elevation 1e-6 above -pi/2", Vec<3>(0.5, 0.5, 0.0), -2.0, -0.5 * kPi + 1e-6},
    {"anchor 100 km from the origin", Vec<3>(1e5, -1e5, 30.0), 2.5, -0.05},
};

TEST_CASE(
    "InverseDepthToPoint3 and InverseDepthRadiusToTree Jacobians equal automatic differentiation",
    "[landmarks][jacobian][autodiff]") {
  const Vec<7> pose =
      sylva_test::lookAtPose(Vec<3>(1.0, 1.0, 1.0), Vec<3>(5.0, 2.0, 0.0), 0.3, 2.5);
  const Vec<13> state = sylva_test::lookAt(Vec<3>(1.0, 1.0, 1.0), Vec<3>(5.0, 2.0, 0.0), 0.3, 2.5);
  for (const Ray& ray : kRays) {
    // rho from a point 1 cm away to one 1000 km away.
    for (const double rho : {0.1, 100.0, 1e-6}) {
      Vec<6> l;
      l << ray.anchor, ray.theta, ray.phi, rho;
      INFO(ray.name << ", rho " << rho);
      checkConversionAgainstAutoDiff(InverseDepthToPoint3<Pose3D>{}, pose, l);
      checkConversionAgainstAutoDiff(InverseDepthToPoint3<ConstantVelocity3D>{}, state, l);
      // kappa = radius / depth: a 1 mm trunk 1000 km away up to a 1 m trunk 10 cm away.
      for (const double kappa : {0.03, 1e-9, 10.0}) {
        INFO("kappa " << kappa);
        Vec<7> tree;
        tree << l, kappa;
        checkConversionAgainstAutoDiff(InverseDepthRadiusToTree<Pose3D>{}, pose, tree);
        checkConversionAgainstAutoDiff(InverseDepthRadiusToTree<ConstantVelocity3D>{}, state, tree);
      }
    }
  }
}

}  // namespace unity_landmarks_conversion_autodiff
