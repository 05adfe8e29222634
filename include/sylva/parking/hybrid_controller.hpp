#pragma once
/// @file
/// sylva::parking::HybridController: the image-based hybrid parking controller of Amarasinghe's
/// thesis (2008), Ch. 5. It reads the horizontal image positions of the parking station's
/// three features, one frame at a time, and returns the robot command (v, omega) and the
/// state of its finite state machine. It knows nothing of the simulator: on a real robot the
/// positions come from a blob detector and the command goes to the wheels.
///
/// Image and sign conventions
/// --------------------------
/// u is measured in pixels from the left image edge, increasing to the right; W is the image
/// width. The features are P1, P2, P3 from left to right, u1 < u2 < u3 (a frame is sorted
/// before use). omega is counter-clockwise positive (sylva's convention), so turning left
/// (omega > 0) moves every feature to the right in the image (u grows).
///
///   e_i = u_i - u_i^r,   f1 = u2 - u1,   f2 = u3 - u2,   A = u3 - u1,   E_A = A - A^r
///
/// The finite state machine (eq. 5.4, Fig. 5.5; Algorithms 5-8)
/// --------------------------------------------------------------
///   Start    turn in place, omega = -k1 e2, until |e2| <= delta_u; then measure the
///            station's asymmetry (from f1, f2), set the virtual edge c (eq. 5.9) and leave
///            with eps1 -> Forward if E_A < 0 (the station looks smaller than the reference:
///            too far), else eps2 -> Reverse.
///   Forward  v = v_c. The side comes from the last Start: the nearer half of the station
///            looks wider, so f1 < f2 means the robot is on P3's side of the axis and must
///            turn towards it, which moves the station right: P3 is held at the right virtual
///            edge, omega = k2 (W - c - u3). Otherwise P1 is held at the left one, omega =
///            -k2 (u1 - c). It leaves with eps4 -> Start when the other (uncontrolled) outer
///            feature comes within c of its edge (u1 <= c, resp. W - u3 <= c).
///   Reverse  v = -v_r (v_slow near the goal: |E_A| < 25 px and a small asymmetry), omega =
///            -k1 e2: straight back along the line through P2. Leaves with eps3 -> Stop when
///            the parking condition (eq. 5.1) holds, with eps5 -> Forward when A < A_min.
///   Stop     v = omega = 0 (terminal: parked).
///   Lost     v = omega = 0 (terminal, not in the thesis): a frame showed fewer than three
///            features, i.e. the station left the image. The thesis assumes this never happens.
///
/// Virtual edge (eq. 5.9): c = c_max - k_c |asymmetry|, clamped to [c_min, c_max]. k_c stands
/// for the thesis' product k_s k. c_max must stay below min(u1^r, W - u3^r) (478 px for Table
/// 5.2), or a forward move could end before the station looks as large as the reference.
///
/// Where this differs from the printed algorithms (docs/examples/parking.md has the evidence;
/// examples/parking runs it in closed loop with a simulated camera):
///   * Algorithm 6 prints the loop conditions of its two branches swapped (each tests the
///     feature that the branch controls, which would end the move as soon as the control
///     converges); the text and Theorem 5.4.1 say the move ends on the uncontrolled feature.
///   * Algorithm 7 prints "while (NOT A < A_min) OR parked"; the intent (and what is coded) is
///     "while NOT (A < A_min) AND NOT parked".
///   * scaled_asymmetry (default on): the side and c come from (f1 - f2) (A^r/A)^2 - (f1^r -
///     f2^r) instead of the raw f1 - f2. The raw value grows as 1/r^2, and a forward move with
///     a small c ends closer (A = W - 2c), so a small c measures a large |f1 - f2| and keeps c
///     small: above a gain of about 5 the raw law locks into endless cycles. Scaled, it depends
///     on the polar angle alone (what eq. 5.11 assumes), and relative to the reference it aims
///     at the goal rather than at the symmetric view (Table 5.2's reference is lopsided by
///     2 px). raw: scaled_asymmetry = false.
///   * exit_on_width (default on): a forward move also ends when A >= W - 2c. This is the
///     thesis' end point while the held feature sits on its edge (eq. 5.8); when the turn lags
///     behind near the station the held feature slips past its edge, the thesis' test fires
///     late, and the station can leave the image in the following Start turn.
///   * start_exit_frames (default 5): Start measures over five aligned frames, not one (the
///     "termination measurement" of Sec. 5.3.1), to average the pixel noise out of c.
///   * parked_frames (default 1, as printed): eq. 5.1 may be asked of consecutive frames.
///   * One transition per frame: the state entered on a frame computes its command from that
///     frame, but its own exit test waits for the next frame (as a frame loop on a robot does).
///   * omega is limited to +-max_omega (a real base has a top turn rate).
/// Gains: Table 5.2's 0.25 and 0.1 are read as deg/s per pixel (the unit Pioneer robots take
/// turn rates in); as rad/s per pixel the loop would be unstable at 19 frames per second.
///
/// Bad input: a frame with a non-finite position throws sylva::Error(kNonFinite); a position
/// outside [0, W], more than three features or two features closer than min_feature_gap_px (a
/// duplicated blob) throws kInvalidArgument, and the controller is left as it was. Fewer than
/// three features is the defined "station lost" outcome. Parameters are checked on
/// construction (kInvalidArgument / kNonFinite with a sentence naming the parameter).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <sstream>
#include <string>
#include <vector>

#include "sylva/core/angles.hpp"
#include "sylva/core/error.hpp"

namespace sylva::parking {

enum class State { kStart, kForward, kReverse, kStop, kLost };

/// The events of the FSM (eps1..eps5 of eq. 5.4) and the station-lost event added here.
enum class Event { kNone, kEps1, kEps2, kEps3, kEps4, kEps5, kStationLost };

inline const char* toString(State s) {
  switch (s) {
    case State::kStart:
      return "Start";
    case State::kForward:
      return "Forward";
    case State::kReverse:
      return "Reverse";
    case State::kStop:
      return "Stop";
    case State::kLost:
      return "Lost";
  }
  return "?";
}

inline const char* toString(Event e) {
  switch (e) {
    case Event::kNone:
      return "none";
    case Event::kEps1:
      return "eps1";
    case Event::kEps2:
      return "eps2";
    case Event::kEps3:
      return "eps3";
    case Event::kEps4:
      return "eps4";
    case Event::kEps5:
      return "eps5";
    case Event::kStationLost:
      return "lost";
  }
  return "?";
}

/// The tunable parameters (Table 5.1); defaults from Table 5.2 where it gives them.
struct ControllerParams {
  double image_width_px = 1392.0;                           ///< W (Basler A102fc: 1392 x 1040)
  std::array<double, 3> reference_px{478.0, 695.0, 910.0};  ///< [u1^r, u2^r, u3^r]
  double k1_radps_per_px = 0.25 * kRadPerDeg;  ///< start/reverse turn gain (Table 5.2: 0.25)
  double k2_radps_per_px = 0.10 * kRadPerDeg;  ///< forward turn gain (Table 5.2: 0.1)
  double c_min_px = 255.0;                    ///< Table 5.2
  double c_max_px = 470.0;                    ///< Fig. 5.15 (allowed maximum 478)
  bool adapt_c = true;                        ///< eq. 5.9; false: c = c_static_px always
  double c_gain = 12.0;  ///< k_c = k_s k of eq. 5.9 (px of c per px of asymmetry)
  /// true: the asymmetry that picks the side and sets c is f1 - f2 scaled to the reference
  /// size and taken relative to the reference's own f1^r - f2^r (see the file comment);
  /// false: the raw f1 - f2 of Algorithms 5-6 and eq. 5.9.
  bool scaled_asymmetry = true;
  /// true: a forward move also ends when the station is wider than the virtual window,
  /// A >= W - 2c (the same moment as the thesis' test while the held feature sits on its
  /// virtual edge, earlier when the turn lags behind and the held feature slips past it).
  bool exit_on_width = true;
  double c_static_px = 470.0;        ///< the virtual edge when adapt_c is false
  double v_forward_mps = 0.14;       ///< v_c (Table 5.2: 140 mm/s)
  double v_reverse_mps = 0.10;       ///< v_r (Table 5.2: 100 mm/s)
  double v_reverse_slow_mps = 0.02;  ///< reverse speed near the goal (Sec. 5.5.3; value ours)
  double slow_band_EA_px = 25.0;     ///< slow when |E_A| < this (Sec. 5.5.3) ...
  double slow_band_f12_px = 8.0;     ///< ... and |asymmetry| < this (threshold ours)
  double delta_u_px = 1.5;           ///< Table 5.2
  double delta_A_px = 1.5;           ///< Table 5.2
  int parked_frames = 1;             ///< consecutive frames on which eq. 5.1 must hold (thesis: 1)
  /// Frames over which Start measures f1, f2 and E_A once P2 is aligned (its "termination
  /// measurement", Sec. 5.3.1); the mean sets c and the next state. Thesis: 1 frame.
  int start_exit_frames = 5;
  double A_min_px = 260.0;          ///< reverse until A < A_min (not in Table 5.2; ours)
  double max_omega_radps = 1.0;     ///< turn-rate limit (not in the thesis)
  double min_feature_gap_px = 1.0;  ///< closer blobs are one feature seen twice

  double referenceWidth() const { return reference_px[2] - reference_px[0]; }
  /// The largest c for which a forward move ends with the station larger than the reference.
  double cAllowedMax() const { return std::min(reference_px[0], image_width_px - reference_px[2]); }

  /// Throws sylva::Error naming the first parameter that makes no sense.
  void validate() const {
    using sylva::ErrorCode;
    const auto finite = [](const char* name, double value) {
      if (!std::isfinite(value)) {
        std::ostringstream os;
        os << "parking controller: " << name << " must be finite, got " << value;
        sylva::fail(ErrorCode::kNonFinite, os.str());
      }
    };
    const auto require = [](bool ok, const std::string& sentence) {
      if (!ok) sylva::fail(ErrorCode::kInvalidArgument, "parking controller: " + sentence);
    };
    const auto positive = [&](const char* name, double value) {
      finite(name, value);
      std::ostringstream os;
      os << name << " must be > 0, got " << value;
      require(value > 0.0, os.str());
    };
    positive("image_width_px", image_width_px);
    for (double u : reference_px) finite("reference_px", u);
    {
      std::ostringstream os;
      os << "the reference positions must satisfy 0 < u1 < u2 < u3 < W = " << image_width_px
         << ", got [" << reference_px[0] << ", " << reference_px[1] << ", " << reference_px[2]
         << "]";
      require(reference_px[0] > 0.0 && reference_px[0] < reference_px[1] &&
                  reference_px[1] < reference_px[2] && reference_px[2] < image_width_px,
              os.str());
    }
    positive("k1_radps_per_px", k1_radps_per_px);
    positive("k2_radps_per_px", k2_radps_per_px);
    positive("c_min_px", c_min_px);
    positive("c_max_px", c_max_px);
    finite("c_gain", c_gain);
    {
      std::ostringstream os;
      os << "c_min_px (" << c_min_px << ") must not exceed c_max_px (" << c_max_px << ")";
      require(c_min_px <= c_max_px, os.str());
    }
    {
      std::ostringstream os;
      os << "c_max_px (" << c_max_px << ") must be below min(u1^r, W - u3^r) = " << cAllowedMax()
         << ", or a forward move can end before the station looks as large as the reference";
      require(c_max_px < cAllowedMax(), os.str());
    }
    {
      std::ostringstream os;
      os << "c_gain must be >= 0, got " << c_gain;
      require(c_gain >= 0.0, os.str());
    }
    positive("c_static_px", c_static_px);
    {
      std::ostringstream os;
      os << "c_static_px (" << c_static_px
         << ") must be below min(u1^r, W - u3^r) = " << cAllowedMax();
      require(c_static_px < cAllowedMax(), os.str());
    }
    positive("v_forward_mps", v_forward_mps);
    positive("v_reverse_mps", v_reverse_mps);
    positive("v_reverse_slow_mps", v_reverse_slow_mps);
    {
      std::ostringstream os;
      os << "v_reverse_slow_mps (" << v_reverse_slow_mps << ") must not exceed v_reverse_mps ("
         << v_reverse_mps << ")";
      require(v_reverse_slow_mps <= v_reverse_mps, os.str());
    }
    finite("slow_band_EA_px", slow_band_EA_px);
    finite("slow_band_f12_px", slow_band_f12_px);
    require(slow_band_EA_px >= 0.0 && slow_band_f12_px >= 0.0,
            "the slow-reverse bands must be >= 0");
    positive("delta_u_px", delta_u_px);
    positive("delta_A_px", delta_A_px);
    if (parked_frames < 1 || parked_frames > 100) {
      std::ostringstream os;
      os << "parked_frames must be in [1, 100], got " << parked_frames;
      require(false, os.str());
    }
    if (start_exit_frames < 1 || start_exit_frames > 100) {
      std::ostringstream os;
      os << "start_exit_frames must be in [1, 100], got " << start_exit_frames;
      require(false, os.str());
    }
    positive("A_min_px", A_min_px);
    {
      std::ostringstream os;
      os << "A_min_px (" << A_min_px
         << ") must be below the reference width A^r = " << referenceWidth()
         << " less delta_A, or the reverse move ends before it can park";
      require(A_min_px < referenceWidth() - delta_A_px, os.str());
    }
    positive("max_omega_radps", max_omega_radps);
    finite("min_feature_gap_px", min_feature_gap_px);
    require(min_feature_gap_px >= 0.0, "min_feature_gap_px must be >= 0");
  }
};

/// The station as one frame shows it, sorted left to right.
struct StationImage {
  std::array<double, 3> u{};  ///< [u1, u2, u3]
  double f1() const { return u[1] - u[0]; }
  double f2() const { return u[2] - u[1]; }
  double width() const { return u[2] - u[0]; }  ///< A
};

/// What the controller asks of the robot for the coming frame interval.
struct Command {
  double v_mps = 0.0;           ///< forward speed (negative: reversing)
  double omega_radps = 0.0;     ///< turn rate, counter-clockwise positive
  State state = State::kStart;  ///< the state after this frame
  Event event = Event::kNone;   ///< the event this frame raised, if any
};

/// One entry of the FSM trace.
struct Transition {
  long frame = 0;  ///< index of the frame that raised the event (0-based)
  State from = State::kStart;
  State to = State::kStart;
  Event event = Event::kNone;
  double c_px = 0.0;  ///< the virtual edge after the transition
};

class HybridController {
 public:
  explicit HybridController(const ControllerParams& params = {}) : p_(params) {
    p_.validate();
    reset();
  }

  /// Back to Start, as before the first frame.
  void reset() {
    state_ = State::kStart;
    frame_ = 0;
    c_ = p_.adapt_c ? p_.c_max_px : p_.c_static_px;
    asymmetry_ = 0.0;
    parked_streak_ = 0;
    start_measurement_ = StartMeasurement{};
    forward_moves_ = reverse_moves_ = 0;
    transitions_.clear();
  }

  /// Feeds one frame: the horizontal positions (px, any order) of the features found in it.
  /// Returns the command for the coming frame interval. Throws on malformed frames (see the
  /// file comment) and then leaves the controller unchanged.
  Command step(const std::vector<double>& detections_px) {
    if (isTerminal()) {
      ++frame_;
      return Command{0.0, 0.0, state_, Event::kNone};
    }
    const StationImage image = checkedImage(detections_px);  // may throw: nothing written yet
    Command out;
    if (detections_px.size() < 3) {
      transition(State::kLost, Event::kStationLost);
      out = Command{0.0, 0.0, state_, Event::kStationLost};
      ++frame_;
      return out;
    }
    const int streak = state_ == State::kReverse && parked(image) ? parked_streak_ + 1 : 0;
    StartMeasurement measurement = start_measurement_;
    if (state_ == State::kStart &&
        (measurement.frames > 0 || std::abs(image.u[1] - p_.reference_px[1]) <= p_.delta_u_px)) {
      ++measurement.frames;
      measurement.asymmetry_sum += asymmetry(image);
      measurement.E_A_sum += image.width() - p_.referenceWidth();
    }
    const Event event = exitEvent(image, streak, measurement);
    parked_streak_ = event == Event::kNone ? streak : 0;
    start_measurement_ = event == Event::kNone ? measurement : StartMeasurement{};
    if (event != Event::kNone) {
      if (state_ == State::kStart) {
        // Algorithm 5, exit: f1, f2 (here their asymmetry) for the forward move; c by eq. 5.9.
        asymmetry_ = measurement.asymmetry_sum / measurement.frames;
        c_ = virtualEdge(asymmetry_);
      }
      transition(nextState(event), event);
    }
    out = command(image);
    out.event = event;
    ++frame_;
    return out;
  }

  /// How lopsided the station looks, in pixels: the raw f1 - f2 of the thesis, or (with
  /// scaled_asymmetry) (f1 - f2) (A^r / max(A, A_min))^2 - (f1^r - f2^r). Positive: the
  /// robot is on P1's side of the goal. f1 - f2 of a centred station at distance r and polar
  /// angle phi is about 2 f d^2 sin(phi) / r^2 (eq. 5.10) and A about 2 f d / r, so the
  /// scaled value depends on phi alone (for A >= A_min), about (A^r)^2 tan(phi) / (2 f).
  double asymmetry(const StationImage& image) const {
    const double raw = image.f1() - image.f2();
    if (!p_.scaled_asymmetry) return raw;
    // Below A_min (farther than a reverse move goes) the scale stops growing: the factor
    // would amplify the pixel noise of a tiny station.
    const double scale = p_.referenceWidth() / std::max(image.width(), p_.A_min_px);
    const double reference =
        (p_.reference_px[1] - p_.reference_px[0]) - (p_.reference_px[2] - p_.reference_px[1]);
    return raw * scale * scale - reference;
  }

  /// The virtual edge of eq. 5.9 for a Start exit that measured `asymmetry`.
  double virtualEdge(double asymmetry) const {
    if (!p_.adapt_c) return p_.c_static_px;
    const double c = p_.c_max_px - p_.c_gain * std::abs(asymmetry);
    return std::clamp(c, p_.c_min_px, p_.c_max_px);
  }

  /// The parking condition, eq. 5.1.
  bool parked(const StationImage& image) const {
    const double e_A = image.width() - p_.referenceWidth();
    if (!(std::abs(e_A) < p_.delta_A_px)) return false;
    for (int i = 0; i < 3; ++i)
      if (!(std::abs(image.u[static_cast<std::size_t>(i)] -
                     p_.reference_px[static_cast<std::size_t>(i)]) < p_.delta_u_px))
        return false;
    return true;
  }

  State state() const { return state_; }
  bool isTerminal() const { return state_ == State::kStop || state_ == State::kLost; }
  double virtualEdgePx() const { return c_; }
  /// True when the forward move holds P3 at the right virtual edge (f1 < f2 at the last
  /// Start exit: the robot is on P3's side).
  bool holdsRightFeature() const { return asymmetry_ < 0.0; }
  /// The asymmetry measured at the last Start exit.
  double lastAsymmetryPx() const { return asymmetry_; }
  long frames() const { return frame_; }
  int forwardMoves() const { return forward_moves_; }
  int reverseMoves() const { return reverse_moves_; }
  const std::vector<Transition>& transitions() const { return transitions_; }
  const ControllerParams& params() const { return p_; }

 private:
  StationImage checkedImage(const std::vector<double>& d) const {
    using sylva::ErrorCode;
    for (std::size_t i = 0; i < d.size(); ++i) {
      if (!std::isfinite(d[i])) {
        std::ostringstream os;
        os << "parking controller: frame " << frame_ << " holds a non-finite feature position (u["
           << i << "] = " << d[i] << ")";
        sylva::fail(ErrorCode::kNonFinite, os.str());
      }
      if (d[i] < 0.0 || d[i] > p_.image_width_px) {
        std::ostringstream os;
        os << "parking controller: frame " << frame_ << " holds u[" << i << "] = " << d[i]
           << " px, outside the image [0, " << p_.image_width_px << "]";
        sylva::fail(ErrorCode::kInvalidArgument, os.str());
      }
    }
    if (d.size() > 3) {
      std::ostringstream os;
      os << "parking controller: frame " << frame_ << " holds " << d.size()
         << " features; the station has 3 (remove spurious blobs before the controller)";
      sylva::fail(ErrorCode::kInvalidArgument, os.str());
    }
    std::vector<double> sorted = d;
    std::sort(sorted.begin(), sorted.end());
    for (std::size_t i = 1; i < sorted.size(); ++i) {
      if (sorted[i] - sorted[i - 1] < p_.min_feature_gap_px) {
        std::ostringstream os;
        os << "parking controller: frame " << frame_
           << " holds a duplicated feature: u = " << sorted[i - 1] << " and " << sorted[i]
           << " px are closer than " << p_.min_feature_gap_px << " px";
        sylva::fail(ErrorCode::kInvalidArgument, os.str());
      }
    }
    StationImage image;
    for (std::size_t i = 0; i < sorted.size() && i < 3; ++i) image.u[i] = sorted[i];
    return image;
  }

  /// What Start has measured since P2 came onto its reference.
  struct StartMeasurement {
    int frames = 0;
    double asymmetry_sum = 0.0;
    double E_A_sum = 0.0;
  };

  /// The exit test of the current state on this frame (Algorithms 5-7).
  Event exitEvent(const StationImage& image,
                  int parked_streak,
                  const StartMeasurement& measurement) const {
    switch (state_) {
      case State::kStart:
        if (measurement.frames < p_.start_exit_frames) return Event::kNone;
        return measurement.E_A_sum < 0.0 ? Event::kEps1 : Event::kEps2;
      case State::kForward:
        // The uncontrolled outer feature reached its virtual edge (see the file comment).
        if (p_.exit_on_width && image.width() >= p_.image_width_px - 2.0 * c_) return Event::kEps4;
        if (holdsRightFeature()) return image.u[0] <= c_ ? Event::kEps4 : Event::kNone;
        return p_.image_width_px - image.u[2] <= c_ ? Event::kEps4 : Event::kNone;
      case State::kReverse:
        if (parked_streak >= p_.parked_frames) return Event::kEps3;
        return image.width() < p_.A_min_px ? Event::kEps5 : Event::kNone;
      case State::kStop:
      case State::kLost:
        return Event::kNone;
    }
    return Event::kNone;
  }

  static State nextState(Event e) {
    switch (e) {
      case Event::kEps1:
        return State::kForward;
      case Event::kEps2:
        return State::kReverse;
      case Event::kEps3:
        return State::kStop;
      case Event::kEps4:
        return State::kStart;
      case Event::kEps5:
        return State::kForward;
      case Event::kStationLost:
        return State::kLost;
      case Event::kNone:
        break;
    }
    return State::kStart;
  }

  void transition(State to, Event event) {
    transitions_.push_back(Transition{frame_, state_, to, event, c_});
    state_ = to;
    if (to == State::kForward) ++forward_moves_;
    if (to == State::kReverse) ++reverse_moves_;
  }

  double limitTurn(double omega) const {
    return std::clamp(omega, -p_.max_omega_radps, p_.max_omega_radps);
  }

  /// The command of the current state's control loop for this frame.
  Command command(const StationImage& image) const {
    const double W = p_.image_width_px;
    const double e2 = image.u[1] - p_.reference_px[1];
    Command out;
    out.state = state_;
    switch (state_) {
      case State::kStart:  // Algorithm 5: turn in place onto P2.
        out.omega_radps = limitTurn(-p_.k1_radps_per_px * e2);
        break;
      case State::kForward:  // Algorithm 6: hold one outer feature at the virtual edge.
        out.v_mps = p_.v_forward_mps;
        if (holdsRightFeature())
          out.omega_radps = limitTurn(p_.k2_radps_per_px * (W - c_ - image.u[2]));
        else
          out.omega_radps = limitTurn(-p_.k2_radps_per_px * (image.u[0] - c_));
        break;
      case State::kReverse: {  // Algorithm 7: straight back, P2 held on its reference.
        const double E_A = image.width() - p_.referenceWidth();
        const bool near_goal =
            std::abs(E_A) < p_.slow_band_EA_px && std::abs(asymmetry(image)) < p_.slow_band_f12_px;
        out.v_mps = -(near_goal ? p_.v_reverse_slow_mps : p_.v_reverse_mps);
        out.omega_radps = limitTurn(-p_.k1_radps_per_px * e2);
        break;
      }
      case State::kStop:
      case State::kLost:
        break;
    }
    return out;
  }

  ControllerParams p_;
  State state_ = State::kStart;
  long frame_ = 0;
  double c_ = 0.0;
  double asymmetry_ = 0.0;
  int parked_streak_ = 0;  ///< frames in a row on which eq. 5.1 held (Reverse only)
  StartMeasurement start_measurement_;
  int forward_moves_ = 0;
  int reverse_moves_ = 0;
  std::vector<Transition> transitions_;
};

}  // namespace sylva::parking
