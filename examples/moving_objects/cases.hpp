#pragma once
// The five cases of Amarasinghe 2008, Sec. 4.3.4, as scripted scenes: a scanner standing at
// the origin looking along +x into a room (back wall 6 m ahead, side walls 5 m to each side)
// takes two scans dt = 0.2 s apart (the thesis' 5 Hz) while one object moves.
//
//   1 perfectly separated  a disc (r 15 cm) 3 m ahead moves 0.4 m sideways: more than its
//                          width, so its two positions do not overlap (Fig. 4.2);
//   2 partially separated  a disc (r 25 cm) moves 15 cm away and 15 cm sideways: part of it
//                          is now behind where it was (in O_C), part in front of the wall
//                          (in M_C) (Fig. 4.3);
//   3 moving away          a disc (r 20 cm) moves 20 cm straight away: all of it is behind
//                          where it was, M_C is empty and the object is in O_C (Fig. 4.4);
//   4 moving towards       the same disc moves 20 cm straight towards the scanner: all of it
//                          is in M_C;
//   5 lateral              a flat board 1.2 m wide facing the scanner slides 20 cm
//                          sideways: the overlap matches itself (A_C), only the leading
//                          20 cm are in M_C (Fig. 4.5).
//
// Each case says which object moves, so a detection can be scored against the truth the
// simulated scan records per beam. The same scenes serve the tests and the program.

#include <string>
#include <vector>

#include <sylva/core/types.hpp>
#include <sylva/sim/dynamic_scene_2d.hpp>
#include <sylva/sim/laser_scene_2d.hpp>

namespace moving_objects {

using namespace sylva::laser;  // the detector and its scans (include/sylva/laser)
using sylva::LaserScanGeometry;

using sylva::Id;
using sylva::Vec;

inline constexpr Id kRoomId = 1;

/// The room of the scripted cases: back wall at x = 6, side walls at y = +-5.
inline sylva::sim::LaserScene2D caseRoom() {
  sylva::sim::LaserScene2D room;
  room.addPolyline({Vec<2>(-1.0, 5.0), Vec<2>(6.0, 5.0), Vec<2>(6.0, -5.0), Vec<2>(-1.0, -5.0)}, false, kRoomId);
  return room;
}

struct ScriptedCase {
  int number = 0;        ///< 1..5, Sec. 4.3.4
  std::string name;      ///< short name
  std::string what;      ///< one sentence
  sylva::sim::DynamicScene2D world;
  Id moving_id = 0;      ///< the object that moves
  double dt_s = 0.2;     ///< previous scan at t = 0, current at t = dt
  Vec<3> previous_pose = Vec<3>::Zero();
  Vec<3> current_pose = Vec<3>::Zero();
};

inline std::vector<ScriptedCase> fiveCases() {
  using sylva::sim::RigidObject2D;
  constexpr Id kObject = 100;
  std::vector<ScriptedCase> cases;
  const auto add = [&](int number, std::string name, std::string what, RigidObject2D object) {
    ScriptedCase c;
    c.number = number;
    c.name = std::move(name);
    c.what = std::move(what);
    c.world = sylva::sim::DynamicScene2D(caseRoom());
    c.moving_id = object.object_id;
    c.world.addRigidObject(std::move(object));
    cases.push_back(std::move(c));
  };
  add(1, "perfectly separated", "a 30 cm disc 3 m ahead moves 0.4 m sideways",
      RigidObject2D::disc(kObject, 0.15, Vec<3>(3.0, 0.5, 0.0), Vec<3>(0.0, -2.0, 0.0)));
  add(2, "partially separated", "a 50 cm disc moves 15 cm away and 15 cm sideways",
      RigidObject2D::disc(kObject, 0.25, Vec<3>(3.0, 0.3, 0.0), Vec<3>(0.75, -0.75, 0.0)));
  add(3, "moving away", "a 40 cm disc 3 m ahead moves 20 cm straight away",
      RigidObject2D::disc(kObject, 0.20, Vec<3>(3.0, 0.0, 0.0), Vec<3>(1.0, 0.0, 0.0)));
  add(4, "moving towards", "a 40 cm disc 3 m ahead moves 20 cm straight towards the scanner",
      RigidObject2D::disc(kObject, 0.20, Vec<3>(3.0, 0.0, 0.0), Vec<3>(-1.0, 0.0, 0.0)));
  add(5, "lateral", "a 1.2 m board 3 m ahead slides 20 cm sideways",
      RigidObject2D::board(kObject, 1.2, Vec<3>(3.0, 0.3, 0.0), Vec<3>(0.0, -1.0, 0.0)));
  return cases;
}

}  // namespace moving_objects
