// TreeXYR: the 2D tree landmark [x, y, r]; its domain r > 0 is enforced by the filter on
// initialization and on every update (kOutOfDomain, filter unchanged).

#include <sylva/filter/ekf.hpp>
#include <sylva/landmarks/tree_xyr.hpp>
#include <sylva/measurements/range_bearing_diameter.hpp>
#include <sylva/motion/unicycle_2d.hpp>

#include "error_helpers.hpp"
#include "sylva_catch.hpp"

TEST_CASE("TreeXYR: layout and domain", "[landmarks][tree2d]") {
  STATIC_REQUIRE(sylva::TreeXYR::kDim == 3);
  CHECK(sylva::TreeXYR::domainViolation(sylva::Vec<3>(1.0, 2.0, 0.3)) == nullptr);
  CHECK(sylva::TreeXYR::domainViolation(sylva::Vec<3>(1.0, 2.0, 0.0)) != nullptr);
  CHECK(sylva::TreeXYR::domainViolation(sylva::Vec<3>(1.0, 2.0, -0.1)) != nullptr);
  CHECK(sylva::TreeXYR::domainViolation(sylva::Vec<3>(1.0, 2.0, NAN)) != nullptr);
}

TEST_CASE("TreeXYR in a filter: a radius pushed to zero or below is refused", "[landmarks][tree2d]") {
  using namespace sylva;
  Ekf<Unicycle2D, TreeXYR> ekf(Vec<3>::Zero(), Mat<3, 3>::Zero());
  const auto loose = Gaussian<3>::sigmas(Vec<3>(0.1, 0.01, 0.5));
  ekf.add(1, InverseRangeBearingDiameter{}, Vec<3>(10.0, 0.0, 0.2), loose);
  const Eigen::VectorXd mean = ekf.mean();
  const auto tight = Gaussian<3>::sigmas(Vec<3>(0.1, 0.01, 1e-3));
  CHECK(sylva_test::throwsCode([&] { ekf.update(RangeBearingDiameter{}, 1, Vec<3>(10.0, 0.0, -1.0), tight); },
                               ErrorCode::kOutOfDomain));
  CHECK((ekf.mean().array() == mean.array()).all());
  ekf.update(RangeBearingDiameter{}, 1, Vec<3>(10.0, 0.0, 0.3), tight);
  CHECK(ekf.landmarkMean<TreeXYR>(1)[2] == Approx(0.15).margin(1e-3));
}
