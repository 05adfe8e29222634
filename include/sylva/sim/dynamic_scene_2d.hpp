#pragma once
/// @file
/// `sim::DynamicScene2D`: a world for a planar laser scanner with static structure (walls,
/// poles) and moving objects, turned into a `LaserScene2D` snapshot at any time t.
///
/// Moving objects are of two kinds:
///
///   RigidObject2D     circles and segments fixed in a body frame whose pose moves at a
///                     constant velocity: pose(t) = pose0 + t [vx, vy, omega] (world
///                     frame; a body point p_b is at R(heading(t)) p_b + position(t));
///   WalkingPerson2D   two legs with a gait (walking_person_2d.hpp).
///
/// Every moving object's id (a rigid object's, each leg's) is "dynamic": `isDynamic(id)`
/// tells a detector's evaluation whether a beam that hit `id` saw a moving object, and
/// `objectPosition(id, t)` gives the object's reference point (the body origin, a leg's
/// centre) for position errors. Static shapes are given once, at construction.
///
/// Errors: a dynamic id used twice or also used by a static shape -> kDuplicateId; a rigid
/// object without shapes or with a non-finite pose or velocity -> kInvalidArgument /
/// kNonFinite; a non-finite time -> kNonFinite.

#include <cmath>
#include <optional>
#include <sstream>
#include <utility>
#include <vector>

#include "sylva/core/error.hpp"
#include "sylva/core/types.hpp"
#include "sylva/sim/laser_scene_2d.hpp"
#include "sylva/sim/walking_person_2d.hpp"

namespace sylva::sim {

/// A rigid body moving at constant velocity. `body` holds its shapes in the body frame
/// (their ids are ignored: every shape takes `object_id`).
struct RigidObject2D {
  Id object_id = 0;
  LaserScene2D body;
  Vec<3> pose_at_zero = Vec<3>::Zero();  ///< [x, y, heading] at t = 0
  Vec<3> velocity = Vec<3>::Zero();      ///< [vx, vy, omega] (m/s, m/s, rad/s), world frame

  Vec<3> poseAt(double t) const { return pose_at_zero + t * velocity; }

  /// A rectangular box (length along the body x axis, width along y) centred on the origin.
  static RigidObject2D box(Id id, double length_m, double width_m, const Vec<3>& pose0, const Vec<3>& velocity) {
    if (!(length_m > 0.0) || !(width_m > 0.0))
      fail(ErrorCode::kInvalidArgument, "RigidObject2D::box: length and width must be > 0");
    RigidObject2D o;
    o.object_id = id;
    const double hx = 0.5 * length_m, hy = 0.5 * width_m;
    o.body.addPolyline({Vec<2>(-hx, -hy), Vec<2>(hx, -hy), Vec<2>(hx, hy), Vec<2>(-hx, hy)}, true, id);
    o.pose_at_zero = pose0;
    o.velocity = velocity;
    return o;
  }

  /// A disc of `radius_m` centred on the body origin (a bin, a trunk on a trolley).
  static RigidObject2D disc(Id id, double radius_m, const Vec<3>& pose0, const Vec<3>& velocity) {
    RigidObject2D o;
    o.object_id = id;
    o.body.addCircle(Vec<2>::Zero(), radius_m, id);
    o.pose_at_zero = pose0;
    o.velocity = velocity;
    return o;
  }

  /// A flat board: one segment of `length_m` along the body y axis (a door, a panel).
  static RigidObject2D board(Id id, double length_m, const Vec<3>& pose0, const Vec<3>& velocity) {
    RigidObject2D o;
    o.object_id = id;
    o.body.addSegment(Vec<2>(0.0, -0.5 * length_m), Vec<2>(0.0, 0.5 * length_m), id);
    o.pose_at_zero = pose0;
    o.velocity = velocity;
    return o;
  }
};

class DynamicScene2D {
 public:
  DynamicScene2D() = default;
  explicit DynamicScene2D(LaserScene2D static_part) : static_(std::move(static_part)) {}

  const LaserScene2D& staticPart() const { return static_; }
  const std::vector<RigidObject2D>& rigidObjects() const { return rigid_; }
  const std::vector<WalkingPerson2D>& people() const { return people_; }

  void addRigidObject(RigidObject2D object) {
    if (object.body.empty())
      fail(ErrorCode::kInvalidArgument, "DynamicScene2D::addRigidObject: the object has no shapes");
    if (!object.pose_at_zero.allFinite() || !object.velocity.allFinite())
      fail(ErrorCode::kNonFinite, "DynamicScene2D::addRigidObject: pose or velocity is not finite");
    claim(object.object_id);
    rigid_.push_back(std::move(object));
  }

  void addPerson(const WalkingPerson2D& person) {
    if (person.legId(0) == person.legId(1))
      fail(ErrorCode::kDuplicateId, "DynamicScene2D::addPerson: both legs have the same id");
    claim(person.legId(0));
    claim(person.legId(1));
    people_.push_back(person);
  }

  /// True when `id` belongs to a moving object (a rigid object or a leg).
  bool isDynamic(Id id) const {
    for (const Id d : dynamic_ids_)
      if (d == id) return true;
    return false;
  }

  /// Reference point of the moving object `id` at time t (rigid: body origin; leg: its
  /// centre); nullopt for static or unknown ids.
  std::optional<Vec<2>> objectPosition(Id id, double t) const {
    checkTime(t);
    for (const RigidObject2D& o : rigid_)
      if (o.object_id == id) return Vec<2>(o.poseAt(t).head<2>());
    for (const WalkingPerson2D& p : people_)
      for (int leg = 0; leg < 2; ++leg)
        if (p.legId(leg) == id) return p.legCenter(leg, t);
    return std::nullopt;
  }

  /// Every moving object's id with its reference point at time t.
  std::vector<std::pair<Id, Vec<2>>> dynamicObjectPositions(double t) const {
    checkTime(t);
    std::vector<std::pair<Id, Vec<2>>> out;
    for (const RigidObject2D& o : rigid_) out.emplace_back(o.object_id, o.poseAt(t).head<2>());
    for (const WalkingPerson2D& p : people_)
      for (int leg = 0; leg < 2; ++leg) out.emplace_back(p.legId(leg), p.legCenter(leg, t));
    return out;
  }

  /// The scene at time t: the static part, then every rigid object, then every person.
  /// Reuses `out`'s storage.
  void snapshot(double t, LaserScene2D& out) const {
    checkTime(t);
    out.clear();
    out.append(static_);
    for (const RigidObject2D& o : rigid_) {
      const Vec<3> pose = o.poseAt(t);
      const double c = std::cos(pose[2]), s = std::sin(pose[2]);
      const auto toWorld = [&](const Vec<2>& p) {
        return Vec<2>(pose[0] + c * p.x() - s * p.y(), pose[1] + s * p.x() + c * p.y());
      };
      for (const Circle2D& circle : o.body.circles())
        out.addCircle(toWorld(circle.center), circle.radius_m, o.object_id);
      for (const Segment2D& segment : o.body.segments())
        out.addSegment(toWorld(segment.a), toWorld(segment.b), o.object_id);
    }
    for (const WalkingPerson2D& p : people_) p.addTo(t, out);
  }

  LaserScene2D snapshot(double t) const {
    LaserScene2D out;
    snapshot(t, out);
    return out;
  }

 private:
  static void checkTime(double t) {
    if (!std::isfinite(t)) fail(ErrorCode::kNonFinite, "DynamicScene2D: the time is not finite");
  }

  void claim(Id id) {
    bool taken = isDynamic(id);
    for (const Circle2D& c : static_.circles()) taken = taken || c.object_id == id;
    for (const Segment2D& s : static_.segments()) taken = taken || s.object_id == id;
    if (taken) {
      std::ostringstream os;
      os << "DynamicScene2D: the moving-object id " << id
         << " is already used (by another moving object or a static shape)";
      fail(ErrorCode::kDuplicateId, os.str());
    }
    dynamic_ids_.push_back(id);
  }

  LaserScene2D static_;
  std::vector<RigidObject2D> rigid_;
  std::vector<WalkingPerson2D> people_;
  std::vector<Id> dynamic_ids_;
};

}  // namespace sylva::sim
