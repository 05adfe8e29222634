// smallestNis: the smallest NIS of one measurement over candidate landmarks (the test before
// a measurement starts a new landmark).

#include "sylva_catch.hpp"

#include <limits>
#include <vector>

#include <sylva/association/smallest_nis.hpp>

#include "association/scenarios.hpp"

using namespace sylva;
using sylva_test::Scenario;

TEST_CASE("smallestNis is the NIS of the closest candidate, infinity without candidates", "[association]") {
  const Scenario s = sylva_test::easyScenario();  // ids 1..4, 5 m apart
  const sylva_test::Snapshot before(s.ekf);
  const Vec<2> z = s.measure(s.points[1]) + Vec<2>(0.05, -0.01);  // landmark 2, one sigma off
  double expected = std::numeric_limits<double>::infinity();
  for (const Id id : s.ids) expected = std::min(expected, s.ekf.innovation(RangeBearing{}, id, z, s.noise).nis());
  CHECK(smallestNis(s.ekf, RangeBearing{}, z, s.noise, s.ids) == expected);
  CHECK(expected == s.ekf.innovation(RangeBearing{}, 2, z, s.noise).nis());
  CHECK(expected < 3.0);
  // Without landmark 2 the closest candidate is 5 m away: far beyond any gate.
  CHECK(smallestNis(s.ekf, RangeBearing{}, z, s.noise, std::vector<Id>{1, 3, 4}) > 100.0);
  CHECK(smallestNis(s.ekf, RangeBearing{}, z, s.noise, std::vector<Id>{}) == std::numeric_limits<double>::infinity());
  CHECK(sylva_test::Snapshot(s.ekf) == before);
}

TEST_CASE("smallestNis names an unknown candidate and leaves the filter unchanged", "[association]") {
  const Scenario s = sylva_test::easyScenario();
  const sylva_test::Snapshot before(s.ekf);
  const Vec<2> z = s.measure(s.points[0]);
  try {
    smallestNis(s.ekf, RangeBearing{}, z, s.noise, std::vector<Id>{1, 99});
    FAIL("an unknown candidate was accepted");
  } catch (const Error& e) {
    CHECK(e.code() == ErrorCode::kUnknownId);
    CHECK(std::string(e.what()).find("99") != std::string::npos);
  }
  CHECK(sylva_test::Snapshot(s.ekf) == before);
}
