#pragma once
// The simulated indoor world of the laser_camera_slam example (multisensor thesis Sec. 3.5:
// office corridors driven around a loop). A corridor of width 2 * half_width runs around a
// rounded-rectangle loop path (sim::LoopPath2D): the outer wall is the path's bounding box
// grown by half_width, the inner wall (a block of offices) the box shrunk by half_width, so
// the robot drives along the corridor's centre line. Along both walls, every `spacing_m`,
// one feature after a fixed pattern:
//
//   door    a flush door frame: two vertical edges on the wall, floor to 2.1 m, seen only
//           from the corridor. The wall stays flat: invisible to the laser, the thesis'
//           case for the camera (its Fig. 3.3: corridors without direction-invariant
//           laser features);
//   poster  two vertical edges from 1.2 m to 1.9 m: above the laser plane (0.40 m), so the
//           laser-camera sensor must reject them (they do not cross the laser plane);
//   pillar  a 0.4 m x 0.3 m pillar protruding from the wall: four corners the laser can see
//           (two concave at the wall, two convex), each a floor-to-ceiling vertical edge;
//   blank   nothing.
//
// Every corner of both walls is a floor-to-ceiling edge too. The world is fixed (no random
// draws): `--seed` changes the noise, not the building.

#include <cmath>
#include <utility>
#include <vector>

#include <sylva/core/types.hpp>
#include <sylva/sim/laser_scene_2d.hpp>
#include <sylva/sim/loop_path_2d.hpp>
#include <sylva/sim/vertical_edge_camera.hpp>

namespace laser_camera_slam {

using sylva::Id;
using sylva::Vec;

struct IndoorWorldOptions {
  double half_width_m = 1.5;    ///< corridor half width
  double spacing_m = 2.0;       ///< distance between feature slots along a wall
  double end_margin_m = 1.2;    ///< no feature closer than this to a wall corner
  double ceiling_m = 2.6;
  double door_width_m = 0.9;
  double door_height_m = 2.1;
  double poster_width_m = 0.6;
  double poster_bottom_m = 1.2;
  double poster_top_m = 1.9;
  double pillar_width_m = 0.4;
  double pillar_depth_m = 0.3;
};

enum class Feature { kDoor, kPoster, kPillar, kBlank };

struct IndoorWorld {
  sylva::sim::LaserScene2D walls;
  std::vector<sylva::sim::VerticalEdge> edges;
  int doors = 0, posters = 0, pillars = 0;
};

namespace detail {

/// Builds one closed wall (a rectangle, counter-clockwise corners) with its features; `into`
/// is the unit normal of each side pointing into the corridor, `pattern_offset` shifts the
/// feature pattern so the two walls differ.
inline void addWall(IndoorWorld& world,
                    const std::vector<Vec<2>>& corners,
                    bool normal_left,
                    int pattern_offset,
                    Id wall_id,
                    const IndoorWorldOptions& o) {
  static const Feature kPattern[] = {Feature::kDoor,  Feature::kPillar, Feature::kPoster, Feature::kDoor,
                                     Feature::kBlank, Feature::kDoor,   Feature::kPillar, Feature::kPoster};
  constexpr int kPatternSize = 8;
  auto edge = [&](const Vec<2>& p, double z0, double z1, const Vec<2>& facing) {
    world.edges.push_back({p, z0, z1, facing, static_cast<Id>(world.edges.size())});
  };
  std::vector<Vec<2>> outline;
  int slot = pattern_offset;
  for (std::size_t k = 0; k < corners.size(); ++k) {
    const Vec<2>& a = corners[k];
    const Vec<2>& b = corners[(k + 1) % corners.size()];
    const double length = (b - a).norm();
    const Vec<2> t = (b - a) / length;
    const Vec<2> n = normal_left ? Vec<2>(-t.y(), t.x()) : Vec<2>(t.y(), -t.x());
    outline.push_back(a);
    edge(a, 0.0, o.ceiling_m, Vec<2>::Zero());
    const int slots = static_cast<int>(std::floor((length - 2.0 * o.end_margin_m) / o.spacing_m)) + 1;
    const double first = 0.5 * (length - (slots - 1) * o.spacing_m);
    for (int i = 0; i < slots; ++i, ++slot) {
      const double s = first + i * o.spacing_m;
      const Feature f = kPattern[slot % kPatternSize];
      if (f == Feature::kDoor) {
        edge(a + (s - 0.5 * o.door_width_m) * t, 0.0, o.door_height_m, n);
        edge(a + (s + 0.5 * o.door_width_m) * t, 0.0, o.door_height_m, n);
        ++world.doors;
      } else if (f == Feature::kPoster) {
        edge(a + (s - 0.5 * o.poster_width_m) * t, o.poster_bottom_m, o.poster_top_m, n);
        edge(a + (s + 0.5 * o.poster_width_m) * t, o.poster_bottom_m, o.poster_top_m, n);
        ++world.posters;
      } else if (f == Feature::kPillar) {
        const Vec<2> p0 = a + (s - 0.5 * o.pillar_width_m) * t;
        const Vec<2> p1 = p0 + o.pillar_depth_m * n;
        const Vec<2> p3 = a + (s + 0.5 * o.pillar_width_m) * t;
        const Vec<2> p2 = p3 + o.pillar_depth_m * n;
        for (const Vec<2>& p : {p0, p1, p2, p3}) {
          outline.push_back(p);
          edge(p, 0.0, o.ceiling_m, Vec<2>::Zero());
        }
        ++world.pillars;
      }
    }
  }
  world.walls.addPolyline(outline, true, wall_id);
}

}  // namespace detail

/// The corridor around `path` (see the file comment).
inline IndoorWorld makeIndoorWorld(const sylva::sim::LoopPath2D& path, const IndoorWorldOptions& o = {}) {
  IndoorWorld world;
  const double x0 = -0.5 * path.length(), x1 = 0.5 * path.length();
  const double y0 = 0.0, y1 = path.width();
  const double w = o.half_width_m;
  // Counter-clockwise rectangles; the corridor lies outside the inner one (normal to the
  // right of a counter-clockwise side) and inside the outer one (normal to the left).
  detail::addWall(world, {Vec<2>(x0 - w, y0 - w), Vec<2>(x1 + w, y0 - w), Vec<2>(x1 + w, y1 + w), Vec<2>(x0 - w, y1 + w)},
                  true, 0, 1, o);
  detail::addWall(world, {Vec<2>(x0 + w, y0 + w), Vec<2>(x1 - w, y0 + w), Vec<2>(x1 - w, y1 - w), Vec<2>(x0 + w, y1 - w)},
                  false, 3, 2, o);
  return world;
}

}  // namespace laser_camera_slam
