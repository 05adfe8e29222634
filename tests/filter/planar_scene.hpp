#pragma once
// The small planar scene of the linearization tests (first estimates, ideal, invariant, pose
// view): the noise of the odometry [v, omega] and of the range-bearing sensor, a filter that
// has just seen landmark 7 at range 5 m, bearing 0.4 rad, and landmarks on two rings around
// the circle a robot drives.

#include <cmath>
#include <vector>

#include <sylva/core/angles.hpp>
#include <sylva/filter/ekf.hpp>
#include <sylva/landmarks/point2.hpp>
#include <sylva/measurements/range_bearing.hpp>
#include <sylva/motion/unicycle_2d.hpp>
#include <sylva/noise/gaussian.hpp>

namespace sylva_test {

inline sylva::Gaussian<2> planarControlNoise() { return sylva::Gaussian<2>::sigmas(sylva::Vec<2>(0.1, 0.05)); }
inline sylva::Gaussian<2> planarSensorNoise() { return sylva::Gaussian<2>::sigmas(sylva::Vec<2>(0.2, 0.05)); }

/// A filter at `x0` (covariance 0.01 I) with linearization `point` that has added landmark 7.
inline sylva::Ekf<sylva::Unicycle2D, sylva::Point2> filterWithLandmark7(const sylva::Vec<3>& x0,
                                                                        sylva::LinearizationPoint point) {
  sylva::Ekf<sylva::Unicycle2D, sylva::Point2> ekf(x0, sylva::Mat<3, 3>::Identity() * 0.01);
  ekf.setLinearizationPoint(point);
  ekf.add(7, sylva::InverseRangeBearing(), sylva::Vec<2>(5.0, 0.4), planarSensorNoise());
  return ekf;
}

/// `count` landmarks around the circle of radius `radius` about (0, radius) that a robot
/// starting at the origin heading along +x drives (counter-clockwise): at even indices on a
/// ring `outer` from the centre, at odd ones `inner`, evenly spaced in angle.
inline std::vector<sylva::Vec<2>> landmarksOnTwoRings(int count, double radius, double inner, double outer) {
  std::vector<sylva::Vec<2>> out;
  for (int i = 0; i < count; ++i) {
    const double a = 2.0 * sylva::kPi * i / count;
    const double r = i % 2 == 0 ? outer : inner;
    out.emplace_back(r * std::sin(a), radius - r * std::cos(a));
  }
  return out;
}

}  // namespace sylva_test
