#pragma once
// Test helpers: camera poses and XYZ-R trees valid for TreeWidth, ordinary and awkward, shared
// by the forward model's Jacobian checks (measurements/tree_width.test.cpp) and the inverse
// models' autodiff checks (measurements/inverse_autodiff.test.cpp), so that both models are
// checked at the same geometry.
#include <vector>

#include <sylva/core/types.hpp>

#include "camera_pose.hpp"

namespace sylva_test {

struct TreeWidthGeometry {
  const char* name;
  sylva::Vec<7> camera;  ///< Pose3D [r_WC, q_WC]
  sylva::Vec<4> tree;    ///< XYZ-R [base centre, radius]
};

inline std::vector<TreeWidthGeometry> treeWidthGeometries() {
  using sylva::Vec;
  constexpr double kHalfPi = 1.57079632679489661923;
  const Vec<3> eye(1.0, -2.0, 1.6);
  const Vec<3> far(1e5, 1e5, 1.6);
  return {
      {"ordinary", lookAtPose(eye, Vec<3>(6.0, 1.0, 0.5)), Vec<4>(6.0, 1.0, 0.2, 0.3)},
      {"camera 1 cm above the base plane",
       lookAtPose(Vec<3>(0.0, 0.0, 0.21), Vec<3>(5.0, 0.5, 0.3)),
       Vec<4>(5.0, 0.5, 0.2, 0.25)},
      {"camera 1 mm above the base plane",
       lookAtPose(Vec<3>(0.0, 0.0, 0.201), Vec<3>(5.0, 0.5, 0.3)),
       Vec<4>(5.0, 0.5, 0.2, 0.25)},
      {"camera 1 mm below the base plane",
       lookAtPose(Vec<3>(0.0, 0.0, 0.199), Vec<3>(5.0, 0.5, 0.3)),
       Vec<4>(5.0, 0.5, 0.2, 0.25)},
      {"camera exactly on the base plane",
       lookAtPose(Vec<3>(0.0, 0.0, 0.2), Vec<3>(5.0, 0.5, 0.6)),
       Vec<4>(5.0, 0.5, 0.2, 0.25)},
      {"camera 1.2 m below the base plane",
       lookAtPose(Vec<3>(0.0, 0.0, -1.0), Vec<3>(5.0, 0.5, 0.0)),
       Vec<4>(5.0, 0.5, 0.2, 0.25)},
      {"tree near the image border",
       lookAtPose(eye, Vec<3>(8.0, 4.4, 0.8)),
       Vec<4>(6.0, 2.8, 0.0, 0.3)},
      {"large radius, close", lookAtPose(eye, Vec<3>(4.0, -2.0, 0.5)), Vec<4>(4.0, -2.0, 0.0, 2.0)},
      {"a wide trunk 1.5 m away",
       lookAtPose(eye, Vec<3>(2.5, -2.0, 0.5)),
       Vec<4>(2.5, -2.0, 0.0, 0.6)},
      {"a thin tree 40 m away",
       lookAtPose(eye, Vec<3>(40.0, 10.0, 0.0)),
       Vec<4>(40.0, 10.0, 0.0, 0.1)},
      {"small radius, far", lookAtPose(eye, Vec<3>(40.0, 10.0, 0.0)), Vec<4>(40.0, 10.0, 0.0, 0.01)},
      {"camera rolled 90 deg about the optical axis",
       lookAtPose(eye, Vec<3>(6.0, 1.0, 0.5), kHalfPi),
       Vec<4>(6.0, 1.0, 0.2, 0.3)},
      {"camera rolled 90 deg, looking down",
       lookAtPose(eye, Vec<3>(3.0, -1.0, -1.0), -kHalfPi),
       Vec<4>(3.5, -1.0, 0.0, 0.3)},
      {"looking straight down",
       lookAtPose(Vec<3>(2.0, 0.0, 5.0), Vec<3>(2.0, 0.0, 0.0)),
       Vec<4>(2.5, 1.0, 0.0, 0.4)},
      {"looking steeply down on the tree",
       lookAtPose(Vec<3>(2.0, 0.0, 5.0), Vec<3>(2.0, 1e-3, 0.0)),
       Vec<4>(2.0, 1.0, 0.0, 0.4)},
      {"quaternion not unit (norm 0.05)",
       lookAtPose(eye, Vec<3>(6.0, 1.0, 0.5), 0.3, 0.05),
       Vec<4>(6.0, 1.0, 0.2, 0.3)},
      {"quaternion not unit (norm 0.3)",
       lookAtPose(eye, Vec<3>(6.0, 1.0, 0.5), -0.4, 0.3),
       Vec<4>(6.0, 1.0, 0.2, 0.3)},
      {"quaternion not unit (norm 1.7)",
       lookAtPose(eye, Vec<3>(6.0, 1.0, 0.5), 0.4, 1.7),
       Vec<4>(6.0, 1.0, 0.2, 0.3)},
      {"quaternion not unit (norm 40)",
       lookAtPose(eye, Vec<3>(6.0, 1.0, 0.5), 0.3, 40.0),
       Vec<4>(6.0, 1.0, 0.2, 0.3)},
      {"tree in the -x direction (azimuth near +pi)",
       lookAtPose(Vec<3>(10.0, 0.0, 1.5), Vec<3>(4.0, 1e-9, 0.0)),
       Vec<4>(4.0, 1e-9, 0.0, 0.3)},
      {"tree in the -x direction (azimuth near -pi)",
       lookAtPose(Vec<3>(10.0, 0.0, 1.5), Vec<3>(4.0, -1e-9, 0.0)),
       Vec<4>(4.0, -1e-9, 0.0, 0.3)},
      {"500 m from the origin",
       lookAtPose(Vec<3>(500.0, -300.0, 20.0), Vec<3>(510.0, -295.0, 18.0)),
       Vec<4>(510.0, -295.0, 18.0, 0.5)},
      {"camera 100 km from the origin",
       lookAtPose(far, far + Vec<3>(6.0, 2.0, -1.2)),
       Vec<4>(far.x() + 6.0, far.y() + 2.0, 0.0, 0.3)},
  };
}

}  // namespace sylva_test
