#pragma once
// The simulated worlds of the moving_objects program.
//
// Default dynamic scene (like the thesis' Fig. 4.9 and 4.10): a 12.5 m x 10 m room with
// pillars and a cabinet; a robot drives slowly into it (0.125 m/s) while three people walk
// (one crossing 1.7-3.2 m in front of it, one about 7 m away, one walking diagonally away and
// back) and a cart rolls sideways at 0.75 m/s, about the minimum detectable speed of eq. 4.5
// at its 4-6 m range. Scans at 5 Hz (dt = 0.2 s, as in Sec. 4.4.2), 12 s.
// The seed only changes where along their routes the people start.
//
// SLAM scene: a robot drives 1.2 laps of a 40 m loop (rounded rectangle about 13 m x 6.7 m)
// at 0.5 m/s in a hall with walls, among `poles` thin poles (radius 5-12 cm, 1-6 m from the
// path, at least 2 m apart): the map's landmarks. `people` people walk back and forth on
// 4-8 m routes that cross the robot's path at random places and angles, at 0.9-1.4 m/s.
// Their legs (radius 6 cm) look just like poles to a point-feature extractor.

#include <cmath>
#include <cstdint>
#include <vector>

#include <sylva/core/types.hpp>
#include <sylva/sim/dynamic_scene_2d.hpp>
#include <sylva/sim/landmarks_2d.hpp>
#include <sylva/sim/laser_scene_2d.hpp>
#include <sylva/sim/loop_trajectory_2d.hpp>
#include <sylva/sim/random.hpp>
#include <sylva/sim/walking_person_2d.hpp>

namespace moving_objects {

using namespace sylva::laser;  // the detector and its scans (include/sylva/laser)
using sylva::LaserScanGeometry;

using sylva::Id;
using sylva::Vec;

inline constexpr Id kWallId = 1;
inline constexpr Id kFirstPoleId = 1000;
inline constexpr Id kFirstLegId = 5000;  // person p has legs kFirstLegId + 2p and + 2p + 1
inline constexpr Id kCartId = 9000;

inline bool isLegId(Id id) { return id >= kFirstLegId && id < kCartId; }
inline Id personOfLeg(Id id) { return (id - kFirstLegId) / 2; }

struct DefaultScene {
  sylva::sim::DynamicScene2D world;
  std::vector<Vec<3>> robot_poses;  ///< sensor pose at each scan
  std::vector<double> times;        ///< time of each scan
  double dt_s = 0.2;
  std::vector<std::vector<Vec<2>>> walls;  ///< polylines, for drawing
};

inline DefaultScene makeDefaultScene(std::uint64_t seed, int scans = 61) {
  using sylva::sim::WalkingPerson2D;
  using sylva::sim::WalkingPerson2DOptions;
  DefaultScene s;
  sylva::sim::LaserScene2D room;
  const std::vector<Vec<2>> outline{Vec<2>(-1.5, -5.0), Vec<2>(11.0, -5.0), Vec<2>(11.0, 5.0), Vec<2>(-1.5, 5.0)};
  room.addPolyline(outline, true, kWallId);
  s.walls.push_back(outline);
  s.walls.back().push_back(outline.front());
  const std::vector<Vec<2>> cabinet{Vec<2>(8.3, 3.4), Vec<2>(9.5, 3.4), Vec<2>(9.5, 4.1), Vec<2>(8.3, 4.1)};
  room.addPolyline(cabinet, true, kWallId + 1);
  s.walls.push_back(cabinet);
  s.walls.back().push_back(cabinet.front());
  const Vec<3> pillars[] = {Vec<3>(5.0, -2.6, 0.15), Vec<3>(6.3, 2.2, 0.12), Vec<3>(9.6, -1.2, 0.2),
                            Vec<3>(2.2, 4.0, 0.1), Vec<3>(1.5, -3.8, 0.1)};
  Id id = kFirstPoleId;
  for (const Vec<3>& p : pillars) room.addCircle(p.head<2>(), p[2], id++);
  s.world = sylva::sim::DynamicScene2D(room);

  sylva::sim::Rng rng(sylva::sim::deriveSeed(seed, 100));
  struct Route {
    Vec<2> a, b;
    double speed;
  };
  const Route routes[] = {{Vec<2>(3.2, -3.6), Vec<2>(3.2, 3.6), 1.1},   // crossing, near
                          {Vec<2>(7.4, -4.0), Vec<2>(7.4, 2.8), 1.3},   // crossing, far
                          {Vec<2>(2.4, 2.6), Vec<2>(9.8, 0.2), 0.9}};   // away and back
  for (std::size_t p = 0; p < 3; ++p) {
    WalkingPerson2DOptions o;
    o.waypoints = {routes[p].a, routes[p].b};
    o.speed_mps = routes[p].speed;
    o.start_distance_m = rng.uniform(0.0, 2.0 * (routes[p].b - routes[p].a).norm());
    s.world.addPerson(WalkingPerson2D(o, kFirstLegId + 2 * static_cast<Id>(p), kFirstLegId + 2 * static_cast<Id>(p) + 1));
  }
  s.world.addRigidObject(sylva::sim::RigidObject2D::box(kCartId, 0.6, 0.45, Vec<3>(5.6, -4.4, 0.0), Vec<3>(0.0, 0.75, 0.0)));

  for (int k = 0; k < scans; ++k) {
    const double t = k * s.dt_s;
    s.times.push_back(t);
    s.robot_poses.push_back(Vec<3>(0.125 * t, 0.0, 0.0));
  }
  return s;
}

struct SlamSceneOptions {
  int poles = 40;
  int people = 6;
  double perimeter_m = 40.0;
  double speed_mps = 0.5;
  double dt_s = 0.2;
  double laps = 1.2;
  double sigma_v_mps = 0.05;
  double sigma_omega_radps = 1.0 * sylva::kRadPerDeg;
};

struct SlamScene {
  sylva::sim::LoopTrajectory2D trajectory;
  sylva::sim::DynamicScene2D world;
  std::vector<sylva::sim::TrueLandmark2D> poles;  ///< ids kFirstPoleId + i
  std::vector<double> pole_radii;
  std::vector<std::vector<Vec<2>>> walls;
  std::vector<std::pair<Vec<2>, Vec<2>>> person_routes;
  int steps = 0;
};

inline SlamScene makeSlamScene(const SlamSceneOptions& o, std::uint64_t seed) {
  using sylva::sim::WalkingPerson2D;
  using sylva::sim::WalkingPerson2DOptions;
  sylva::sim::LoopTrajectory2DOptions t;
  t.perimeter_m = o.perimeter_m;
  t.corner_radius_m = 2.5;
  t.speed_mps = o.speed_mps;
  t.dt_s = o.dt_s;
  t.sigma_v_mps = o.sigma_v_mps;
  t.sigma_omega_radps = o.sigma_omega_radps;
  SlamScene s{sylva::sim::LoopTrajectory2D(t), {}, {}, {}, {}, {}, 0};
  s.steps = static_cast<int>(std::lround(o.laps * s.trajectory.stepsPerLap()));

  sylva::sim::Rng rng(sylva::sim::deriveSeed(seed, 200));
  sylva::sim::LandmarkField2DOptions field;
  field.count = o.poles;
  field.band_min_m = 1.0;
  field.band_max_m = 6.0;
  field.min_separation_m = 2.0;
  auto poles = sylva::sim::landmarksAlongPath(s.trajectory.path(), field, rng);

  const auto& path = s.trajectory.path();
  const double half_length = 0.5 * path.length();
  const double margin = 7.5;
  const std::vector<Vec<2>> hall{Vec<2>(-half_length - margin, -margin), Vec<2>(half_length + margin, -margin),
                                 Vec<2>(half_length + margin, path.width() + margin),
                                 Vec<2>(-half_length - margin, path.width() + margin)};
  sylva::sim::LaserScene2D statics;
  statics.addPolyline(hall, true, kWallId);
  s.walls.push_back(hall);
  s.walls.back().push_back(hall.front());
  for (std::size_t i = 0; i < poles.size(); ++i) {
    const double radius = rng.uniform(0.05, 0.12);
    const Id id = kFirstPoleId + static_cast<Id>(i);
    statics.addCircle(poles[i].position, radius, id);
    s.poles.push_back({id, poles[i].position});
    s.pole_radii.push_back(radius);
  }
  s.world = sylva::sim::DynamicScene2D(statics);

  for (int p = 0; p < o.people; ++p) {
    const double at = rng.uniform(0.0, path.perimeter());
    const Vec<2> centre = path.position(at);
    const double angle = path.heading(at) + sylva::kPi / 2.0 + rng.uniform(-0.8, 0.8);
    const Vec<2> direction(std::cos(angle), std::sin(angle));
    const double before = rng.uniform(2.0, 4.0), after = rng.uniform(2.0, 4.0);
    WalkingPerson2DOptions w;
    w.waypoints = {centre - before * direction, centre + after * direction};
    w.speed_mps = rng.uniform(0.9, 1.4);
    w.step_length_m = 0.55 + 0.1 * w.speed_mps;
    w.start_distance_m = rng.uniform(0.0, 2.0 * (before + after));
    s.world.addPerson(WalkingPerson2D(w, kFirstLegId + 2 * p, kFirstLegId + 2 * p + 1));
    s.person_routes.emplace_back(w.waypoints[0], w.waypoints[1]);
  }
  return s;
}

}  // namespace moving_objects
