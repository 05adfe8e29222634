#pragma once
// A small monocular tree-SLAM rig for the filter tests that exercise the whole camera filter
// (allocation counting, fault injection): the camera 1.5 m above the ground looking along
// world +x (camera x = -y_W, y = -z_W, z = x_W) driving at 1 m/s, the camera models, the
// inverse-depth initialization and 1 px noise.

#include <sylva/core/types.hpp>
#include <sylva/measurements/inverse_depth_initialization.hpp>
#include <sylva/measurements/pinhole_camera.hpp>
#include <sylva/measurements/pinhole_point.hpp>
#include <sylva/measurements/tree_width.hpp>
#include <sylva/noise/gaussian.hpp>

namespace sylva_test {

struct MonocularRig {
  sylva::PinholeCamera camera{500.0, 500.0, 320.0, 240.0, 640, 480};
  sylva::Vec<13> x0 = forwardCamera();
  sylva::PinholePoint<sylva::InverseDepth> id_model{camera};
  sylva::PinholePoint<sylva::Point3> xyz_model{camera};
  sylva::TreeWidth width_model{camera};
  sylva::InverseDepthInitialization init{camera};
  sylva::Gaussian<2> pixel = sylva::Gaussian<2>::sigmas(sylva::Vec<2>(1.0, 1.0));
  sylva::Gaussian<3> pixel_width = sylva::Gaussian<3>::sigmas(sylva::Vec<3>(1.0, 1.0, 1.0));

  static sylva::Vec<13> forwardCamera() {
    sylva::Vec<13> x = sylva::Vec<13>::Zero();
    x.head<3>() = sylva::Vec<3>(0.0, 0.0, 1.5);
    x.segment<4>(3) = sylva::Vec<4>(0.5, -0.5, 0.5, -0.5);
    x.segment<3>(7) = sylva::Vec<3>(1.0, 0.0, 0.0);
    return x;
  }
};

}  // namespace sylva_test
