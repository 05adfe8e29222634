// associateKnownIds: ids the filter holds are passed through, the others become nullopt.

#include "sylva_catch.hpp"

#include <sylva/association/known_ids.hpp>

#include "association/scenarios.hpp"

using namespace sylva;
using sylva_test::ids;

TEST_CASE("known ids: mapped ids are paired, new ids are not", "[association][known_ids]") {
  const sylva_test::Scenario s = sylva_test::easyScenario();  // ids 1..4
  const sylva_test::Snapshot before(s.ekf);

  CHECK(associateKnownIds(s.ekf, {3, 7, 1, -2, 4}) == ids({3, std::nullopt, 1, std::nullopt, 4}));
  // The same id reported twice is paired twice (two observations of one landmark).
  CHECK(associateKnownIds(s.ekf, {2, 2}) == ids({2, 2}));
  CHECK(associateKnownIds(s.ekf, {}).empty());

  const sylva_test::Filter empty(Vec<3>::Zero(), Mat<3, 3>::Zero());
  CHECK(associateKnownIds(empty, {1, 2}) == ids({std::nullopt, std::nullopt}));
  CHECK(sylva_test::Snapshot(s.ekf) == before);
}

TEST_CASE("known ids: a removed landmark is no longer paired", "[association][known_ids]") {
  sylva_test::Scenario s = sylva_test::easyScenario();
  s.ekf.remove(2);
  CHECK(associateKnownIds(s.ekf, {1, 2, 3}) == ids({1, std::nullopt, 3}));
}
