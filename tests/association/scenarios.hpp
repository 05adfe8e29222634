#pragma once
// Deterministic 2D range-bearing maps for the association tests. Every landmark is
// initialized from a noise-free measurement taken at the true initial pose, so the mapped
// means are the true positions and every measurement below is derived, not drawn.

#include "filter_snapshot.hpp"
#include "sylva_catch.hpp"

#include <string>
#include <utility>
#include <vector>

#include <sylva/association.hpp>
#include <sylva/sylva.hpp>

namespace sylva_test {

using Filter = sylva::Ekf<sylva::Unicycle2D, sylva::Point2>;
using Pairing = std::vector<std::optional<sylva::Id>>;

struct Scenario {
  Filter ekf;
  std::vector<sylva::Id> ids;         ///< ids of the mapped landmarks, in map order
  std::vector<sylva::Vec<2>> points;  ///< their true (= mapped) positions
  sylva::Vec<3> true_pose;            ///< where the robot really is when it measures
  sylva::Gaussian<2> noise;           ///< range-bearing noise used to map and to gate

  /// Noise-free range-bearing measurement of `point` from the true pose.
  sylva::Vec<2> measure(const sylva::Vec<2>& point) const {
    return sylva::RangeBearing{}(true_pose, point);
  }
  /// Measurements of the landmarks with the given indices into `points`.
  std::vector<sylva::Vec<2>> measureLandmarks(const std::vector<int>& which) const {
    std::vector<sylva::Vec<2>> z;
    for (const int k : which) z.push_back(measure(points[static_cast<std::size_t>(k)]));
    return z;
  }
};

/// Maps `points` (ids first_id, first_id + 1, ...) from the pose x0 with robot prior P0 and
/// sensor noise `noise`.
inline Scenario mapPoints(const sylva::Vec<3>& x0,
                          const sylva::Mat<3, 3>& P0,
                          const std::vector<sylva::Vec<2>>& points,
                          const sylva::Gaussian<2>& noise,
                          sylva::Id first_id) {
  Scenario s{Filter(x0, P0), {}, points, x0, noise};
  for (std::size_t k = 0; k < points.size(); ++k) {
    const sylva::Id id = first_id + static_cast<sylva::Id>(k);
    s.ekf.add(id, sylva::InverseRangeBearing{}, sylva::RangeBearing{}(x0, points[k]), noise);
    s.ids.push_back(id);
  }
  return s;
}

/// Four landmarks 5 m apart around a robot at the origin that knows its pose to 1 cm.
inline Scenario easyScenario() {
  const sylva::Vec<3> x0(0.0, 0.0, 0.0);
  const sylva::Mat<3, 3> P0 = sylva::Vec<3>(1e-4, 1e-4, 1e-6).asDiagonal();
  const std::vector<sylva::Vec<2>> points = {{5.0, 0.0}, {5.0, 5.0}, {0.0, 5.0}, {-5.0, -2.0}};
  return mapPoints(x0, P0, points, sylva::Gaussian<2>::sigmas(sylva::Vec<2>(0.05, 0.01)), 1);
}

/// The row of trees. The robot heads along +y (theta = pi/2) past a row of five trees 10 m to
/// its right, at x = 10 m with uneven spacings 1.0, 1.25, 0.9, 1.1 m along y (ids 10..14). It
/// maps them from the origin with a range-bearing sensor of 5 cm and 3 mrad: along the row,
/// which the sensor sees as bearing, each tree is placed to about 3 cm relative to the robot,
/// so the trees are known relative to each other to a few centimetres while their absolute
/// positions share the robot's prior error of 0.3 m (strongly correlated through the robot).
/// It then drives 1 m along +y on odometry whose speed noise is 0.5 m/s: the estimate says
/// y = 1 m, with an along-track standard deviation of 0.5 m relative to the map. In truth the
/// wheels slipped and the robot is at y = 1 - slip_m. (The trees stand 10 m away so that a
/// 0.7 m error of the robot is still small against the range and the linearized innovation
/// covariances describe it well.)
inline Scenario treeRowScenario(double slip_m) {
  const sylva::Vec<3> x0(0.0, 0.0, sylva::kPi / 2.0);
  const sylva::Mat<3, 3> P0 = sylva::Vec<3>(0.09, 0.09, 1e-4).asDiagonal();
  const std::vector<sylva::Vec<2>> points = {
      {10.0, 0.0}, {10.0, 1.0}, {10.0, 2.25}, {10.0, 3.15}, {10.0, 4.25}};
  Scenario s =
      mapPoints(x0, P0, points, sylva::Gaussian<2>::sigmas(sylva::Vec<2>(0.05, 0.003)), 10);
  const double dt_s = 1.0;
  s.ekf.predict(
      sylva::Vec<2>(1.0, 0.0), dt_s, sylva::Gaussian<2>::sigmas(sylva::Vec<2>(0.5, 1e-3)));
  s.true_pose = sylva::Vec<3>(0.0, 1.0 - slip_m, sylva::kPi / 2.0);
  return s;
}

inline Pairing ids(std::initializer_list<std::optional<sylva::Id>> list) { return Pairing(list); }

}  // namespace sylva_test
