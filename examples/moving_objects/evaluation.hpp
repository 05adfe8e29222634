#pragma once
// Scoring a detection against the simulator's truth (which object each beam hit).
//
// Point scores. A reading of the current scan is "on a moving object" when the beam hit an
// object of the dynamic scene (a rigid mover, a leg). Precision is the share of the readings
// the detector reports that are on a moving object. Recall is the share of readings on
// objects that moved far enough between the two scans to be detectable that the detector
// reports. "Far enough" is eq. 4.5 read backwards: the object's reference point moved more
// than the closest-point threshold dd_c at its range. A leg in stance does not move at all
// and is not counted in this recall (`recall_all` counts it).
//
// Position error: each detected object is paired with the moving object whose readings it
// holds most of; the error is the distance from the object's hull centroid (and from its
// bounding-box centre) to that object's true reference point (a leg's centre, a rigid
// object's origin).

#include <algorithm>
#include <map>
#include <optional>
#include <vector>

#include <sylva/core/types.hpp>
#include <sylva/laser/moving_object_detector.hpp>
#include <sylva/sim/dynamic_scene_2d.hpp>
#include <sylva/sim/laser_scanner_2d.hpp>

namespace moving_objects {

using namespace sylva::laser;  // the detector and its scans (include/sylva/laser)
using sylva::LaserScanGeometry;

using sylva::Id;

struct PointScores {
  int reported = 0;            ///< readings the detector calls moving
  int reported_on_moving = 0;  ///< ... of which are on a moving object
  int detectable = 0;          ///< readings on objects that moved detectably
  int detectable_found = 0;    ///< ... of which the detector reports
  int on_moving = 0;           ///< readings on any moving object (moved or not)
  int on_moving_found = 0;

  /// NaN-free conventions: precision 1 when nothing is reported, recall 1 when nothing is
  /// there to find.
  double precision() const { return reported == 0 ? 1.0 : double(reported_on_moving) / reported; }
  double recall() const { return detectable == 0 ? 1.0 : double(detectable_found) / detectable; }
  double recallAll() const { return on_moving == 0 ? 1.0 : double(on_moving_found) / on_moving; }

  PointScores& operator+=(const PointScores& o) {
    reported += o.reported;
    reported_on_moving += o.reported_on_moving;
    detectable += o.detectable;
    detectable_found += o.detectable_found;
    on_moving += o.on_moving;
    on_moving_found += o.on_moving_found;
    return *this;
  }
};

/// True when object `id` moved more than dd_c (at its range from the current sensor)
/// between t_previous and t_current.
inline bool movedDetectably(const sylva::sim::DynamicScene2D& world,
                            Id id,
                            double t_previous,
                            double t_current,
                            const Vec<2>& sensor_position,
                            const LaserScanGeometry& g,
                            const MatchingOptions& o) {
  const auto before = world.objectPosition(id, t_previous);
  const auto after = world.objectPosition(id, t_current);
  if (!before || !after) return false;
  const double range = (*after - sensor_position).norm();
  return (*after - *before).norm() > rangeThreshold(o.match_k, o.match_floor_m, g.angle_increment_rad, range);
}

inline PointScores scorePoints(const Detection& d,
                               const sylva::sim::LaserScan2D& current_truth,
                               const sylva::sim::DynamicScene2D& world,
                               double t_previous,
                               double t_current,
                               const Vec<2>& sensor_position,
                               const LaserScanGeometry& g,
                               const MatchingOptions& o) {
  PointScores s;
  std::map<Id, bool> detectable;
  for (std::size_t i = 0; i < d.moving.size(); ++i) {
    const Id id = current_truth.hit_object[i];
    const bool valid = d.sets.current[i] != PointSet::kNone;
    const bool dynamic = valid && id != sylva::sim::kNoObject && world.isDynamic(id);
    const bool reported = d.moving[i] != 0;
    if (reported) {
      ++s.reported;
      if (dynamic) ++s.reported_on_moving;
    }
    if (!dynamic) continue;
    ++s.on_moving;
    if (reported) ++s.on_moving_found;
    auto it = detectable.find(id);
    if (it == detectable.end())
      it = detectable.emplace(id, movedDetectably(world, id, t_previous, t_current, sensor_position, g, o)).first;
    if (it->second) {
      ++s.detectable;
      if (reported) ++s.detectable_found;
    }
  }
  return s;
}

struct ObjectError {
  Id truth_id = sylva::sim::kNoObject;  ///< kNoObject: the object holds no moving readings
  double hull_error_m = 0.0;
  double box_error_m = 0.0;
};

/// The position error of each detected object (see the file comment).
inline std::vector<ObjectError> objectErrors(const Detection& d,
                                             const sylva::sim::LaserScan2D& current_truth,
                                             const sylva::sim::DynamicScene2D& world,
                                             double t_current) {
  std::vector<ObjectError> out;
  for (const DetectedObject& object : d.objects) {
    std::map<Id, int> votes;
    for (const int b : object.beams) {
      const Id id = current_truth.hit_object[static_cast<std::size_t>(b)];
      if (id != sylva::sim::kNoObject && world.isDynamic(id)) ++votes[id];
    }
    ObjectError e;
    int best = 0;
    for (const auto& [id, count] : votes)
      if (count > best) {
        best = count;
        e.truth_id = id;
      }
    if (e.truth_id != sylva::sim::kNoObject) {
      const Vec<2> truth = *world.objectPosition(e.truth_id, t_current);
      e.hull_error_m = (object.hull_centroid - truth).norm();
      e.box_error_m = (object.box.center() - truth).norm();
    }
    out.push_back(e);
  }
  return out;
}

}  // namespace moving_objects
