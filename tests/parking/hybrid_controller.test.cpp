// The hybrid parking controller on hand-made frames: every FSM transition (eps1..eps5 and
// station lost), the control laws' signs, eq. 5.1 and 5.9, and the refusal of bad frames and
// nonsense parameters.
#include "sylva_catch.hpp"

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "error_helpers.hpp"
#include <sylva/parking/hybrid_controller.hpp>

namespace unity_parking_controller {

using sylva::parking::Command;
using sylva::parking::ControllerParams;
using sylva::parking::Event;
using sylva::parking::HybridController;
using sylva::parking::State;
using sylva::ErrorCode;
using sylva_test::throwsCode;

/// Default parameters, but Start decides on one frame (as printed in Algorithm 5).
ControllerParams oneFrameStart() {
  ControllerParams p;
  p.start_exit_frames = 1;
  return p;
}

/// A station centred on P2's reference, with halves f1 and f2.
std::vector<double> centred(double f1, double f2) { return {695.0 - f1, 695.0, 695.0 + f2}; }

/// A controller brought into Reverse (the first frame shows the station too large).
HybridController inReverse(ControllerParams p = oneFrameStart()) {
  HybridController c(p);
  const Command cmd = c.step(centred(260.0, 260.0));
  REQUIRE(cmd.event == Event::kEps2);
  REQUIRE(c.state() == State::kReverse);
  return c;
}

bool throwsWithText(const ControllerParams& p, ErrorCode code, const std::string& text) {
  try {
    p.validate();
  } catch (const sylva::Error& e) {
    return e.code() == code && std::string(e.what()).find(text) != std::string::npos;
  }
  return false;
}

}  // namespace unity_parking_controller

using namespace unity_parking_controller;

TEST_CASE("parking controller: Start turns on the spot towards P2's reference", "[parking]") {
  const ControllerParams p = oneFrameStart();
  HybridController c(p);
  // P2 25 px right of its reference: turn clockwise (omega < 0) to move it left.
  Command cmd = c.step({500.0, 720.0, 930.0});
  CHECK(cmd.state == State::kStart);
  CHECK(cmd.event == Event::kNone);
  CHECK(cmd.v_mps == 0.0);
  CHECK(cmd.omega_radps == Approx(-p.k1_radps_per_px * 25.0));
  cmd = c.step({460.0, 670.0, 880.0});
  CHECK(cmd.omega_radps == Approx(p.k1_radps_per_px * 25.0));
  CHECK(c.transitions().empty());
}

TEST_CASE("parking controller: Start leaves with eps1 to Forward when the station looks small",
          "[parking]") {
  const ControllerParams p = oneFrameStart();
  HybridController c(p);
  const Command cmd = c.step(centred(100.0, 100.0));  // A = 200 < A^r = 432
  CHECK(cmd.event == Event::kEps1);
  CHECK(cmd.state == State::kForward);
  CHECK(cmd.v_mps == p.v_forward_mps);
  REQUIRE(c.transitions().size() == 1);
  CHECK(c.transitions()[0].from == State::kStart);
  CHECK(c.transitions()[0].to == State::kForward);
  CHECK(c.transitions()[0].frame == 0);
  CHECK(c.forwardMoves() == 1);
}

TEST_CASE("parking controller: Start leaves with eps2 to Reverse when the station looks large",
          "[parking]") {
  const ControllerParams p = oneFrameStart();
  HybridController c(p);
  const Command cmd = c.step(centred(250.0, 250.0));  // A = 500, E_A = 68 > 25: full speed
  CHECK(cmd.event == Event::kEps2);
  CHECK(cmd.state == State::kReverse);
  CHECK(cmd.v_mps == -p.v_reverse_mps);
  CHECK(c.reverseMoves() == 1);
}

TEST_CASE("parking controller: Start is not left while P2 is off its reference", "[parking]") {
  HybridController c(oneFrameStart());
  CHECK(c.step({595.0, 697.0, 795.0}).event == Event::kNone);  // |e2| = 2 > 1.5
  CHECK(c.step({594.0, 696.4, 795.0}).event == Event::kEps1);  // |e2| = 1.4
}

TEST_CASE("parking controller: Start averages its exit measurement over start_exit_frames",
          "[parking]") {
  ControllerParams p;
  p.start_exit_frames = 5;
  HybridController c(p);
  CHECK(c.step({500.0, 720.0, 930.0}).event == Event::kNone);  // not aligned: does not count
  for (int i = 0; i < 4; ++i) CHECK(c.step(centred(100.0, 110.0)).event == Event::kNone);
  // The fifth aligned frame ends Start; the side comes from the mean asymmetry (f1 < f2:
  // the robot is on P3's side), even though this last frame alone points the other way.
  CHECK(c.step(centred(110.0, 100.0)).event == Event::kEps1);
  CHECK(c.holdsRightFeature());
  CHECK(c.lastAsymmetryPx() < 0.0);
}

TEST_CASE("parking controller: Forward holds the far outer feature on the virtual edge",
          "[parking]") {
  const ControllerParams p = oneFrameStart();
  const double W = p.image_width_px;
  SECTION("robot on P3's side (f1 < f2): P3 held at W - c, turning left") {
    HybridController c(p);
    c.step(centred(95.0, 105.0));
    REQUIRE(c.state() == State::kForward);
    CHECK(c.holdsRightFeature());
    const double cv = c.virtualEdgePx();
    const Command cmd = c.step(centred(95.0, 105.0));
    CHECK(cmd.v_mps == p.v_forward_mps);
    CHECK(cmd.omega_radps == Approx(p.k2_radps_per_px * (W - cv - 800.0)));
    CHECK(cmd.omega_radps > 0.0);
  }
  SECTION("robot on P1's side (f1 > f2): P1 held at c, turning right") {
    HybridController c(p);
    c.step(centred(105.0, 95.0));
    REQUIRE(c.state() == State::kForward);
    CHECK_FALSE(c.holdsRightFeature());
    const double cv = c.virtualEdgePx();
    const Command cmd = c.step(centred(105.0, 95.0));
    CHECK(cmd.omega_radps == Approx(-p.k2_radps_per_px * (590.0 - cv)));
    CHECK(cmd.omega_radps < 0.0);
  }
}

TEST_CASE(
    "parking controller: Forward ends with eps4 when the uncontrolled feature reaches its "
    "virtual edge",
    "[parking]") {
  ControllerParams p = oneFrameStart();
  p.adapt_c = false;
  p.c_static_px = 400.0;
  p.exit_on_width = false;  // the thesis' test alone
  SECTION("holding P3: ends on u1 <= c") {
    HybridController c(p);
    c.step(centred(95.0, 105.0));
    REQUIRE(c.holdsRightFeature());
    CHECK(c.step({401.0, 700.0, 990.0}).event == Event::kNone);
    const Command cmd = c.step({400.0, 700.0, 992.0});
    CHECK(cmd.event == Event::kEps4);
    CHECK(cmd.state == State::kStart);
    CHECK(cmd.v_mps == 0.0);
  }
  SECTION("holding P1: ends on W - u3 <= c") {
    HybridController c(p);
    c.step(centred(105.0, 95.0));
    REQUIRE_FALSE(c.holdsRightFeature());
    CHECK(c.step({400.0, 690.0, 991.0}).event == Event::kNone);
    CHECK(c.step({400.0, 690.0, 992.0}).event == Event::kEps4);
  }
}

TEST_CASE("parking controller: Forward also ends when the station is wider than W - 2c",
          "[parking]") {
  ControllerParams p = oneFrameStart();
  p.adapt_c = false;
  p.c_static_px = 400.0;  // virtual window W - 2c = 592 px
  // Holding P3, the turn lags: P3 has slipped past its edge (u3 = 1050 > 992) while P1 is
  // still 50 px inside its own. The thesis' test waits; the width test ends the move.
  const std::vector<double> frame{450.0, 740.0, 1050.0};  // A = 600
  p.exit_on_width = false;
  HybridController thesis(p);
  thesis.step(centred(95.0, 105.0));
  CHECK(thesis.step(frame).event == Event::kNone);
  p.exit_on_width = true;
  HybridController ours(p);
  ours.step(centred(95.0, 105.0));
  CHECK(ours.step(frame).event == Event::kEps4);
}

TEST_CASE("parking controller: Reverse backs straight out, slower near the goal", "[parking]") {
  const ControllerParams p = oneFrameStart();
  HybridController c = inReverse(p);
  Command cmd = c.step({430.0, 697.0, 950.0});  // E_A = 88: far from the goal
  CHECK(cmd.v_mps == -p.v_reverse_mps);
  CHECK(cmd.omega_radps == Approx(-p.k1_radps_per_px * 2.0));
  cmd = c.step({472.0, 695.0, 916.0});  // E_A = 12, symmetric like the reference
  CHECK(cmd.state == State::kReverse);
  CHECK(cmd.v_mps == -p.v_reverse_slow_mps);
  cmd = c.step({462.0, 695.0, 926.0});  // E_A = 32: back to full speed
  CHECK(cmd.v_mps == -p.v_reverse_mps);
}

TEST_CASE("parking controller: Reverse stops with eps3 on the parking condition (eq. 5.1)",
          "[parking]") {
  HybridController c = inReverse();
  const Command cmd = c.step({478.5, 695.5, 909.2});
  CHECK(cmd.event == Event::kEps3);
  CHECK(cmd.state == State::kStop);
  CHECK(cmd.v_mps == 0.0);
  CHECK(cmd.omega_radps == 0.0);
  CHECK(c.isTerminal());
  // Stop is terminal: later frames, even empty ones, change nothing.
  const auto transitions = c.transitions().size();
  for (const std::vector<double>& frame :
       {std::vector<double>{}, std::vector<double>{100.0, 700.0, 1200.0}}) {
    const Command later = c.step(frame);
    CHECK(later.state == State::kStop);
    CHECK(later.v_mps == 0.0);
    CHECK(later.omega_radps == 0.0);
  }
  CHECK(c.transitions().size() == transitions);
}

TEST_CASE("parking controller: Reverse hands over to Forward with eps5 below A_min", "[parking]") {
  const ControllerParams p = oneFrameStart();
  HybridController c = inReverse(p);
  CHECK(c.step(centred(131.0, 131.0)).event == Event::kNone);  // A = 262 > A_min = 260
  const Command cmd = c.step(centred(129.0, 129.0));           // A = 258
  CHECK(cmd.event == Event::kEps5);
  CHECK(cmd.state == State::kForward);
  CHECK(cmd.v_mps == p.v_forward_mps);
  CHECK(c.forwardMoves() == 1);
  CHECK(c.reverseMoves() == 1);
}

TEST_CASE("parking controller: the parking condition is strict and checks every feature",
          "[parking]") {
  const HybridController c(oneFrameStart());
  sylva::parking::StationImage image;
  image.u = {478.0, 695.0, 910.0};
  CHECK(c.parked(image));
  image.u = {479.49, 695.0, 911.49};
  CHECK(c.parked(image));
  image.u = {479.5, 695.0, 911.5};  // |e1| = |e3| = 1.5: not < delta_u
  CHECK_FALSE(c.parked(image));
  image.u = {478.0, 696.5, 910.0};  // only e2 off
  CHECK_FALSE(c.parked(image));
  image.u = {477.2, 695.0, 910.8};  // every |e_i| < 1.5 but |E_A| = 1.6
  CHECK_FALSE(c.parked(image));
}

TEST_CASE("parking controller: parked_frames asks for the condition on consecutive frames",
          "[parking]") {
  ControllerParams p = oneFrameStart();
  p.parked_frames = 2;
  HybridController c = inReverse(p);
  const std::vector<double> goal{478.0, 695.0, 910.0};
  CHECK(c.step(goal).event == Event::kNone);
  CHECK(c.step({470.0, 695.0, 918.0}).event == Event::kNone);  // the streak breaks
  CHECK(c.step(goal).event == Event::kNone);
  CHECK(c.step(goal).event == Event::kEps3);
}

TEST_CASE("parking controller: eq. 5.9, c falls linearly with the asymmetry, clamped",
          "[parking]") {
  ControllerParams p;
  p.c_gain = 12.0;
  const HybridController c(p);
  CHECK(c.virtualEdge(0.0) == p.c_max_px);
  CHECK(c.virtualEdge(5.0) == Approx(p.c_max_px - 60.0));
  CHECK(c.virtualEdge(-5.0) == Approx(p.c_max_px - 60.0));
  CHECK(c.virtualEdge(1000.0) == p.c_min_px);
  p.adapt_c = false;
  p.c_static_px = 300.0;
  CHECK(HybridController(p).virtualEdge(5.0) == 300.0);
}

TEST_CASE("parking controller: the asymmetry, raw or scaled to the reference", "[parking]") {
  ControllerParams p;
  sylva::parking::StationImage reference;
  reference.u = {478.0, 695.0, 910.0};
  sylva::parking::StationImage twice;  // the reference at twice the size (half the distance)
  twice.u = {695.0 - 434.0, 695.0, 695.0 + 430.0};
  sylva::parking::StationImage far;  // smaller than A_min: scaled as if A = A_min
  far.u = {695.0 - 60.0, 695.0, 695.0 + 58.0};
  const HybridController scaled(p);
  CHECK(scaled.asymmetry(reference) == Approx(0.0).margin(1e-12));
  CHECK(scaled.asymmetry(twice) == Approx(4.0 * 0.25 - 2.0));
  CHECK(scaled.asymmetry(far) == Approx(2.0 * (432.0 / 260.0) * (432.0 / 260.0) - 2.0));
  p.scaled_asymmetry = false;
  const HybridController raw(p);
  CHECK(raw.asymmetry(reference) == 2.0);
  CHECK(raw.asymmetry(twice) == 4.0);
}

TEST_CASE("parking controller: detections in any order are sorted left to right", "[parking]") {
  HybridController a(oneFrameStart());
  HybridController b(oneFrameStart());
  const Command ca = a.step({595.0, 695.0, 795.0});
  const Command cb = b.step({795.0, 595.0, 695.0});
  CHECK(ca.event == cb.event);
  CHECK(ca.omega_radps == cb.omega_radps);
  CHECK(ca.v_mps == cb.v_mps);
}

TEST_CASE("parking controller: the turn rate is limited to max_omega", "[parking]") {
  ControllerParams p = oneFrameStart();
  p.max_omega_radps = 0.3;
  HybridController c(p);
  CHECK(c.step({1000.0, 1200.0, 1380.0}).omega_radps == -0.3);
  CHECK(c.step({10.0, 100.0, 300.0}).omega_radps == 0.3);
}

TEST_CASE("parking controller: a frame with fewer than three features means station lost",
          "[parking]") {
  for (const std::vector<double>& frame :
       {std::vector<double>{}, std::vector<double>{600.0}, std::vector<double>{600.0, 800.0}}) {
    HybridController c(oneFrameStart());
    c.step(centred(100.0, 100.0));  // in Forward, moving
    const Command cmd = c.step(frame);
    CHECK(cmd.event == Event::kStationLost);
    CHECK(cmd.state == State::kLost);
    CHECK(cmd.v_mps == 0.0);
    CHECK(cmd.omega_radps == 0.0);
    CHECK(c.isTerminal());
    CHECK(c.transitions().back().to == State::kLost);
    // Lost is terminal: the station coming back does not restart the task on its own.
    CHECK(c.step(centred(100.0, 100.0)).state == State::kLost);
    c.reset();
    CHECK(c.state() == State::kStart);
    CHECK(c.transitions().empty());
    CHECK(c.frames() == 0);
  }
}

TEST_CASE("parking controller: malformed frames throw and leave the controller as it was",
          "[parking]") {
  HybridController c(oneFrameStart());
  c.step(centred(100.0, 100.0));
  REQUIRE(c.state() == State::kForward);
  const long frames = c.frames();
  const double edge = c.virtualEdgePx();
  const double inf = std::numeric_limits<double>::infinity();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  CHECK(throwsCode([&] { c.step({500.0, 600.0, 700.0, 800.0}); }, ErrorCode::kInvalidArgument));
  CHECK(throwsCode([&] { c.step({500.0, 700.0, 700.0}); }, ErrorCode::kInvalidArgument));
  CHECK(throwsCode([&] { c.step({500.0, 700.0, 700.5}); }, ErrorCode::kInvalidArgument));
  CHECK(throwsCode([&] { c.step({500.0, nan, 800.0}); }, ErrorCode::kNonFinite));
  CHECK(throwsCode([&] { c.step({500.0, 700.0, inf}); }, ErrorCode::kNonFinite));
  CHECK(throwsCode([&] { c.step({-1.0, 700.0, 800.0}); }, ErrorCode::kInvalidArgument));
  CHECK(throwsCode([&] { c.step({500.0, 700.0, 1392.5}); }, ErrorCode::kInvalidArgument));
  CHECK(throwsCode([&] { c.step({500.0, 500.0}); }, ErrorCode::kInvalidArgument));
  CHECK(c.state() == State::kForward);
  CHECK(c.frames() == frames);
  CHECK(c.virtualEdgePx() == edge);
  CHECK(c.transitions().size() == 1);
  try {
    c.step({500.0, 600.0, 700.0, 800.0});
  } catch (const sylva::Error& e) {
    CHECK(std::string(e.what()).find("4 features") != std::string::npos);
  }
  try {
    c.step({500.0, 700.0, 700.0});
  } catch (const sylva::Error& e) {
    CHECK(std::string(e.what()).find("duplicated feature") != std::string::npos);
  }
  CHECK(c.step(centred(100.0, 100.0)).state == State::kForward);  // still usable
}

TEST_CASE("parking controller: nonsense parameters are refused with a sentence naming them",
          "[parking]") {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  ControllerParams p;
  CHECK_NOTHROW(p.validate());
  p.c_min_px = 480.0;
  p.c_max_px = 300.0;
  CHECK(throwsWithText(p, ErrorCode::kInvalidArgument, "c_min_px (480) must not exceed c_max_px"));
  CHECK(throwsCode([&] { HybridController c(p); }, ErrorCode::kInvalidArgument));
  p = ControllerParams{};
  p.c_max_px = 478.0;  // = min(u1^r, W - u3^r): a forward move could end too far away
  CHECK(throwsWithText(p, ErrorCode::kInvalidArgument, "c_max_px"));
  p = ControllerParams{};
  p.v_forward_mps = -0.1;
  CHECK(throwsWithText(p, ErrorCode::kInvalidArgument, "v_forward_mps must be > 0"));
  p = ControllerParams{};
  p.v_reverse_mps = 0.0;
  CHECK(throwsWithText(p, ErrorCode::kInvalidArgument, "v_reverse_mps"));
  p = ControllerParams{};
  p.v_reverse_slow_mps = 0.2;
  CHECK(throwsWithText(p, ErrorCode::kInvalidArgument, "v_reverse_slow_mps"));
  p = ControllerParams{};
  p.k1_radps_per_px = nan;
  CHECK(throwsWithText(p, ErrorCode::kNonFinite, "k1_radps_per_px"));
  p = ControllerParams{};
  p.c_gain = std::numeric_limits<double>::infinity();
  CHECK(throwsWithText(p, ErrorCode::kNonFinite, "c_gain"));
  p = ControllerParams{};
  p.c_gain = -1.0;
  CHECK(throwsWithText(p, ErrorCode::kInvalidArgument, "c_gain"));
  p = ControllerParams{};
  p.A_min_px = 431.0;
  CHECK(throwsWithText(p, ErrorCode::kInvalidArgument, "A_min_px"));
  p = ControllerParams{};
  p.reference_px = {478.0, 910.0, 695.0};
  CHECK(throwsWithText(p, ErrorCode::kInvalidArgument, "reference positions"));
  p = ControllerParams{};
  p.delta_u_px = 0.0;
  CHECK(throwsWithText(p, ErrorCode::kInvalidArgument, "delta_u_px"));
  p = ControllerParams{};
  p.parked_frames = 0;
  CHECK(throwsWithText(p, ErrorCode::kInvalidArgument, "parked_frames"));
  p = ControllerParams{};
  p.start_exit_frames = 0;
  CHECK(throwsWithText(p, ErrorCode::kInvalidArgument, "start_exit_frames"));
  p = ControllerParams{};
  p.image_width_px = nan;
  CHECK(throwsWithText(p, ErrorCode::kNonFinite, "image_width_px"));
}
