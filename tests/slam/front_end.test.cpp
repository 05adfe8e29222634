// slam::FrontEnd: the SLAM step as a library layer. Each case compares the front end with the
// same filter operations written out by hand (bit for bit), or checks one rule of the step
// (gates, tentative tracks, removal, thinning, fallback) on a geometry where the answer is
// known.

#include "sylva_catch.hpp"

#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include <sylva/association/jcbb.hpp>
#include <sylva/association/nearest_neighbor.hpp>
#include <sylva/association/smallest_nis.hpp>
#include <sylva/consistency/chi_square.hpp>
#include <sylva/filter/ekf.hpp>
#include <sylva/measurements/range_bearing_diameter.hpp>
#include <sylva/motion/unicycle_2d.hpp>
#include <sylva/slam/front_end.hpp>
#include <sylva/slam/reach.hpp>

#include "error_helpers.hpp"

// Own namespace: the tests of a folder are compiled as one unity translation unit.
namespace unity_slam_front_end {

using namespace sylva;
using sylva_test::throwsCode;

using Filter = Ekf<Unicycle2D, Point2, TreeXYR>;
using FrontEnd = slam::FrontEnd<Filter, RangeBearing, InverseRangeBearing>;
using Reading = FrontEnd::ReadingType;

const Gaussian<2> kNoise = Gaussian<2>::sigmas(Vec<2>(0.05, 0.01));
const Gaussian<2> kMotion = Gaussian<2>::sigmas(Vec<2>(0.05, 0.02));

// Landmarks on a ring around the start, 4 m apart or more.
std::vector<Vec<2>> world() {
  return {Vec<2>(4.0, 0.0), Vec<2>(3.0, 4.0), Vec<2>(-2.0, 4.5), Vec<2>(-4.5, -1.0), Vec<2>(1.0, -4.0),
          Vec<2>(6.0, 3.0)};
}

// Noise-free readings of every landmark from `pose`, with a small deterministic perturbation.
std::vector<Reading> readingsFrom(const Vec<3>& pose, const std::vector<Vec<2>>& landmarks, bool with_ids) {
  std::vector<Reading> out;
  for (std::size_t j = 0; j < landmarks.size(); ++j) {
    const Vec<2> z = RangeBearing{}(pose, landmarks[j]) + Vec<2>(0.01 * std::sin(3.0 * j), 0.002 * std::cos(5.0 * j));
    Reading r{z, kNoise};
    if (with_ids) r.id = static_cast<Id>(j);
    out.push_back(r);
  }
  return out;
}

void requireSame(const Filter& a, const Filter& b) {
  REQUIRE(a.landmarkCount() == b.landmarkCount());
  CHECK(a.mean() == b.mean());
  CHECK(a.covariance() == b.covariance());
}

TEST_CASE("FrontEnd with known ids is the hand-written add-then-update loop", "[slam][front_end]") {
  const auto landmarks = world();
  Filter by_hand(Vec<3>::Zero(), Mat<3, 3>::Zero());
  Filter ekf = by_hand;
  slam::FrontEndOptions options;
  options.association = slam::Association::kKnownIds;
  FrontEnd front_end(RangeBearing{}, InverseRangeBearing{}, options);

  Vec<3> pose = Vec<3>::Zero();
  for (int k = 0; k < 5; ++k) {
    const Vec<2> u(1.0, 0.1);
    pose = Unicycle2D{}(pose, u, 0.5);
    const std::vector<Reading> readings = readingsFrom(pose, landmarks, true);
    by_hand.predict(u, 0.5, kMotion);
    std::vector<Observation<RangeBearing>> paired;
    for (const Reading& r : readings)
      if (by_hand.contains(*r.id)) paired.push_back({*r.id, r.z, r.noise});
    by_hand.update(RangeBearing{}, paired);
    for (const Reading& r : readings)
      if (!by_hand.contains(*r.id)) by_hand.add(*r.id, InverseRangeBearing{}, r.z, r.noise);

    const slam::StepReport& report = front_end.step(ekf, u, 0.5, kMotion, readings, 0.5 * (k + 1));
    requireSame(ekf, by_hand);
    CHECK(report.count(k == 0 ? slam::Outcome::kAdded : slam::Outcome::kPaired) == 6);
    for (std::size_t j = 0; j < readings.size(); ++j) CHECK(report.readings[j].landmark == static_cast<Id>(j));
  }
  CHECK(front_end.sightings(2) == 5);
  CHECK(front_end.sightings(99) == 0);
}

TEST_CASE("FrontEnd with JCBB or NN is association, the new-landmark test, one update and the adds",
          "[slam][front_end]") {
  const auto association = GENERATE(slam::Association::kJcbb, slam::Association::kNearestNeighbor);
  const auto landmarks = world();
  Filter by_hand(Vec<3>::Zero(), Mat<3, 3>::Zero());
  Filter ekf = by_hand;
  slam::FrontEndOptions options;
  options.association = association;
  options.first_new_id = 10;
  FrontEnd front_end(RangeBearing{}, InverseRangeBearing{}, options);
  const double new_gate = chiSquareGate(2, options.new_landmark_probability);
  Id next_id = 10;

  Vec<3> pose = Vec<3>::Zero();
  for (int k = 0; k < 6; ++k) {
    const Vec<2> u(0.8, -0.15);
    pose = Unicycle2D{}(pose, u, 0.5);
    // The first step sees only half of the landmarks, so later steps pair and add.
    std::vector<Vec<2>> seen(landmarks.begin(), landmarks.begin() + (k == 0 ? 3 : 6));
    const std::vector<Reading> readings = readingsFrom(pose, seen, false);

    by_hand.predict(u, 0.5, kMotion);
    std::vector<Vec<2>> z;
    for (const Reading& r : readings) z.push_back(r.z);
    std::vector<Id> candidates;
    for (const LandmarkSlot& s : by_hand.slots()) candidates.push_back(s.id);
    std::vector<std::optional<Id>> pairing(z.size());
    if (!candidates.empty())
      pairing = association == slam::Association::kJcbb ? associateJcbb(by_hand, RangeBearing{}, z, kNoise, candidates)
                                                         : associateNearestNeighbor(by_hand, RangeBearing{}, z, kNoise, candidates);
    std::vector<Observation<RangeBearing>> paired;
    std::vector<std::size_t> fresh;
    for (std::size_t i = 0; i < z.size(); ++i) {
      if (pairing[i])
        paired.push_back({*pairing[i], z[i], kNoise});
      else if (smallestNis(by_hand, RangeBearing{}, z[i], kNoise, candidates) > new_gate)
        fresh.push_back(i);
    }
    by_hand.update(RangeBearing{}, paired);
    for (const std::size_t i : fresh) by_hand.add(next_id++, InverseRangeBearing{}, z[i], kNoise);

    const slam::StepReport& report = front_end.step(ekf, u, 0.5, kMotion, readings, 0.5 * (k + 1));
    requireSame(ekf, by_hand);
    CHECK(report.count(slam::Outcome::kPaired) == static_cast<int>(paired.size()));
    CHECK(report.count(slam::Outcome::kAdded) == static_cast<int>(fresh.size()));
  }
  // Every landmark was mapped once, and each reading went to the landmark it came from.
  CHECK(ekf.landmarkCount() == 6);
  const slam::StepReport& last = front_end.lastReport();
  for (std::size_t j = 0; j < landmarks.size(); ++j) {
    REQUIRE(last.readings[j].outcome == slam::Outcome::kPaired);
    CHECK((ekf.landmarkMean<Point2>(*last.readings[j].landmark) - landmarks[j]).norm() < 0.2);
  }
}

TEST_CASE("FrontEnd reports a reading close to a landmark but outside its gate as ambiguous", "[slam][front_end]") {
  Filter ekf(Vec<3>::Zero(), Mat<3, 3>::Zero());
  ekf.add(0, InverseRangeBearing{}, Vec<2>(5.0, 0.0), kNoise);
  slam::FrontEndOptions options;
  options.association = slam::Association::kNearestNeighbor;
  FrontEnd front_end(RangeBearing{}, InverseRangeBearing{}, options);
  // Bearing 0.05 rad off: NIS about 12 (outside the 0.99 gate, 9.2) and below chi2(2, 0.9999) = 18.4.
  const Filter before = ekf;
  const auto& report = front_end.update(ekf, {Reading{Vec<2>(5.0, 0.045), kNoise}}, 0.0);
  REQUIRE(report.readings[0].outcome == slam::Outcome::kAmbiguous);
  CHECK(report.readings[0].nis > chiSquareGate(2, 0.99));
  CHECK(report.readings[0].nis < chiSquareGate(2, 0.9999));
  requireSame(ekf, before);
  // Far from everything: a new landmark, with its smallest NIS in the report.
  const auto& far = front_end.update(ekf, {Reading{Vec<2>(5.0, 1.0), kNoise}}, 0.1);
  CHECK(far.readings[0].outcome == slam::Outcome::kAdded);
  CHECK(far.readings[0].nis > chiSquareGate(2, 0.9999));
  CHECK(ekf.landmarkCount() == 2);
}

TEST_CASE("FrontEnd's tentative tracks start a landmark only after enough sightings", "[slam][front_end]") {
  Filter ekf(Vec<3>::Zero(), Mat<3, 3>::Zero());
  slam::FrontEndOptions options;
  options.association = slam::Association::kJcbb;
  options.new_landmarks = slam::NewLandmarks::kTentative;
  options.tentative = {3, 0.5, 1.0};
  FrontEnd front_end(RangeBearing{}, InverseRangeBearing{}, options);
  const Reading steady{Vec<2>(4.0, 0.3), kNoise};
  const Reading flicker{Vec<2>(6.0, -0.8), kNoise};

  // Step 1: both start tracks; step 2: both are fed; nothing is mapped yet.
  CHECK(front_end.update(ekf, {steady, flicker}, 0.0).count(slam::Outcome::kTentative) == 2);
  CHECK(front_end.update(ekf, {steady, flicker}, 0.1).count(slam::Outcome::kTentative) == 2);
  CHECK(ekf.landmarkCount() == 0);
  CHECK(front_end.tentativeTracks() == 2);
  // Step 3: the steady one becomes landmark 0; the flicker is not seen.
  const auto& third = front_end.update(ekf, {steady}, 0.2);
  REQUIRE(third.readings[0].outcome == slam::Outcome::kAdded);
  CHECK(third.readings[0].landmark == Id{0});
  CHECK(ekf.landmarkCount() == 1);
  CHECK(third.tentative_tracks == 1);
  // The flicker's track times out 1 s after its last sighting; seen again, it starts over.
  CHECK(front_end.update(ekf, {}, 1.2).tentative_tracks == 0);
  CHECK(front_end.update(ekf, {flicker}, 1.3).count(slam::Outcome::kTentative) == 1);
  CHECK(ekf.landmarkCount() == 1);
  // Two readings of one step never feed the same track: the second starts its own.
  Filter other(Vec<3>::Zero(), Mat<3, 3>::Zero());
  FrontEnd fresh(RangeBearing{}, InverseRangeBearing{}, options);
  CHECK(fresh.update(other, {steady, steady, steady}, 0.0).tentative_tracks == 3);
}

TEST_CASE("FrontEnd removes the landmarks it started that stay unconfirmed", "[slam][front_end]") {
  Filter ekf(Vec<3>::Zero(), Mat<3, 3>::Zero());
  ekf.add(100, InverseRangeBearing{}, Vec<2>(3.0, -1.0), kNoise);  // the caller's own: never removed
  slam::FrontEndOptions options;
  options.association = slam::Association::kKnownIds;
  options.unconfirmed = {2, 1.0};
  FrontEnd front_end(RangeBearing{}, InverseRangeBearing{}, options);
  const auto reading = [](Id id, double range, double bearing) {
    Reading r{Vec<2>(range, bearing), kNoise};
    r.id = id;
    return r;
  };
  front_end.update(ekf, {reading(1, 4.0, 0.2), reading(2, 5.0, -0.4)}, 0.0);
  front_end.update(ekf, {reading(1, 4.0, 0.2)}, 0.5);  // landmark 1 confirmed
  CHECK(front_end.update(ekf, {}, 1.0).removed.empty());  // not yet more than 1 s old
  const auto& report = front_end.update(ekf, {}, 1.5);
  CHECK(report.removed == std::vector<Id>{2});
  CHECK(ekf.contains(1));
  CHECK(!ekf.contains(2));
  CHECK(ekf.contains(100));
}

TEST_CASE("FrontEnd fuses a landmark at most once per interval", "[slam][front_end]") {
  Filter ekf(Vec<3>::Zero(), Mat<3, 3>::Zero());
  slam::FrontEndOptions options;
  options.association = slam::Association::kKnownIds;
  options.min_fusion_interval_s = 1.0;
  FrontEnd front_end(RangeBearing{}, InverseRangeBearing{}, options);
  Reading r{Vec<2>(4.0, 0.2), kNoise};
  r.id = 7;
  CHECK(front_end.update(ekf, {r}, 0.0).readings[0].outcome == slam::Outcome::kAdded);
  const Filter before = ekf;
  CHECK(front_end.update(ekf, {r}, 0.5).readings[0].outcome == slam::Outcome::kThinned);
  requireSame(ekf, before);
  CHECK(front_end.update(ekf, {r}, 1.0).readings[0].outcome == slam::Outcome::kPaired);
  CHECK(front_end.sightings(7) == 2);
}

TEST_CASE("FrontEnd's known-id outlier gate and repeated readings", "[slam][front_end]") {
  Filter ekf(Vec<3>::Zero(), Mat<3, 3>::Zero());
  ekf.add(1, InverseRangeBearing{}, Vec<2>(5.0, 0.0), kNoise);
  slam::FrontEndOptions options;
  options.association = slam::Association::kKnownIds;
  options.known_id_gate_probability = 0.999;
  FrontEnd front_end(RangeBearing{}, InverseRangeBearing{}, options);
  Reading outlier{Vec<2>(6.0, 0.0), kNoise};  // 1 m off at 5 cm noise
  outlier.id = 1;
  Reading twice{Vec<2>(3.0, 1.0), kNoise};
  twice.id = 2;
  const auto& report = front_end.update(ekf, {outlier, twice, twice}, 0.0);
  CHECK(report.readings[0].outcome == slam::Outcome::kGatedOut);
  CHECK(report.readings[0].nis > chiSquareGate(2, 0.999));
  CHECK(report.readings[1].outcome == slam::Outcome::kAdded);
  CHECK(report.readings[2].outcome == slam::Outcome::kRepeated);
  CHECK(ekf.landmarkMean<Point2>(1) == Vec<2>(5.0, 0.0));
}

// RangeBearing that refuses a negative range when it fuses (the filter checks a batch before
// fusing any of it), and counts its linearizations.
struct CheckedRangeBearing : RangeBearing {
  static constexpr const char* kName = "CheckedRangeBearing";
  static inline int linearizations = 0;
  static const char* measurementViolation(const Vec<2>& z) { return z[0] < 0.0 ? "negative range" : nullptr; }
  template <int = 0>
  Vec<2> operator()(const Vec<3>& robot, const Vec<2>& landmark, JacobianRef<2, 3> J_z_x = {},
                    JacobianRef<2, 2> J_z_l = {}) const {
    if (J_z_x || J_z_l) ++linearizations;
    return RangeBearing::operator()(robot, landmark, J_z_x, J_z_l);
  }
};
using CheckedFrontEnd = slam::FrontEnd<Filter, CheckedRangeBearing, InverseRangeBearing>;

TEST_CASE("FrontEnd reports bad readings and refused fusions as values, and a refused batch falls back",
          "[slam][front_end]") {
  Filter ekf(Vec<3>::Zero(), Mat<3, 3>::Zero());
  ekf.add(1, InverseRangeBearing{}, Vec<2>(5.0, 0.0), kNoise);
  ekf.add(2, InverseRangeBearing{}, Vec<2>(4.0, 1.0), kNoise);
  ekf.add(3, InverseRangeBearingDiameter{}, Vec<3>(3.0, -1.0, 0.4), Gaussian<3>::sigmas(Vec<3>(0.05, 0.01, 0.02)));
  ekf.add(4, InverseRangeBearing{}, Vec<2>(6.0, -0.5), kNoise);
  slam::FrontEndOptions options;
  options.association = slam::Association::kKnownIds;
  CheckedFrontEnd front_end(CheckedRangeBearing{}, InverseRangeBearing{}, options);
  const auto reading = [](std::optional<Id> id, const Vec<2>& z) {
    Reading r{z, kNoise};
    r.id = id;
    return r;
  };
  Filter by_hand = ekf;
  const std::vector<Reading> readings = {
      reading(1, Vec<2>(5.02, 0.001)),
      reading(3, Vec<2>(3.0, -1.0)),  // a tree: this model reads points only
      reading(std::nullopt, Vec<2>(2.0, 0.0)),
      reading(5, Vec<2>(std::nan(""), 0.0)),
      reading(6, Vec<2>(0.0, 0.3)),     // range 0: the inverse model refuses it
      reading(4, Vec<2>(-6.0, -0.5)),   // the model refuses it, and with it the batch
      reading(2, Vec<2>(3.98, 1.002)),
  };
  const auto& report = front_end.update(ekf, readings, 0.0);
  REQUIRE(report.batch_refused);
  CHECK(report.readings[0].outcome == slam::Outcome::kPaired);
  CHECK(report.readings[1].outcome == slam::Outcome::kRefused);
  CHECK(report.readings[1].error == ErrorCode::kWrongLandmarkType);
  CHECK(report.readings[2].error == ErrorCode::kInvalidArgument);
  CHECK(report.readings[3].error == ErrorCode::kNonFinite);
  CHECK(report.readings[4].error == ErrorCode::kDegenerateGeometry);
  CHECK(!report.readings[4].why.empty());
  CHECK(report.readings[5].outcome == slam::Outcome::kRefused);
  CHECK(report.readings[5].error == ErrorCode::kDegenerateGeometry);
  CHECK(report.readings[6].outcome == slam::Outcome::kPaired);
  // The fallback fuses the others one at a time.
  by_hand.update(RangeBearing{}, 1, readings[0].z, kNoise);
  by_hand.update(RangeBearing{}, 2, readings[6].z, kNoise);
  requireSame(ekf, by_hand);

  // Without the fallback, every reading of the refused batch is refused and nothing moves.
  options.fallback_to_sequential = false;
  CheckedFrontEnd strict(CheckedRangeBearing{}, InverseRangeBearing{}, options);
  const Filter before = ekf;
  const auto& refused = strict.update(ekf, {readings[0], readings[5]}, 0.0);
  CHECK(refused.count(slam::Outcome::kRefused) == 2);
  requireSame(ekf, before);
}

TEST_CASE("FrontEnd linearizes each landmark once per step", "[slam][front_end]") {
  const auto association =
      GENERATE(slam::Association::kKnownIds, slam::Association::kJcbb, slam::Association::kNearestNeighbor);
  const auto landmarks = world();
  Filter ekf(Vec<3>::Zero(), Mat<3, 3>::Zero());
  for (std::size_t j = 0; j < landmarks.size(); ++j)
    ekf.add(static_cast<Id>(j), InverseRangeBearing{}, RangeBearing{}(Vec<3>::Zero(), landmarks[j]), kNoise);
  slam::FrontEndOptions options;
  options.association = association;
  options.report_nis = true;
  CheckedFrontEnd front_end(CheckedRangeBearing{}, InverseRangeBearing{}, options);
  // Every landmark seen, plus one new reading far from all of them.
  const Vec<2> u(1.0, 0.1);
  ekf.predict(u, 0.5, kMotion);
  std::vector<Reading> readings =
      readingsFrom(Unicycle2D{}(Vec<3>::Zero(), u, 0.5), landmarks, association == slam::Association::kKnownIds);
  readings.push_back(Reading{Vec<2>(9.0, 2.5), kNoise, std::nullopt, Id{40}});
  CheckedRangeBearing::linearizations = 0;
  const auto& report = front_end.update(ekf, readings, 0.0);
  CHECK(report.count(slam::Outcome::kPaired) == 6);
  CHECK(report.count(slam::Outcome::kAdded) == 1);
  CHECK(CheckedRangeBearing::linearizations == 6);
  // The old path: association, the new-landmark test and the update each linearize again.
  CheckedRangeBearing::linearizations = 0;
  Filter copy = ekf;
  std::vector<Id> ids = {0, 1, 2, 3, 4, 5};
  std::vector<Vec<2>> z;
  for (const Reading& r : readings) z.push_back(r.z);
  associateJcbb(copy, CheckedRangeBearing{}, z, kNoise, ids);
  smallestNis(copy, CheckedRangeBearing{}, z.back(), kNoise, ids);
  CHECK(CheckedRangeBearing::linearizations == 12);
}

TEST_CASE("FrontEnd refuses bad options and a time that runs backwards", "[slam][front_end]") {
  const auto make = [](const slam::FrontEndOptions& o) { FrontEnd(RangeBearing{}, InverseRangeBearing{}, o); };
  slam::FrontEndOptions o;
  o.gate_probability = 1.0;
  CHECK(throwsCode([&] { make(o); }, ErrorCode::kInvalidArgument));
  o = {};
  o.new_landmark_probability = std::nan("");
  CHECK(throwsCode([&] { make(o); }, ErrorCode::kInvalidArgument));
  o = {};
  o.tentative.confirm_sightings = 0;
  CHECK(throwsCode([&] { make(o); }, ErrorCode::kInvalidArgument));
  o = {};
  o.min_fusion_interval_s = -1.0;
  CHECK(throwsCode([&] { make(o); }, ErrorCode::kInvalidArgument));
  o = {};
  o.known_id_gate_probability = 0.0;
  CHECK(throwsCode([&] { make(o); }, ErrorCode::kInvalidArgument));

  Filter ekf(Vec<3>::Zero(), Mat<3, 3>::Zero());
  FrontEnd front_end(RangeBearing{}, InverseRangeBearing{});
  front_end.update(ekf, {Reading{Vec<2>(4.0, 0.2), kNoise}}, 1.0);
  const Filter before = ekf;
  CHECK(throwsCode([&] { front_end.update(ekf, {Reading{Vec<2>(4.0, 0.2), kNoise}}, 0.5); },
                   ErrorCode::kInvalidArgument));
  CHECK(throwsCode([&] { front_end.update(ekf, {}, std::numeric_limits<double>::infinity()); },
                   ErrorCode::kInvalidArgument));
  requireSame(ekf, before);
  // A malformed reach is refused when the candidate source is made.
  CHECK(throwsCode([] { slam::candidatesInReach<Point2>(RangeBearing{}, {-1.0, 1.0, 0.0}); },
                   ErrorCode::kInvalidArgument));
}

TEST_CASE("FrontEnd asks its candidate source, and associates each reading with its own gate noise",
          "[slam][front_end]") {
  Filter ekf(Vec<3>::Zero(), Mat<3, 3>::Zero());
  ekf.add(0, InverseRangeBearing{}, Vec<2>(5.0, 0.0), kNoise);  // ahead
  ekf.add(1, InverseRangeBearing{}, Vec<2>(5.0, kPi), kNoise);  // behind
  slam::FrontEndOptions options;
  options.association = slam::Association::kNearestNeighbor;
  FrontEnd ahead_only(RangeBearing{}, InverseRangeBearing{}, options,
                      slam::candidatesInReach<Point2>(RangeBearing{}, {10.0, 0.5 * kPi}));
  Filter copy = ekf;
  const auto& report = ahead_only.update(copy, {Reading{Vec<2>(5.0, 0.001), kNoise}, Reading{Vec<2>(5.0, kPi), kNoise}}, 0.0);
  CHECK(report.candidates == 1);
  CHECK(report.readings[0].landmark == Id{0});
  CHECK(report.readings[1].outcome == slam::Outcome::kAdded);  // its landmark is not a candidate

  // 0.1 rad off: outside the gate at 0.01 rad, inside it with a gate noise of 0.05 rad.
  FrontEnd front_end(RangeBearing{}, InverseRangeBearing{}, options);
  Reading wide{Vec<2>(5.0, 0.1), kNoise};
  wide.gate_noise = Gaussian<2>::sigmas(Vec<2>(0.05, 0.05));
  const Reading narrow{Vec<2>(5.0, kPi - 0.1), kNoise};
  const auto& gated = front_end.update(ekf, {wide, narrow}, 0.0);
  CHECK(gated.readings[0].outcome == slam::Outcome::kPaired);
  CHECK(gated.readings[1].outcome != slam::Outcome::kPaired);
}

TEST_CASE("Association with one noise per measurement: equal noises give the shared-noise answer",
          "[slam][front_end][association]") {
  Filter ekf(Vec<3>::Zero(), Mat<3, 3>::Identity() * 0.01);
  const auto landmarks = world();
  for (std::size_t j = 0; j < landmarks.size(); ++j)
    ekf.add(static_cast<Id>(j), InverseRangeBearing{}, RangeBearing{}(Vec<3>::Zero(), landmarks[j]), kNoise);
  std::vector<Vec<2>> z;
  for (const Reading& r : readingsFrom(Vec<3>(0.05, -0.03, 0.01), landmarks, false)) z.push_back(r.z);
  const std::vector<Id> candidates = {0, 1, 2, 3, 4, 5};
  const std::vector<Gaussian<2>> same(z.size(), kNoise);
  CHECK(associateJcbb(ekf, RangeBearing{}, z, same, candidates) == associateJcbb(ekf, RangeBearing{}, z, kNoise, candidates));
  CHECK(associateNearestNeighbor(ekf, RangeBearing{}, z, same, candidates) ==
        associateNearestNeighbor(ekf, RangeBearing{}, z, kNoise, candidates));
  const std::vector<Gaussian<2>> too_few(2, kNoise);
  CHECK(throwsCode([&] { associateJcbb(ekf, RangeBearing{}, z, too_few, candidates); }, ErrorCode::kInvalidArgument));
  CHECK(throwsCode([&] { associateNearestNeighbor(ekf, RangeBearing{}, z, too_few, candidates); },
                   ErrorCode::kInvalidArgument));
}

}  // namespace unity_slam_front_end
