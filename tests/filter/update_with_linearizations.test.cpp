// Ekf::update with linearizations made beforehand (by `linearize` or a CompatibilityTable):
// the same posterior bit for bit, and a refusal, with the filter unchanged, for a
// linearization made at another state or for another landmark.

#include <vector>

#include <sylva/association/compatibility_table.hpp>
#include <sylva/filter/ekf.hpp>
#include <sylva/measurements/range_bearing.hpp>
#include <sylva/motion/unicycle_2d.hpp>

#include "error_helpers.hpp"
#include "sylva_catch.hpp"

// Own namespace: the tests of a folder are compiled as one unity translation unit.
namespace unity_filter_update_with_linearizations {

using namespace sylva;
using sylva_test::throwsCode;
using Filter = Ekf<Unicycle2D, Point2>;

Filter mapOfThree(LinearizationPoint point) {
  Filter ekf(Vec<3>::Zero(), Mat<3, 3>::Identity() * 1e-4);
  ekf.setLinearizationPoint(point);
  const Gaussian<2> R = Gaussian<2>::sigmas(Vec<2>(0.05, 0.01));
  ekf.add(0, InverseRangeBearing{}, Vec<2>(4.0, 0.3), R);
  ekf.add(1, InverseRangeBearing{}, Vec<2>(6.0, -0.8), R);
  ekf.add(2, InverseRangeBearing{}, Vec<2>(3.0, 1.9), R);
  ekf.predict(Vec<2>(1.0, 0.2), 0.5, Gaussian<2>::sigmas(Vec<2>(0.1, 0.05)));
  return ekf;
}

TEST_CASE("Ekf::update with linearizations gives the update's own result", "[filter][update]") {
  const auto point = GENERATE(LinearizationPoint::kCurrentEstimate, LinearizationPoint::kFirstEstimates,
                              LinearizationPoint::kIterated);
  Filter plain = mapOfThree(point);
  Filter given = plain;
  const Gaussian<2> R = Gaussian<2>::sigmas(Vec<2>(0.05, 0.01));
  const std::vector<Observation<RangeBearing>> observations = {
      {2, Vec<2>(2.7, 1.8), R}, {0, Vec<2>(3.6, 0.2), R}, {1, Vec<2>(5.4, -0.95), R}};
  std::vector<Linearization<RangeBearing, 3>> lins;
  for (const auto& o : observations) lins.push_back(given.linearize(RangeBearing{}, o.id));
  plain.update(RangeBearing{}, observations);
  given.update(RangeBearing{}, observations, lins);
  CHECK(given.mean() == plain.mean());
  CHECK(given.covariance() == plain.covariance());

  // From a compatibility table (one noise for all), in candidate order.
  Filter from_table = mapOfThree(point);
  const auto table = compatibilityTable(from_table, RangeBearing{}, {Vec<2>(2.7, 1.8)}, R, {2, 0, 1});
  from_table.update(RangeBearing{}, observations, table.lins);
  CHECK(from_table.mean() == plain.mean());
}

TEST_CASE("Ekf::update refuses a linearization of another state or landmark", "[filter][update]") {
  Filter ekf = mapOfThree(LinearizationPoint::kCurrentEstimate);
  const Gaussian<2> R = Gaussian<2>::sigmas(Vec<2>(0.05, 0.01));
  const std::vector<Observation<RangeBearing>> one = {{0, Vec<2>(3.6, 0.2), R}};
  const auto lin = ekf.linearize(RangeBearing{}, 0);
  const Filter before = ekf;

  // Of landmark 1, handed in for landmark 0.
  CHECK(throwsCode([&] { ekf.update(RangeBearing{}, one, {ekf.linearize(RangeBearing{}, 1)}); },
                   ErrorCode::kInvalidArgument));
  // As many linearizations as observations.
  CHECK(throwsCode([&] { ekf.update(RangeBearing{}, one, {lin, lin}); }, ErrorCode::kInvalidArgument));
  CHECK(ekf.mean() == before.mean());
  CHECK(ekf.covariance() == before.covariance());

  // Made before a predict: stale.
  ekf.predict(Vec<2>(1.0, 0.0), 0.1, Gaussian<2>::sigmas(Vec<2>(0.1, 0.05)));
  const Filter predicted = ekf;
  CHECK(throwsCode([&] { ekf.update(RangeBearing{}, one, {lin}); }, ErrorCode::kInvalidArgument));
  CHECK(ekf.mean() == predicted.mean());
  // Made by another filter in the same state, then that filter moved on: refused too.
  Filter twin = ekf;
  const auto twin_lin = twin.linearize(RangeBearing{}, 0);
  twin.update(RangeBearing{}, one);
  ekf.update(RangeBearing{}, one, {twin_lin});  // still the state it was made at: accepted
  CHECK(ekf.mean() == twin.mean());
  CHECK(throwsCode([&] { ekf.update(RangeBearing{}, one, {twin_lin}); }, ErrorCode::kInvalidArgument));
  // Every change of the state takes a new revision.
  const auto r0 = ekf.revision();
  ekf.add(7, InverseRangeBearing{}, Vec<2>(2.0, 0.1), R);
  const auto r1 = ekf.revision();
  ekf.remove(7);
  CHECK(r1 != r0);
  CHECK(ekf.revision() != r1);
}

}  // namespace unity_filter_update_with_linearizations
