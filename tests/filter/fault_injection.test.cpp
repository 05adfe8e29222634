// The strong guarantee under failed allocations: every operation that changes the filter
// (predict, update in each form, add, remove, reparametrize) is run once per allocation it
// makes, with that allocation failing (std::bad_alloc); each time the filter must be exactly
// as it was, and must then do the operation as an untouched copy does.
//
// Allocations are counted in the replaced global operator new (replaced_operator_new.hpp)
// and, for Eigen's own (which go through malloc), through EIGEN_RUNTIME_NO_MALLOC: while a
// fault is armed Eigen's malloc check fails on every heap allocation, and
// eigen_allocation_hook.hpp routes that check to the same counter, which throws
// std::bad_alloc at the chosen allocation (as Eigen itself does when malloc fails).

#include "eigen_allocation_hook.hpp"
#include "replaced_operator_new.hpp"

#include <string>
#include <vector>

#include <sylva/monocular.hpp>

#include "copy_init.hpp"
#include "filter/monocular_rig.hpp"
#include "filter/every_allocation_fails.hpp"
#include "filter/fault_injection_planar.hpp"
#include "sylva_catch.hpp"

using sylva_test::everyAllocationFails;
using namespace sylva_test::fault_injection;
using sylva_test::g_other_eigen_asserts;

using namespace sylva;

namespace {

/// A planar filter with landmarks 1..6 and no update yet (its workspaces are empty, so the
/// operations below allocate them).
template <typename Filter>
Filter planarFilter() {
  Filter ekf(Vec<3>(0.5, -0.2, 0.3), Mat<3, 3>(Vec<3>(0.01, 0.02, 0.003).asDiagonal()));
  for (int i = 1; i <= 6; ++i) ekf.add(i, InverseRangeBearing{}, Vec<2>(3.0 + i, -1.2 + 0.4 * i), kReading);
  return ekf;
}

}  // namespace

TEST_CASE("fault injection: predict, add and remove leave the filter as it was when an allocation fails",
          "[filter][faults]") {
  const Planar ekf = planarFilter<Planar>();
  everyAllocationFails<Planar>(ekf, [](Planar& f) { f.predict(Vec<2>(1.0, 0.1), 0.1, Gaussian<2>::sigmas(Vec<2>(0.1, 0.05))); });
  // add: the storage grows (capacity 1 more than the state would not do), a slot and an id
  // are recorded.
  const long adds = everyAllocationFails<Planar>(
      ekf, [](Planar& f) { f.add(7, InverseRangeBearing{}, Vec<2>(5.0, 0.2), kReading); },
      [](const Planar& f) { return !f.contains(7); });
  CHECK(adds >= 1);
  // remove a landmark from the middle: the blocks after it move up.
  everyAllocationFails<Planar>(ekf, [](Planar& f) { f.remove(3); }, [](const Planar& f) { return f.contains(3); });
}

TEST_CASE("fault injection: every form of update leaves the filter as it was when an allocation fails",
          "[filter][faults]") {
  const Planar ekf = planarFilter<Planar>();
  const RangeBearing model;
  const auto reading = [&](const Planar& f, Id id) {
    return Vec<2>(model(f.robotMean(), f.landmarkMean<Point2>(id)) + Vec<2>(0.05, -0.01));
  };
  const long single = everyAllocationFails<Planar>(ekf, [&](Planar& f) { f.update(model, 2, reading(f, 2), kReading); });
  CHECK(single >= 1);  // the first update sizes its workspaces
  everyAllocationFails<Planar>(ekf, [&](Planar& f) {
    const std::vector<Observation<RangeBearing>> batch{{1, reading(f, 1), kReading}, {4, reading(f, 4), kReading},
                                                       {6, reading(f, 6), kReading}};
    f.update(model, batch);
  });
  for (const LinearizationPoint point :
       {LinearizationPoint::kFirstEstimates, LinearizationPoint::kInvariant, LinearizationPoint::kIterated}) {
    Planar moded = ekf;
    moded.setLinearizationPoint(point);
    everyAllocationFails<Planar>(moded, [&](Planar& f) { f.update(model, 5, reading(f, 5), kReading); });
  }
  const PlanarJoseph joseph = planarFilter<PlanarJoseph>();
  everyAllocationFails<PlanarJoseph>(joseph, [&](PlanarJoseph& f) {
    f.update(model, 2, Vec<2>(model(f.robotMean(), f.landmarkMean<Point2>(2)) + Vec<2>(0.05, -0.01)), kReading);
  });
  everyAllocationFails<PlanarJoseph>(joseph, [&](PlanarJoseph& f) {
    const std::vector<Observation<RangeBearing>> batch{
        {1, Vec<2>(model(f.robotMean(), f.landmarkMean<Point2>(1)) + Vec<2>(0.02, 0.0)), kReading},
        {3, Vec<2>(model(f.robotMean(), f.landmarkMean<Point2>(3)) - Vec<2>(0.02, 0.01)), kReading}};
    f.update(model, batch);
  });
}

TEST_CASE("fault injection: the monocular filter's updates and reparametrizations", "[filter][faults]") {
  using Mono = Ekf<OnManifold<ConstantVelocity3D>, InverseDepth, Point3, TreeXYZR>;
  const sylva_test::MonocularRig rig;
  Mono ekf(rig.x0, Mat<12, 12>::Identity() * 1e-4);
  std::vector<Vec<4>> trees;
  for (int i = 0; i < 6; ++i) trees.emplace_back(6.0 + 0.8 * i, -2.0 + 0.7 * i, 0.0, 0.2 + 0.01 * i);
  for (int i = 0; i < 6; ++i) ekf.add(i, rig.init, rig.init.measurement(rig.xyz_model(ConstantVelocity3D::pose(rig.x0), Vec<3>(trees[i].head<3>()))), rig.init.noise(rig.pixel));
  ekf.reparametrize(4, InverseDepthToPoint3<ConstantVelocity3D>{});
  everyAllocationFails<Mono>(ekf, [&](Mono& f) { f.reparametrize(1, InverseDepthToPoint3<ConstantVelocity3D>{}); },
                             [](const Mono& f) { return f.holds<InverseDepth>(1); });
  everyAllocationFails<Mono>(ekf, [&](Mono& f) { f.reparametrize(4, InverseTreeWidth(rig.camera), rig.width_model(ConstantVelocity3D::pose(rig.x0), trees[4]), rig.pixel_width); },
                             [](const Mono& f) { return f.holds<Point3>(4); });
  for (const LinearizationPoint point : {LinearizationPoint::kCurrentEstimate, LinearizationPoint::kObservabilityConstrained}) {
    Mono moded = ekf;
    moded.setLinearizationPoint(point);
    everyAllocationFails<Mono>(moded, [&](Mono& f) {
      f.update(rig.id_model, 2, rig.id_model(ConstantVelocity3D::pose(f.robotMean()), f.landmarkMean<InverseDepth>(2)) + Vec<2>(0.4, -0.3), rig.pixel);
    });
    everyAllocationFails<Mono>(moded, [&](Mono& f) {
      f.update(rig.xyz_model, 4, rig.xyz_model(ConstantVelocity3D::pose(f.robotMean()), f.landmarkMean<Point3>(4)) + Vec<2>(-0.3, 0.2), rig.pixel);
    });
  }
  CHECK(g_other_eigen_asserts.load() == 0);
}
