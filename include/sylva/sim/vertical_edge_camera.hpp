#pragma once
/// @file
/// `sim::VerticalEdgeCamera`: a forward-looking camera that detects vertical edges (door
/// frames, wall corners, pillar edges, poster borders) and reports what a vertical-line
/// detector would (multisensor thesis Sec. 3.3.1): the line's bearing and its vertical extent
/// in the image, as a `VerticalLineDetection` for `LaserCameraSensor`.
///
/// World. A `VerticalEdge` stands at a point of the world plane from height z_bottom to
/// z_top (m above the floor). An edge drawn on a wall (a poster, a flush door frame) is seen
/// only from the side its `facing` normal points to; a corner or a free edge has facing 0 and
/// is seen from everywhere. Walls are the segments and circles of a `LaserScene2D` taken as
/// floor-to-ceiling: they hide what is behind them.
///
/// Camera. At sensor pose [x, y, theta] (the optical axis along theta), `height_m` above the
/// floor, a pinhole of focal length f pixels with a w x h image centred on the axis. An
/// edge at horizontal distance d and bearing beta (counter-clockwise from the axis) is
/// detected when it is in front (depth x_c = d cos beta > 0), within `max_range_m`, not
/// hidden (the ray to it meets no wall before d - occlusion_tolerance), seen from its facing
/// side, inside the image horizontally, at least `min_length_px` long in the image after
/// clipping to the image height, and passes a Bernoulli draw of `detection_probability`.
///
/// Reported bearing. The lens and the mounting leave a systematic error d(beta) (what the
/// calibration of Sec. 3.3.2 removes) and the detector has pixel noise:
///
///   u = -f tan(beta + d(beta)) + sigma_px n,   n ~ N(0, 1)      (u: pixel column from the centre, right positive)
///   bearing_c = atan(-u / f),     d(beta) = d_0 + d_1 beta + d_2 beta^2 + d_3 beta^3
///
/// Vertical extent: y = (height - z) / x_c for the top and the bottom end (normalized
/// image rows, y down), clipped to the image, without noise.
///
/// Draws, per detected edge in the order of `edges`: one uniform (only when
/// detection_probability < 1), then one normal (only when sigma_px > 0). The truth (edge id,
/// true bearing, distance) is reported alongside for evaluation.
///
/// Errors: options out of range or non-finite -> kInvalidArgument at construction; a
/// non-finite pose -> kNonFinite.

#include <cmath>
#include <sstream>
#include <vector>

#include "sylva/core/angles.hpp"
#include "sylva/core/error.hpp"
#include "sylva/core/types.hpp"
#include "sylva/laser_camera/sensor.hpp"
#include "sylva/sim/laser_scene_2d.hpp"
#include "sylva/sim/random.hpp"

namespace sylva::sim {

/// A vertical edge of the world: position, height range, facing normal (zero: all round).
struct VerticalEdge {
  Vec<2> position;
  double z_bottom_m;
  double z_top_m;
  Vec<2> facing;
  Id id;
};

struct VerticalEdgeCameraOptions {
  double height_m = 0.59;          ///< optical centre above the floor
  double focal_px = 554.0;         ///< 640 px wide: 60 deg horizontal field of view
  double width_px = 640.0;
  double height_px = 480.0;
  double max_range_m = 8.0;        ///< edges farther away are not detected
  double sigma_px = 1.0;           ///< horizontal pixel noise of the line detector
  double min_length_px = 20.0;     ///< shortest detectable line (after clipping)
  double detection_probability = 1.0;
  double occlusion_tolerance_m = 0.02;
  double distortion[4] = {0.0, 0.0, 0.0, 0.0};  ///< d_0 .. d_3 of d(beta) (rad)
};

/// One detection and the truth behind it.
struct EdgeDetection {
  VerticalLineDetection line;
  Id edge_id;
  double true_bearing_rad;
  double true_distance_m;
};

class VerticalEdgeCamera {
 public:
  explicit VerticalEdgeCamera(const VerticalEdgeCameraOptions& options = {}) : options_(validated(options)) {}

  const VerticalEdgeCameraOptions& options() const { return options_; }
  /// Half of the horizontal field of view (rad).
  double halfFov() const { return std::atan(0.5 * options_.width_px / options_.focal_px); }

  /// d(beta), the systematic bearing error.
  double distortion(double beta) const {
    const double* d = options_.distortion;
    return d[0] + beta * (d[1] + beta * (d[2] + beta * d[3]));
  }

  /// The bearing the camera reports for a line at true bearing beta (one normal draw when
  /// sigma_px > 0).
  double reportedBearing(double beta, Rng& rng) const {
    double u = -options_.focal_px * std::tan(beta + distortion(beta));
    if (options_.sigma_px > 0.0) u += options_.sigma_px * rng.normal();
    return std::atan(-u / options_.focal_px);
  }

  /// Detections of `edges` from `pose`, walls of `walls` hiding what is behind them.
  void observe(const Vec<3>& pose,
               const std::vector<VerticalEdge>& edges,
               const LaserScene2D& walls,
               Rng& rng,
               std::vector<EdgeDetection>& out) const {
    if (!pose.allFinite()) fail(ErrorCode::kNonFinite, "VerticalEdgeCamera::observe: the pose is not finite");
    out.clear();
    const Vec<2> origin = pose.head<2>();
    const double half_w = 0.5 * options_.width_px / options_.focal_px;
    const double half_h = 0.5 * options_.height_px / options_.focal_px;
    for (const VerticalEdge& e : edges) {
      const Vec<2> delta = e.position - origin;
      const double distance = delta.norm();
      if (!(distance > 1e-6) || distance > options_.max_range_m) continue;
      const double beta = wrapAngle(std::atan2(delta.y(), delta.x()) - pose[2]);
      const double depth = distance * std::cos(beta);
      if (!(depth > 0.0)) continue;
      if (std::abs(std::tan(beta + distortion(beta))) > half_w) continue;
      if (e.facing.squaredNorm() > 0.0 && !(e.facing.dot(-delta) > 0.0)) continue;
      const RayHit hit = walls.castRay(origin, delta / distance, distance - options_.occlusion_tolerance_m);
      if (hit.object_id != kNoObject) continue;
      const double top = std::max(-half_h, (options_.height_m - e.z_top_m) / depth);
      const double bottom = std::min(half_h, (options_.height_m - e.z_bottom_m) / depth);
      if ((bottom - top) * options_.focal_px < options_.min_length_px) continue;
      if (options_.detection_probability < 1.0 && !(rng.uniform01() < options_.detection_probability)) continue;
      const double bearing = reportedBearing(beta, rng);
      out.push_back(EdgeDetection{VerticalLineDetection{bearing, top, bottom}, e.id, beta, distance});
    }
  }

 private:
  static VerticalEdgeCameraOptions validated(const VerticalEdgeCameraOptions& o) {
    std::ostringstream os;
    const bool finite = std::isfinite(o.height_m) && std::isfinite(o.focal_px) && std::isfinite(o.width_px) &&
                        std::isfinite(o.height_px) && std::isfinite(o.max_range_m) && std::isfinite(o.sigma_px) &&
                        std::isfinite(o.min_length_px) && std::isfinite(o.detection_probability) &&
                        std::isfinite(o.occlusion_tolerance_m) && std::isfinite(o.distortion[0]) &&
                        std::isfinite(o.distortion[1]) && std::isfinite(o.distortion[2]) &&
                        std::isfinite(o.distortion[3]);
    if (!finite) {
      os << "VerticalEdgeCamera: every option must be finite";
    } else if (!(o.focal_px > 0.0) || !(o.width_px > 0.0) || !(o.height_px > 0.0) || !(o.max_range_m > 0.0)) {
      os << "VerticalEdgeCamera: focal length, image size and range must be > 0";
    } else if (!(o.sigma_px >= 0.0) || !(o.min_length_px >= 0.0) || !(o.occlusion_tolerance_m >= 0.0)) {
      os << "VerticalEdgeCamera: sigma_px, min_length_px and occlusion_tolerance_m must be >= 0";
    } else if (!(o.detection_probability >= 0.0) || !(o.detection_probability <= 1.0)) {
      os << "VerticalEdgeCamera: detection_probability must be in [0, 1], got " << o.detection_probability;
    } else {
      return o;
    }
    fail(ErrorCode::kInvalidArgument, os.str());
  }

  VerticalEdgeCameraOptions options_;
};

}  // namespace sylva::sim
