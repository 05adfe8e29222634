// associateNearestNeighbor: individual compatibility nearest neighbour with a chi-square gate
// (multisensor thesis eq. 2.40), each landmark used at most once (greedy by smallest NIS).

#include "sylva_catch.hpp"

#include <limits>

#include <sylva/association/nearest_neighbor.hpp>

#include "association/scenarios.hpp"
#include "filter/test_models.hpp"

using namespace sylva;
using sylva_test::ids;
using sylva_test::Pairing;
using sylva_test::Scenario;

TEST_CASE("nearest neighbour pairs well-separated landmarks", "[association][nn]") {
  const Scenario s = sylva_test::easyScenario();  // ids 1..4, 5 m apart, pose known to 1 cm
  const sylva_test::Snapshot before(s.ekf);
  // Measurements in shuffled order, each perturbed by about one sigma of the sensor.
  std::vector<Vec<2>> z = s.measureLandmarks({2, 0, 3, 1});
  z[0] += Vec<2>(0.05, -0.01);
  z[1] += Vec<2>(-0.04, 0.008);
  z[2] += Vec<2>(0.03, 0.01);
  z[3] += Vec<2>(-0.05, -0.005);
  CHECK(associateNearestNeighbor(s.ekf, RangeBearing{}, z, s.noise, s.ids) == ids({3, 1, 4, 2}));
  // Only the listed candidates are considered.
  CHECK(associateNearestNeighbor(s.ekf, RangeBearing{}, z, s.noise, {1, 4}) ==
        ids({std::nullopt, 1, 4, std::nullopt}));
  CHECK(sylva_test::Snapshot(s.ekf) == before);
}

TEST_CASE("nearest neighbour leaves a measurement outside every gate unpaired",
          "[association][nn]") {
  const Scenario s = sylva_test::easyScenario();
  std::vector<Vec<2>> z = s.measureLandmarks({0, 1});
  z.push_back(s.measure(Vec<2>(2.5, 2.5)));  // halfway between landmarks: no gate contains it
  // The same point as landmark 1 measured 0.5 m too far: 10 sigma of range noise.
  z.push_back(s.measure(s.points[0]) + Vec<2>(0.5, 0.0));
  const Pairing result = associateNearestNeighbor(s.ekf, RangeBearing{}, z, s.noise, s.ids);
  CHECK(result == ids({1, 2, std::nullopt, std::nullopt}));
  // The fourth one fails the gate on its own, whatever landmark 1 is paired with.
  const double nis = s.ekf.innovation(RangeBearing{}, 1, z[3], s.noise).nis();
  CHECK(nis > chiSquareGate(2, 0.99));
}

TEST_CASE("nearest neighbour resolves two measurements of one landmark greedily",
          "[association][nn]") {
  const Scenario s = sylva_test::easyScenario();
  // Two measurements near landmark 1; the first is closer (smaller NIS) and wins it.
  const Vec<2> z1 = s.measure(s.points[0]);
  const std::vector<Vec<2>> z = {z1 + Vec<2>(0.08, 0.0), z1 + Vec<2>(0.02, 0.0)};
  CHECK(associateNearestNeighbor(s.ekf, RangeBearing{}, z, s.noise, s.ids) ==
        ids({std::nullopt, 1}));
  // With a second landmark within the loser's gate, the loser falls back to it.
  Scenario close = sylva_test::mapPoints(Vec<3>::Zero(),
                                         Mat<3, 3>(Vec<3>(1e-4, 1e-4, 1e-6).asDiagonal()),
                                         {Vec<2>(5.0, 0.0), Vec<2>(5.0, 0.2)},
                                         Gaussian<2>::sigmas(Vec<2>(0.05, 0.02)),
                                         1);
  // Both measurements lie between the landmarks and nearer landmark 1; the second is nearer
  // still and takes it, so the first falls back to landmark 2.
  const std::vector<Vec<2>> between = {close.measure(Vec<2>(5.0, 0.09)),
                                       close.measure(Vec<2>(5.0, 0.05))};
  const auto nis = [&](int i, Id id) {
    return close.ekf
        .innovation(RangeBearing{}, id, between[static_cast<std::size_t>(i)], close.noise)
        .nis();
  };
  REQUIRE(nis(0, 1) < nis(0, 2));
  REQUIRE(nis(1, 1) < nis(0, 1));
  REQUIRE(nis(0, 2) < chiSquareGate(2, 0.99));
  CHECK(associateNearestNeighbor(close.ekf, RangeBearing{}, between, close.noise, close.ids) ==
        ids({2, 1}));
}

TEST_CASE("nearest neighbour with nothing to pair", "[association][nn]") {
  const Scenario s = sylva_test::easyScenario();
  const std::vector<Vec<2>> z = s.measureLandmarks({0, 1});
  CHECK(associateNearestNeighbor(s.ekf, RangeBearing{}, z, s.noise, {}) ==
        ids({std::nullopt, std::nullopt}));
  CHECK(associateNearestNeighbor(s.ekf, RangeBearing{}, {}, s.noise, s.ids).empty());
}

TEST_CASE("nearest neighbour rejects bad input", "[association][nn][errors]") {
  using Mixed = Ekf<Unicycle2D, Point2, sylva_test::InverseDistance2>;
  const auto noise = Gaussian<2>::sigmas(Vec<2>(0.05, 0.01));
  Mixed ekf(Vec<3>::Zero(), Mat<3, 3>(Vec<3>(1e-4, 1e-4, 1e-6).asDiagonal()));
  ekf.add(1, InverseRangeBearing{}, Vec<2>(5.0, 0.3), noise);
  ekf.add(2, sylva_test::InverseDistanceFromRangeBearing{}, Vec<2>(6.0, -0.3), noise);
  const std::vector<Vec<2>> z = {Vec<2>(5.0, 0.3)};
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();

  sylva_test::requireRejected(ekf, ErrorCode::kUnknownId, "candidate landmark id 9", [&] {
    associateNearestNeighbor(ekf, RangeBearing{}, z, noise, {1, 9});
  });
  sylva_test::requireRejected(ekf, ErrorCode::kInvalidArgument, "more than once", [&] {
    associateNearestNeighbor(ekf, RangeBearing{}, z, noise, {1, 1});
  });
  sylva_test::requireRejected(ekf, ErrorCode::kWrongLandmarkType, "InverseDistance2", [&] {
    associateNearestNeighbor(ekf, RangeBearing{}, z, noise, {1, 2});
  });
  sylva_test::requireRejected(ekf, ErrorCode::kNonFinite, "measurement 1", [&] {
    associateNearestNeighbor(ekf, RangeBearing{}, {z[0], Vec<2>(nan, 0.0)}, noise, {1});
  });
  sylva_test::requireRejected(ekf, ErrorCode::kNonFinite, "measurement 0", [&] {
    associateNearestNeighbor(ekf, RangeBearing{}, {Vec<2>(5.0, inf)}, noise, {1});
  });
  for (const double p : {0.0, 1.0, -0.1, 1.5, nan}) {
    sylva_test::requireRejected(ekf, ErrorCode::kInvalidArgument, "gate_probability", [&] {
      associateNearestNeighbor(ekf, RangeBearing{}, z, noise, {1}, p);
    });
  }
}
