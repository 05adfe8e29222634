#pragma once
/// @file
/// `sim::BezierLoop2D`: a closed, C1-continuous curve through waypoints in the plane, made of
/// one cubic Bezier segment per pair of consecutive waypoints (tree-width thesis,
/// Sec. 4.1.1: the camera trajectory is a Bezier curve through chosen points). The inner
/// control points come from Catmull-Rom tangents, so the curve passes through every
/// waypoint with a continuous tangent:
///
///   segment i from P_i to P_{i+1}:  B_i(s) = (1-s)^3 P_i + 3 (1-s)^2 s (P_i + T_i / 3)
///                                          + 3 (1-s) s^2 (P_{i+1} - T_{i+1} / 3) + s^3 P_{i+1},
///   T_i = (P_{i+1} - P_{i-1}) / 2   (indices modulo the number of waypoints).
///
/// Positions are looked up by arc length (a table of 400 samples per segment, then linear
/// interpolation of the curve parameter), so a trajectory can move at constant speed.

#include <algorithm>
#include <cmath>
#include <vector>

#include "sylva/core/error.hpp"
#include "sylva/core/types.hpp"

namespace sylva::sim {

class BezierLoop2D {
 public:
  /// Throws kInvalidArgument for fewer than 3 waypoints, repeated consecutive waypoints, or
  /// non-finite ones.
  explicit BezierLoop2D(std::vector<Vec<2>> waypoints) : points_(std::move(waypoints)) {
    const int n = static_cast<int>(points_.size());
    if (n < 3) fail(ErrorCode::kInvalidArgument, "BezierLoop2D: need at least 3 waypoints, got " + std::to_string(n));
    for (int i = 0; i < n; ++i) {
      if (!points_[i].allFinite()) fail(ErrorCode::kNonFinite, "BezierLoop2D: waypoint " + std::to_string(i) + " is not finite");
      if ((points_[(i + 1) % n] - points_[i]).norm() < 1e-9)
        fail(ErrorCode::kInvalidArgument, "BezierLoop2D: waypoints " + std::to_string(i) + " and " +
                                              std::to_string((i + 1) % n) + " coincide");
    }
    // Arc-length table.
    table_s_.push_back(0.0);
    table_param_.push_back(0.0);
    Vec<2> previous = bezier(0, 0.0);
    for (int i = 0; i < n; ++i) {
      for (int k = 1; k <= kSamplesPerSegment; ++k) {
        const double s = static_cast<double>(k) / kSamplesPerSegment;
        const Vec<2> p = bezier(i, s);
        table_s_.push_back(table_s_.back() + (p - previous).norm());
        table_param_.push_back(i + s);
        previous = p;
      }
    }
  }

  const std::vector<Vec<2>>& waypoints() const { return points_; }
  double length() const { return table_s_.back(); }

  /// Position at arc length s (any real s; wraps around the loop).
  Vec<2> position(double s) const {
    const double u = parameter(s);
    const int i = std::min(static_cast<int>(u), segments() - 1);
    return bezier(i, u - i);
  }

  /// Unit tangent (direction of travel) at arc length s.
  Vec<2> tangent(double s) const {
    const double u = parameter(s);
    const int i = std::min(static_cast<int>(u), segments() - 1);
    return derivative(i, u - i).normalized();
  }

  /// Segment i (0-based) at curve parameter t in [0, 1].
  Vec<2> bezier(int i, double t) const {
    Vec<2> c[4];
    controls(i, c);
    const double a = 1.0 - t;
    return a * a * a * c[0] + 3.0 * a * a * t * c[1] + 3.0 * a * t * t * c[2] + t * t * t * c[3];
  }

  /// d bezier(i, t) / dt.
  Vec<2> derivative(int i, double t) const {
    Vec<2> c[4];
    controls(i, c);
    const double a = 1.0 - t;
    return 3.0 * a * a * (c[1] - c[0]) + 6.0 * a * t * (c[2] - c[1]) + 3.0 * t * t * (c[3] - c[2]);
  }

 private:
  static constexpr int kSamplesPerSegment = 400;

  int segments() const { return static_cast<int>(points_.size()); }

  void controls(int i, Vec<2> (&c)[4]) const {
    const int n = segments();
    const Vec<2>& p_prev = points_[(i + n - 1) % n];
    const Vec<2>& p0 = points_[i];
    const Vec<2>& p1 = points_[(i + 1) % n];
    const Vec<2>& p2 = points_[(i + 2) % n];
    c[0] = p0;
    c[1] = p0 + (p1 - p_prev) / 6.0;
    c[2] = p1 - (p2 - p0) / 6.0;
    c[3] = p1;
  }

  /// Curve parameter (segment index + local t) at arc length s, wrapped to one lap.
  double parameter(double s) const {
    const double L = length();
    double w = std::fmod(s, L);
    if (w < 0.0) w += L;
    const auto it = std::upper_bound(table_s_.begin(), table_s_.end(), w);
    const std::size_t k = std::clamp<std::size_t>(static_cast<std::size_t>(it - table_s_.begin()), 1, table_s_.size() - 1);
    const double s0 = table_s_[k - 1], s1 = table_s_[k];
    const double f = s1 > s0 ? (w - s0) / (s1 - s0) : 0.0;
    return table_param_[k - 1] + f * (table_param_[k] - table_param_[k - 1]);
  }

  std::vector<Vec<2>> points_;
  std::vector<double> table_s_;
  std::vector<double> table_param_;
};

}  // namespace sylva::sim
