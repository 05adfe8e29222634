#pragma once
/// @file
/// `sim::WalkingPerson2D`: a person as a laser scanner at knee height sees one, two legs,
/// each a disc, that take turns: one stands still on the ground (stance) while the other
/// swings forward (swing), as in the multisensor thesis' Fig. 4.9.
///
/// Route. The body walks along a polyline of waypoints at constant speed v, either around
/// it (`closed`) or to its end and back again (ping-pong). s(t) = s0 + v t is the distance
/// walked; the route repeats with period P (the perimeter, or twice the polyline's length).
///
/// Gait. Let L be the step length (the distance the body travels per step; a gait cycle is
/// two steps, 2 L, and lasts 2 L / v). Leg k (0 = left, 1 = right) runs the cycle shifted
/// by k L. With u = (s - k L) / (2 L), cycle c = floor(u) and phase phi = u - c in [0, 1),
/// the leg's foot sits at the route distance
///
///   stance, phi in [0, 1/2):  f = k L + 2 L c + L / 2                (fixed on the ground)
///   swing,  phi in [1/2, 1):  f = k L + 2 L c + L / 2 + L (1 - cos(pi w)),  w = 2 phi - 1
///
/// so each foot rests while the body passes over it (from L/2 behind to L/2 ahead) and then
/// swings 2 L forward with a smooth speed profile that peaks at pi v mid-swing and is zero at
/// both ends. f is continuous; the two legs are never in swing together. The disc of leg k
/// is centred at route(f) + side_k (spacing / 2) n(f), with n the left normal of the walking
/// direction and side = +1 for the left leg, -1 for the right.
///
/// Simplifications: stance and swing last half a cycle each (real walking has double
/// support); at a waypoint the lateral offset turns with the route at once, and at the end
/// of a ping-pong route the legs swap sides as the person turns on the spot.
///
/// Defaults: 1.2 m/s with 0.65 m steps (a gait cycle of about 1.1 s), legs of 6 cm radius
/// whose centres are 20 cm apart, the laser plane being at about knee height.
///
/// Errors (kInvalidArgument / kNonFinite at construction): fewer than two waypoints, two
/// consecutive waypoints that coincide, speed < 0, step length or leg radius <= 0, leg
/// spacing < 0, anything non-finite.

#include <array>
#include <cmath>
#include <sstream>
#include <utility>
#include <vector>

#include "sylva/core/angles.hpp"
#include "sylva/core/error.hpp"
#include "sylva/core/types.hpp"
#include "sylva/sim/laser_scene_2d.hpp"

namespace sylva::sim {

struct WalkingPerson2DOptions {
  std::vector<Vec<2>> waypoints;  ///< the route, at least two points
  bool closed = false;            ///< true: walk around; false: to the end and back
  double speed_mps = 1.2;         ///< body speed, >= 0
  double step_length_m = 0.65;    ///< body travel per step (half a gait cycle), > 0
  double leg_radius_m = 0.06;     ///< > 0
  double leg_spacing_m = 0.20;    ///< lateral distance between the leg centres, >= 0
  double start_distance_m = 0.0;  ///< distance along the route walked at t = 0
};

class WalkingPerson2D {
 public:
  WalkingPerson2D(const WalkingPerson2DOptions& options, Id left_leg_id, Id right_leg_id)
      : options_(validated(options)), leg_ids_{left_leg_id, right_leg_id} {
    const auto& w = options_.waypoints;
    cumulative_.push_back(0.0);
    const std::size_t sides = options_.closed ? w.size() : w.size() - 1;
    for (std::size_t i = 0; i < sides; ++i)
      cumulative_.push_back(cumulative_.back() + (w[(i + 1) % w.size()] - w[i]).norm());
    polyline_length_ = cumulative_.back();
    period_ = options_.closed ? polyline_length_ : 2.0 * polyline_length_;
  }

  const WalkingPerson2DOptions& options() const { return options_; }
  Id legId(int leg) const { return leg_ids_[checkedLeg(leg)]; }
  /// Length of one period of the route (m): the perimeter, or there and back.
  double routePeriod() const { return period_; }

  /// Distance walked by the body at time t (unbounded; the route repeats every period).
  double bodyDistance(double t) const { return options_.start_distance_m + options_.speed_mps * t; }

  /// Route distance of the foot of `leg` (0 left, 1 right) when the body has walked s.
  double footDistance(int leg, double s) const {
    const double step = options_.step_length_m;
    const double shifted = s - checkedLeg(leg) * step;
    const double cycle = std::floor(shifted / (2.0 * step));
    const double phase = shifted / (2.0 * step) - cycle;
    const double rest = checkedLeg(leg) * step + 2.0 * step * cycle + 0.5 * step;
    if (phase < 0.5) return rest;
    const double w = 2.0 * phase - 1.0;
    return rest + step * (1.0 - std::cos(kPi * w));
  }

  /// True while `leg` is in stance (not moving) at time t.
  bool inStance(int leg, double t) const {
    const double step = options_.step_length_m;
    const double shifted = bodyDistance(t) - checkedLeg(leg) * step;
    const double phase = shifted / (2.0 * step) - std::floor(shifted / (2.0 * step));
    return phase < 0.5;
  }

  /// Body position (between the legs, on the route) at time t.
  Vec<2> bodyPosition(double t) const { return routePoint(bodyDistance(t)); }

  /// Centre of the disc of `leg` at time t.
  Vec<2> legCenter(int leg, double t) const {
    const double f = footDistance(leg, bodyDistance(t));
    const Vec<2> direction = routeDirection(f);
    const Vec<2> left_normal(-direction.y(), direction.x());
    const double side = checkedLeg(leg) == 0 ? 1.0 : -1.0;
    return routePoint(f) + side * 0.5 * options_.leg_spacing_m * left_normal;
  }

  /// Adds both legs at time t to `scene`.
  void addTo(double t, LaserScene2D& scene) const {
    for (int leg = 0; leg < 2; ++leg)
      scene.addCircle(legCenter(leg, t), options_.leg_radius_m, leg_ids_[static_cast<std::size_t>(leg)]);
  }

  /// Point of the route at distance s (any real s; periodic).
  Vec<2> routePoint(double s) const {
    const auto [index, along] = locate(s);
    return vertex(index) + along * sideDirection(index);
  }

  /// Unit walking direction at distance s (backwards on the return leg of a ping-pong route).
  Vec<2> routeDirection(double s) const { return walkingSign(s) * sideDirection(locate(s).first); }

 private:
  static std::size_t checkedLeg(int leg) {
    if (leg != 0 && leg != 1) {
      std::ostringstream os;
      os << "WalkingPerson2D: leg must be 0 (left) or 1 (right), got " << leg;
      fail(ErrorCode::kInvalidArgument, os.str());
    }
    return static_cast<std::size_t>(leg);
  }

  /// s folded into one pass over the polyline: [0, polyline_length].
  double folded(double s) const {
    double u = std::fmod(s, period_);
    if (u < 0.0) u += period_;
    if (!options_.closed && u > polyline_length_) u = period_ - u;
    return u;
  }

  double walkingSign(double s) const {
    if (options_.closed) return 1.0;
    double u = std::fmod(s, period_);
    if (u < 0.0) u += period_;
    return u > polyline_length_ ? -1.0 : 1.0;
  }

  /// Index of the polyline side holding distance s and the distance along that side.
  std::pair<std::size_t, double> locate(double s) const {
    const double u = folded(s);
    std::size_t i = 0;
    while (i + 2 < cumulative_.size() && u >= cumulative_[i + 1]) ++i;
    return {i, u - cumulative_[i]};
  }

  const Vec<2>& vertex(std::size_t i) const { return options_.waypoints[i % options_.waypoints.size()]; }

  Vec<2> sideDirection(std::size_t i) const { return (vertex(i + 1) - vertex(i)).normalized(); }

  static WalkingPerson2DOptions validated(const WalkingPerson2DOptions& o) {
    std::ostringstream os;
    if (o.waypoints.size() < 2) {
      os << "WalkingPerson2D: the route needs at least two waypoints, got " << o.waypoints.size();
      fail(ErrorCode::kInvalidArgument, os.str());
    }
    for (std::size_t i = 0; i < o.waypoints.size(); ++i) {
      if (!o.waypoints[i].allFinite())
        fail(ErrorCode::kNonFinite, "WalkingPerson2D: a waypoint is not finite");
      const std::size_t next = (i + 1) % o.waypoints.size();
      if ((next != 0 || o.closed) && o.waypoints[i] == o.waypoints[next])
        fail(ErrorCode::kInvalidArgument, "WalkingPerson2D: two consecutive waypoints coincide");
    }
    if (!std::isfinite(o.speed_mps) || !std::isfinite(o.step_length_m) ||
        !std::isfinite(o.leg_radius_m) || !std::isfinite(o.leg_spacing_m) ||
        !std::isfinite(o.start_distance_m)) {
      fail(ErrorCode::kNonFinite, "WalkingPerson2D: speed, step length, leg size or start is not finite");
    }
    if (!(o.speed_mps >= 0.0) || !(o.step_length_m > 0.0) || !(o.leg_radius_m > 0.0) ||
        !(o.leg_spacing_m >= 0.0)) {
      os << "WalkingPerson2D: need speed >= 0, step length > 0, leg radius > 0 and leg spacing "
            ">= 0, got speed = "
         << o.speed_mps << " m/s, step = " << o.step_length_m << " m, radius = " << o.leg_radius_m
         << " m, spacing = " << o.leg_spacing_m << " m";
      fail(ErrorCode::kInvalidArgument, os.str());
    }
    return o;
  }

  WalkingPerson2DOptions options_;
  std::array<Id, 2> leg_ids_;
  std::vector<double> cumulative_;  // route distance at each vertex (closed: incl. back to 0)
  double polyline_length_ = 0.0;
  double period_ = 0.0;
};

}  // namespace sylva::sim
