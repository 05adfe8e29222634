// The strong guarantee of the compressed EKF (Ekf::setCompression) under failed allocations:
// between global updates, predict, updates of the active part (single and batched), add and
// remove are run once per allocation they make, with that allocation failing; each time the
// filter must read exactly as it did (the corrected mean and covariance, the slots), and must
// then do the operation as an untouched copy does. See fault_injection.test.cpp for how
// allocations are failed.

#include "eigen_allocation_hook.hpp"
#include "replaced_operator_new.hpp"

#include <vector>

#include <sylva/filter/compression.hpp>
#include <sylva/filter/ekf.hpp>
#include <sylva/landmarks/point2.hpp>
#include <sylva/measurements/range_bearing.hpp>
#include <sylva/motion/unicycle_2d.hpp>

#include "filter/every_allocation_fails.hpp"
#include "filter/fault_injection_planar.hpp"
#include "sylva_catch.hpp"

namespace unity_fault_injection_compressed {

using namespace sylva;
using sylva_test::everyAllocationFails;
using sylva_test::fault_injection::kReading;
using sylva_test::fault_injection::Planar;

/// Landmarks 1..6, compressed with 1, 2 and 3 active, after a predict and an update (so the
/// passive part is stale and the region's workspaces have their size).
Planar compressedFilter() {
  Planar ekf(Vec<3>(0.5, -0.2, 0.3), Mat<3, 3>(Vec<3>(0.01, 0.02, 0.003).asDiagonal()));
  for (int i = 1; i <= 6; ++i) ekf.add(i, InverseRangeBearing{}, Vec<2>(3.0 + i, -1.2 + 0.4 * i), kReading);
  ekf.setCompression([](const Planar&, const LandmarkSlot& slot) { return slot.id <= 3; });
  ekf.predict(Vec<2>(1.0, 0.1), 0.1, Gaussian<2>::sigmas(Vec<2>(0.1, 0.05)));
  const RangeBearing model;
  ekf.update(model, 1, Vec<2>(model(ekf.robotMean(), ekf.landmarkMean<Point2>(1)) + Vec<2>(0.05, -0.01)), kReading);
  return ekf;
}

TEST_CASE("fault injection: the compressed EKF between global updates", "[filter][faults][compressed]") {
  const Planar ekf = compressedFilter();
  REQUIRE(ekf.compressed());
  REQUIRE(ekf.activeDim() == 3 + 3 * 2);
  const RangeBearing model;
  const auto reading = [&](const Planar& f, Id id) {
    return Vec<2>(model(f.robotMean(), f.landmarkMean<Point2>(id)) + Vec<2>(0.05, -0.01));
  };
  everyAllocationFails<Planar>(ekf, [](Planar& f) { f.predict(Vec<2>(1.0, 0.1), 0.1, Gaussian<2>::sigmas(Vec<2>(0.1, 0.05))); });
  everyAllocationFails<Planar>(ekf, [&](Planar& f) { f.update(model, 2, reading(f, 2), kReading); });
  everyAllocationFails<Planar>(ekf, [&](Planar& f) {
    const std::vector<Observation<RangeBearing>> batch{{1, reading(f, 1), kReading}, {3, reading(f, 3), kReading}};
    f.update(model, batch);
  });
  // add joins the active part (its accumulators grow); remove of a passive landmark moves
  // storage only; remove of an active one costs a global update.
  const long adds = everyAllocationFails<Planar>(
      ekf, [](Planar& f) { f.add(7, InverseRangeBearing{}, Vec<2>(5.0, 0.2), kReading); },
      [](const Planar& f) { return !f.contains(7); });
  CHECK(adds >= 1);
  everyAllocationFails<Planar>(ekf, [](Planar& f) { f.remove(5); }, [](const Planar& f) { return f.contains(5); });
  const long removes = everyAllocationFails<Planar>(ekf, [](Planar& f) { f.remove(2); },
                                                    [](const Planar& f) { return f.contains(2) && f.globalUpdates() == 0; });
  CHECK(removes >= 1);
}

}  // namespace unity_fault_injection_compressed
