// associateJcbb: joint compatibility branch and bound (Neira & Tardos 2001). The required
// case: a map where nearest neighbour pairs every measurement with the wrong landmark and
// JCBB pairs them correctly.

#include "sylva_catch.hpp"

#include <algorithm>
#include <limits>

#include <sylva/association/jcbb.hpp>
#include <sylva/association/joint_compatibility.hpp>
#include <sylva/association/nearest_neighbor.hpp>
#include <sylva/sim/random.hpp>

#include "association/scenarios.hpp"
#include "filter/test_models.hpp"

using namespace sylva;
using sylva_test::ids;
using sylva_test::Pairing;
using sylva_test::Scenario;

namespace {

/// 0 .. n-1 in an order drawn with `rng` (Fisher-Yates; std::shuffle is not reproducible
/// across standard libraries).
std::vector<int> shuffledIndices(sim::Rng& rng, int n) {
  std::vector<int> order(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) order[static_cast<std::size_t>(k)] = k;
  for (int k = n - 1; k > 0; --k) {
    const int pick = std::min(k, static_cast<int>(rng.uniform01() * (k + 1)));
    std::swap(order[static_cast<std::size_t>(k)], order[static_cast<std::size_t>(pick)]);
  }
  return order;
}

int pairings(const Pairing& p) {
  return static_cast<int>(std::count_if(p.begin(), p.end(), [](const auto& x) { return bool(x); }));
}

}  // namespace

// Why nearest neighbour fails here (see treeRowScenario for the numbers). The robot drove
// 1 m along a row of trees, but its wheels slipped by 0.7 m: it believes it is at y = 1 m
// while it is at y = 0.3 m, and its along-track uncertainty relative to the map is 0.5 m.
// Seen from the believed pose, every measured tree appears 0.7 m further along the row
// (a translation of the robot moves all measured points by the same vector). The trees are
// 0.9 to 1.25 m apart, so each measurement lands 0.2 to 0.55 m before the next tree and
// 0.7 m after its own: individually it is closer, in Mahalanobis distance, to the next tree,
// and ICNN shifts the whole pairing by one tree (the last measurement finds its tree taken).
// Both pairings are individually plausible because the robot is that uncertain. What tells
// them apart is the pattern: the true pairing has the same 0.7 m innovation for every tree,
// one robot correction explains all of them; the shifted pairing leaves innovations that
// differ by 0.2 to 0.35 m between trees whose relative positions are known to a few
// centimetres (the spacings are uneven), so its joint NIS is far above the gate.
TEST_CASE("JCBB pairs correctly where nearest neighbour shifts every pairing",
          "[association][jcbb]") {
  const Scenario s = sylva_test::treeRowScenario(0.7);
  const sylva_test::Snapshot before(s.ekf);
  const RangeBearing model;
  const double p = 0.99;

  SECTION("five trees measured") {
    const std::vector<Vec<2>> z = s.measureLandmarks({0, 1, 2, 3, 4});
    const Pairing truth = ids({10, 11, 12, 13, 14});
    const Pairing shifted = ids({11, 12, 13, 14, std::nullopt});

    // The premise: each measurement is individually compatible with its own tree, but
    // nearer the next one.
    for (std::size_t i = 0; i < 4; ++i) {
      const double own = s.ekf.innovation(model, *truth[i], z[i], s.noise).nis();
      const double next = s.ekf.innovation(model, *shifted[i], z[i], s.noise).nis();
      CAPTURE(i, own, next);
      CHECK(own < chiSquareGate(2, p));
      CHECK(next < own);
    }
    const Pairing nn = associateNearestNeighbor(s.ekf, model, z, s.noise, s.ids, p);
    CHECK(nn == shifted);
    CHECK(nn != truth);

    // The joint test accepts the truth and rejects the shifted pairing.
    CHECK(jointNis(s.ekf, model, z, s.noise, truth) < chiSquareGate(2 * 5, p));
    CHECK(jointNis(s.ekf, model, z, s.noise, shifted) > chiSquareGate(2 * 4, p));
    CHECK_FALSE(jointlyCompatible(s.ekf, model, z, s.noise, shifted, p));

    CHECK(associateJcbb(s.ekf, model, z, s.noise, s.ids, p) == truth);
  }

  SECTION("four trees measured: both pairings have four pairs, only the joint test decides") {
    const std::vector<Vec<2>> z = s.measureLandmarks({0, 1, 2, 3});
    const Pairing truth = ids({10, 11, 12, 13});
    const Pairing shifted = ids({11, 12, 13, 14});
    CHECK(associateNearestNeighbor(s.ekf, model, z, s.noise, s.ids, p) == shifted);
    CHECK(jointlyCompatible(s.ekf, model, z, s.noise, truth, p));
    CHECK_FALSE(jointlyCompatible(s.ekf, model, z, s.noise, shifted, p));
    CHECK(associateJcbb(s.ekf, model, z, s.noise, s.ids, p) == truth);
  }

  CHECK(sylva_test::Snapshot(s.ekf) == before);
}

TEST_CASE("JCBB leaves clutter unpaired", "[association][jcbb]") {
  const RangeBearing model;

  SECTION("clutter outside every gate") {
    const Scenario s = sylva_test::easyScenario();
    std::vector<Vec<2>> z = s.measureLandmarks({1, 3});
    z.insert(z.begin() + 1, s.measure(Vec<2>(2.5, 2.5)));
    CHECK(associateJcbb(s.ekf, model, z, s.noise, s.ids) == ids({2, std::nullopt, 4}));
  }

  SECTION("clutter inside a gate but jointly incompatible") {
    // The row of trees, robot where it believes it is, but still 0.5 m uncertain along the
    // row. Three trees are measured, plus a spurious return 0.35 m beyond tree 14: alone it
    // is compatible with tree 14 (0.7 sigma), jointly it is not, since the three true
    // measurements pin the robot to a few centimetres along the row.
    const Scenario s = sylva_test::treeRowScenario(0.0);
    std::vector<Vec<2>> z = s.measureLandmarks({0, 1, 2});
    z.push_back(s.measure(s.points[4] + Vec<2>(0.0, 0.35)));
    REQUIRE(s.ekf.innovation(model, 14, z[3], s.noise).nis() < chiSquareGate(2, 0.99));
    CHECK(associateNearestNeighbor(s.ekf, model, z, s.noise, s.ids) == ids({10, 11, 12, 14}));
    CHECK(associateJcbb(s.ekf, model, z, s.noise, s.ids) == ids({10, 11, 12, std::nullopt}));
  }
}

TEST_CASE("JCBB with nothing to pair", "[association][jcbb]") {
  const Scenario s = sylva_test::easyScenario();
  const std::vector<Vec<2>> z = s.measureLandmarks({0, 1, 2});
  CHECK(associateJcbb(s.ekf, RangeBearing{}, z, s.noise, {}) ==
        ids({std::nullopt, std::nullopt, std::nullopt}));
  CHECK(associateJcbb(s.ekf, RangeBearing{}, {}, s.noise, s.ids).empty());
  // Candidates that do not include the measured landmarks: all outside the gates.
  CHECK(associateJcbb(s.ekf, RangeBearing{}, s.measureLandmarks({0, 1}), s.noise, {3, 4}) ==
        ids({std::nullopt, std::nullopt}));
}

TEST_CASE("JCBB does not change the filter", "[association][jcbb]") {
  const Scenario s = sylva_test::treeRowScenario(0.7);
  const std::vector<Vec<2>> z = s.measureLandmarks({4, 2, 0, 3, 1});
  const sylva_test::Snapshot before(s.ekf);
  const Pairing result = associateJcbb(s.ekf, RangeBearing{}, z, s.noise, s.ids);
  CHECK(result == ids({14, 12, 10, 13, 11}));  // measurement order does not matter
  CHECK(sylva_test::Snapshot(s.ekf) == before);
  (void)associateNearestNeighbor(s.ekf, RangeBearing{}, z, s.noise, s.ids);
  (void)jointNis(s.ekf, RangeBearing{}, z, s.noise, result);
  CHECK(sylva_test::Snapshot(s.ekf) == before);
}

TEST_CASE("JCBB rejects bad input", "[association][jcbb][errors]") {
  using Mixed = Ekf<Unicycle2D, Point2, sylva_test::InverseDistance2>;
  const auto noise = Gaussian<2>::sigmas(Vec<2>(0.05, 0.01));
  Mixed ekf(Vec<3>::Zero(), Mat<3, 3>(Vec<3>(1e-4, 1e-4, 1e-6).asDiagonal()));
  ekf.add(1, InverseRangeBearing{}, Vec<2>(5.0, 0.3), noise);
  ekf.add(2, sylva_test::InverseDistanceFromRangeBearing{}, Vec<2>(6.0, -0.3), noise);
  const std::vector<Vec<2>> z = {Vec<2>(5.0, 0.3)};
  const double nan = std::numeric_limits<double>::quiet_NaN();

  sylva_test::requireRejected(ekf, ErrorCode::kUnknownId, "candidate landmark id 9", [&] {
    associateJcbb(ekf, RangeBearing{}, z, noise, {9, 1});
  });
  // Checked up front, even when there is nothing to measure.
  sylva_test::requireRejected(ekf, ErrorCode::kUnknownId, "associateJcbb", [&] {
    associateJcbb(ekf, RangeBearing{}, {}, noise, {9});
  });
  sylva_test::requireRejected(ekf, ErrorCode::kInvalidArgument, "more than once", [&] {
    associateJcbb(ekf, RangeBearing{}, z, noise, {1, 1});
  });
  sylva_test::requireRejected(ekf, ErrorCode::kWrongLandmarkType, "InverseDistance2", [&] {
    associateJcbb(ekf, RangeBearing{}, z, noise, {2});
  });
  sylva_test::requireRejected(ekf, ErrorCode::kNonFinite, "measurement 1", [&] {
    associateJcbb(ekf, RangeBearing{}, {z[0], Vec<2>(1.0, nan)}, noise, {1});
  });
  for (const double p : {0.0, 1.0, -0.1, 1.5, nan}) {
    sylva_test::requireRejected(ekf, ErrorCode::kInvalidArgument, "gate_probability", [&] {
      associateJcbb(ekf, RangeBearing{}, z, noise, {1}, p);
    });
  }
}

// ---------------------------------------------------------------- against exhaustive search

namespace {

/// Exhaustive search with the definition JCBB implements: every pairing individually
/// compatible, every landmark used once, every partial hypothesis (pairings taken in
/// measurement order) jointly compatible; the most pairings, then the smallest joint NIS.
/// Each hypothesis is evaluated from scratch by `jointNis` (dense Cholesky), independent of
/// the incremental factor inside JCBB.
struct Exhaustive {
  const sylva_test::Filter& ekf;
  const std::vector<Vec<2>>& z;
  const Gaussian<2>& noise;
  const std::vector<Id>& candidates;
  double p;
  Pairing current;
  Pairing best;
  int best_pairings = 0;
  double best_nis = 0.0;

  void search(std::size_t i, int k) {
    if (i == z.size()) {
      const double nis = jointNis(ekf, RangeBearing{}, z, noise, current);
      if (k > best_pairings || (k == best_pairings && nis < best_nis)) {
        best = current;
        best_pairings = k;
        best_nis = nis;
      }
      return;
    }
    for (const Id id : candidates) {
      if (std::find(current.begin(), current.end(), std::optional<Id>(id)) != current.end())
        continue;
      if (!(ekf.innovation(RangeBearing{}, id, z[i], noise).nis() < chiSquareGate(2, p))) continue;
      current[i] = id;
      if (jointlyCompatible(ekf, RangeBearing{}, z, noise, current, p)) search(i + 1, k + 1);
      current[i] = std::nullopt;
    }
    search(i + 1, k);
  }

  Pairing run() {
    current.assign(z.size(), std::nullopt);
    best = current;
    search(0, 0);
    return best;
  }
};

}  // namespace

TEST_CASE("JCBB finds the hypothesis an exhaustive search finds", "[association][jcbb]") {
  // Random small maps with an uncertain robot, so that measurements often gate with several
  // landmarks and the search has real choices to make. Seeded: the same cases every run.
  sim::Rng rng(20240611);
  const auto sensor = Gaussian<2>::sigmas(Vec<2>(0.1, 0.03));
  int ambiguous = 0;
  int nn_differs = 0;
  for (int trial = 0; trial < 60; ++trial) {
    std::vector<Vec<2>> points;
    const int landmark_count = 4 + trial % 3;
    for (int k = 0; k < landmark_count; ++k)
      points.push_back(Vec<2>(rng.uniform(2.0, 7.0), rng.uniform(-3.0, 3.0)));
    Scenario s = sylva_test::mapPoints(
        Vec<3>::Zero(), Mat<3, 3>(Vec<3>(0.01, 0.01, 1e-4).asDiagonal()), points, sensor, 1);
    const auto slip = Gaussian<2>::sigmas(Vec<2>(0.4, 0.05));
    s.ekf.predict(Vec<2>::Zero(), 1.0, slip);
    const Vec<2> e = rng.sample(slip);  // the true slip: along-track and heading
    s.true_pose = Vec<3>(e[0], 0.0, e[1]);

    std::vector<int> order = shuffledIndices(rng, landmark_count);
    order.resize(static_cast<std::size_t>(3 + trial % 2));
    std::vector<Vec<2>> z = s.measureLandmarks(order);
    for (Vec<2>& zi : z) zi += rng.sample(sensor);
    if (trial % 4 == 0)
      z.push_back(s.measure(Vec<2>(rng.uniform(2.0, 7.0), rng.uniform(-3.0, 3.0))));

    Exhaustive exhaustive{s.ekf, z, sensor, s.ids, 0.99, {}, {}, 0, 0.0};
    const Pairing expected = exhaustive.run();
    const Pairing jcbb = associateJcbb(s.ekf, RangeBearing{}, z, sensor, s.ids);
    CAPTURE(trial, exhaustive.best_pairings, exhaustive.best_nis);
    REQUIRE(jcbb == expected);

    for (const Vec<2>& zi : z) {
      int gated = 0;
      for (const Id id : s.ids)
        gated += s.ekf.innovation(RangeBearing{}, id, zi, sensor).nis() < chiSquareGate(2, 0.99);
      if (gated > 1) {
        ++ambiguous;
        break;
      }
    }
    if (associateNearestNeighbor(s.ekf, RangeBearing{}, z, sensor, s.ids) != jcbb) ++nn_differs;
  }
  // The cases were not all trivial.
  CHECK(ambiguous > 20);
  CHECK(nn_differs > 3);
}

TEST_CASE("JCBB on 20 measurements and 30 candidates", "[association][jcbb]") {
  // Thirty trees on a jittered 3 m grid ahead of the robot; it measures twenty of them (in a
  // random order) and three spurious returns from the middle of grid cells, at least 1.4 m
  // from any tree, after an odometry slip of 0.4 m and 0.01 rad.
  sim::Rng rng(7);
  std::vector<Vec<2>> points;
  for (int row = 0; row < 6; ++row)
    for (int col = 0; col < 5; ++col)
      points.push_back(Vec<2>(3.0 + 3.0 * row + rng.uniform(-0.5, 0.5),
                              -6.0 + 3.0 * col + rng.uniform(-0.5, 0.5)));
  const auto sensor = Gaussian<2>::sigmas(Vec<2>(0.05, 0.005));
  Scenario s = sylva_test::mapPoints(
      Vec<3>::Zero(), Mat<3, 3>(Vec<3>(0.01, 0.01, 1e-4).asDiagonal()), points, sensor, 100);
  s.ekf.predict(Vec<2>::Zero(), 1.0, Gaussian<2>::sigmas(Vec<2>(0.3, 0.01)));
  s.true_pose = Vec<3>(-0.4, 0.0, 0.01);

  std::vector<int> observed = shuffledIndices(rng, 30);
  observed.resize(20);
  Pairing truth;
  for (const int k : observed) truth.push_back(s.ids[static_cast<std::size_t>(k)]);
  std::vector<Vec<2>> z = s.measureLandmarks(observed);
  for (Vec<2>& zi : z) zi += rng.sample(sensor);
  // (cell of the 5 x 4 grid of cell centres between the trees, position in the scan)
  for (const auto& [cell, at] : {std::pair<int, int>{3, 2}, {11, 9}, {17, 21}}) {
    const Vec<2> centre(4.5 + 3.0 * (cell / 4), -4.5 + 3.0 * (cell % 4));
    z.insert(z.begin() + at, s.measure(centre));
    truth.insert(truth.begin() + at, std::nullopt);
  }
  const Pairing jcbb = associateJcbb(s.ekf, RangeBearing{}, z, sensor, s.ids);
  CHECK(jcbb == truth);
  CHECK(pairings(jcbb) == 20);
  CHECK(jointlyCompatible(s.ekf, RangeBearing{}, z, sensor, jcbb));
}
