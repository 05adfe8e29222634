// RangeBearingDiameter and InverseRangeBearingDiameter (TreeXYR landmarks): Jacobians against
// central differences and automatic differentiation, with and without a sensor mount, at ordinary and awkward geometry;
// inverse then forward is the identity; bad input is refused and leaves the filter unchanged.

#include <cmath>
#include <limits>

#include <sylva/filter/ekf.hpp>
#include <sylva/measurements/range_bearing_diameter.hpp>
#include <sylva/motion/ackermann_2d.hpp>
#include <sylva/motion/unicycle_2d.hpp>
#include <sylva/testing/check_jacobians.hpp>

#include "autodiff_check.hpp"
#include "error_helpers.hpp"
#include "sylva_catch.hpp"

namespace unity_measurements_range_bearing_diameter {

using namespace sylva;

struct TreeGeometry {
  const char* name;
  Vec<3> robot;
  Vec<3> tree;
};

const TreeGeometry kTrees[] = {
    {"ordinary", Vec<3>(1.0, 2.0, 0.3), Vec<3>(15.0, 9.0, 0.2)},
    {"behind the sensor, bearing at the seam", Vec<3>(0.0, 0.0, 0.0), Vec<3>(-20.0, 1e-7, 0.3)},
    {"heading at the seam", Vec<3>(2.0, -1.0, kPi - 1e-9), Vec<3>(-30.0, -1.5, 0.05)},
    {"close", Vec<3>(3.0, 3.0, -2.0), Vec<3>(0.5, -0.5, 0.4)},
    {"far", Vec<3>(0.0, 0.0, 1.0), Vec<3>(700.0, -700.0, 0.7)},
    {"thin trunk", Vec<3>(0.0, 0.0, 1.0), Vec<3>(5.0, 5.0, 1e-4)},
};
const Vec<2> kMounts[] = {Vec<2>::Zero(), Vec<2>(3.78, 0.5), Vec<2>(3.78, -0.5)};

}  // namespace unity_measurements_range_bearing_diameter

using namespace unity_measurements_range_bearing_diameter;

TEST_CASE("RangeBearingDiameter: prediction and Jacobians", "[measurements][jacobian][tree2d]") {
  for (const Vec<2>& m : kMounts) {
    const RangeBearingDiameter model(m);
    const InverseRangeBearingDiameter inverse(m);
    for (const TreeGeometry& g : kTrees) {
      INFO(g.name << ", mount " << m.transpose());
      const Vec<3> z = model(g.robot, g.tree);
      const Vec<2> rb = RangeBearing(m)(g.robot, Vec<2>(g.tree.head<2>()));
      CHECK(z[0] == rb[0]);
      CHECK(z[1] == rb[1]);
      CHECK(z[2] == 2.0 * g.tree[2]);
      const auto report = testing::checkMeasurementJacobians(model, g.robot, g.tree, 1e-6);
      INFO(report.message());
      CHECK(report.ok);
      // And against forward-mode automatic differentiation of predict<T>, exact to round-off.
      sylva_test::checkMeasurementAgainstAutoDiff(model, g.robot, g.tree);
      const auto inv = testing::checkInverseJacobians(inverse, g.robot, z, 1e-6);
      INFO(inv.message());
      CHECK(inv.ok);
      const Vec<3> l = inverse(g.robot, z);
      CHECK((l - g.tree).norm() <= 1e-9 * std::max(1.0, g.tree.norm()));
    }
  }
  // The bearing residual is wrapped, range and diameter are not.
  const Vec<3> nu = RangeBearingDiameter{}.residual(Vec<3>(5.0, kPi - 0.01, 0.4), Vec<3>(4.0, -kPi + 0.01, 0.5));
  CHECK(nu[0] == Approx(1.0));
  CHECK(nu[1] == Approx(-0.02).margin(1e-12));
  CHECK(nu[2] == Approx(-0.1));
}

TEST_CASE("RangeBearingDiameter: bad input is refused with a reason", "[measurements][errors][tree2d]") {
  using sylva_test::throwsCode;
  CHECK(throwsCode([] { RangeBearingDiameter{}(Vec<3>(1.0, 1.0, 0.0), Vec<3>(1.0, 1.0, 0.2)); },
                   ErrorCode::kDegenerateGeometry));
  CHECK(throwsCode([] { InverseRangeBearingDiameter{}(Vec<3>::Zero(), Vec<3>(5.0, 0.1, 0.0)); }, ErrorCode::kOutOfDomain));
  CHECK(throwsCode([] { InverseRangeBearingDiameter{}(Vec<3>::Zero(), Vec<3>(5.0, 0.1, -0.3)); }, ErrorCode::kOutOfDomain));
  CHECK(throwsCode([] { InverseRangeBearingDiameter{}(Vec<3>::Zero(), Vec<3>(0.0, 0.1, 0.3)); },
                   ErrorCode::kDegenerateGeometry));
  CHECK(throwsCode([] { InverseRangeBearingDiameter{}(Vec<3>::Zero(), Vec<3>(5.0, NAN, 0.3)); }, ErrorCode::kNonFinite));
  CHECK(TreeXYR::domainViolation(Vec<3>(1.0, 2.0, 0.0)) != nullptr);
  CHECK(TreeXYR::domainViolation(Vec<3>(1.0, 2.0, 0.1)) == nullptr);
}

TEST_CASE("Ekf<Ackermann2D, TreeXYR>: add, update, and refused updates leave the filter unchanged", "[measurements][filter][tree2d]") {
  using sylva_test::throwsCode;
  const Vec<2> mount(3.78, 0.5);
  const RangeBearingDiameter model(mount);
  const InverseRangeBearingDiameter inverse(mount);
  const auto noise = Gaussian<3>::sigmas(Vec<3>(0.3, 0.01, 0.1));
  Ekf<Ackermann2D, TreeXYR> ekf(Vec<3>(0.0, 0.0, 0.3), Mat<3, 3>::Identity() * 1e-4, Ackermann2D(2.83, 0.76));
  const Vec<3> tree(20.0, 12.0, 0.25);
  ekf.add(1, inverse, model(ekf.robotMean(), tree), noise);
  ekf.add(2, inverse, model(ekf.robotMean(), Vec<3>(25.0, 2.0, 0.15)), noise);
  CHECK((ekf.landmarkMean<TreeXYR>(1) - tree).norm() < 1e-9);
  ekf.predict(Vec<2>(2.0, 0.05), 0.2, Gaussian<2>::sigmas(Vec<2>(0.1, 0.01)));
  ekf.update(model, 1, model(ekf.robotMean(), tree) + Vec<3>(0.05, 0.002, 0.04), noise);
  CHECK(ekf.landmarkMean<TreeXYR>(1)[2] > 0.25);  // a wider trunk was measured
  // The filter serves a Unicycle2D too (the model is written for Pose2D).
  Ekf<Unicycle2D, TreeXYR> other(Vec<3>::Zero(), Mat<3, 3>::Zero());
  other.add(7, InverseRangeBearingDiameter{}, Vec<3>(10.0, 0.2, 0.5), noise);
  CHECK(other.landmarkMean<TreeXYR>(7)[2] == 0.25);

  const Eigen::VectorXd mean = ekf.mean();
  const Eigen::MatrixXd cov = ekf.covariance();
  const auto unchanged = [&] {
    return (ekf.mean().array() == mean.array()).all() && (ekf.covariance().array() == cov.array()).all();
  };
  // A diameter so small that the posterior radius would be negative.
  const auto tight = Gaussian<3>::sigmas(Vec<3>(0.3, 0.01, 1e-4));
  CHECK(throwsCode([&] { ekf.update(model, 2, Vec<3>(25.0, 0.0, -2.0), tight); }, ErrorCode::kOutOfDomain));
  CHECK(unchanged());
  CHECK(throwsCode([&] { ekf.update(model, 3, Vec<3>(25.0, 0.0, 0.3), noise); }, ErrorCode::kUnknownId));
  CHECK(throwsCode([&] { ekf.update(model, 1, Vec<3>(NAN, 0.0, 0.3), noise); }, ErrorCode::kNonFinite));
  CHECK(throwsCode([&] { ekf.add(3, inverse, Vec<3>(10.0, 0.0, 0.0), noise); }, ErrorCode::kOutOfDomain));
  CHECK(throwsCode([&] { ekf.add(1, inverse, Vec<3>(10.0, 0.0, 0.3), noise); }, ErrorCode::kDuplicateId));
  CHECK(unchanged());
}
