// RangeBearing and InverseRangeBearing: Jacobians against central differences at ordinary
// and awkward geometry, the model laws (inverse then forward is the identity), wrapping,
// degenerate input.

#include <limits>

#include <sylva/measurements/range_bearing.hpp>
#include <sylva/testing/check_jacobians.hpp>

#include "autodiff_check.hpp"
#include "sylva_catch.hpp"

// Own namespace: the tests of a folder are compiled as one unity translation unit.
namespace unity_measurements_range_bearing {

using namespace sylva;

namespace {
struct Geometry {
  const char* name;
  Vec<3> robot;
  Vec<2> landmark;
};

// Ordinary and awkward configurations: landmark straight behind (bearing at the +-pi seam),
// heading at the seam, on the axes (dx = 0 or dy = 0), very close (1 mm), very far (10 km).
const Geometry kGeometries[] = {
    {"ordinary", Vec<3>(1.0, 2.0, 0.3), Vec<2>(5.0, 4.0)},
    {"behind the robot, bearing near +pi", Vec<3>(0.0, 0.0, 0.0), Vec<2>(-5.0, 1e-7)},
    {"behind the robot, bearing near -pi", Vec<3>(0.0, 0.0, 0.0), Vec<2>(-5.0, -1e-7)},
    {"heading at the seam", Vec<3>(2.0, -1.0, kPi - 1e-9), Vec<2>(-3.0, -1.5)},
    {"straight ahead on the x axis", Vec<3>(0.0, 0.0, 0.0), Vec<2>(7.0, 0.0)},
    {"straight left on the y axis", Vec<3>(0.0, 0.0, 0.0), Vec<2>(0.0, 7.0)},
    // The central differences' step (1e-6 * max(1, |x|)) is no longer small against 1 mm:
    // their truncation error (~ (h / d)^2) is covered by the checker's error estimate.
    {"1 mm away", Vec<3>(3.0, 3.0, -2.0), Vec<2>(3.0007, 3.0007)},
    {"10 km away", Vec<3>(0.0, 0.0, 1.0), Vec<2>(7000.0, -7000.0)},
};
}  // namespace

TEST_CASE("RangeBearing Jacobians match numerical differentiation", "[measurements][jacobian]") {
  for (const Geometry& g : kGeometries) {
    INFO(g.name);
    const auto analytic = testing::checkMeasurementJacobians(RangeBearing{}, g.robot, g.landmark);
    INFO(analytic.message());
    CHECK(analytic.ok);
    // The automatic Jacobian of the same prediction agrees with the analytic one to round-off.
    sylva_test::checkMeasurementAgainstAutoDiff(RangeBearing{}, g.robot, g.landmark);
  }
}

TEST_CASE("InverseRangeBearing Jacobians match numerical differentiation", "[measurements][jacobian]") {
  const std::pair<Vec<3>, Vec<2>> cases[] = {
      {Vec<3>(1.0, 2.0, 0.3), Vec<2>(5.0, 0.4)},
      {Vec<3>(0.0, 0.0, kPi), Vec<2>(3.0, kPi)},       // world angle 2 pi
      {Vec<3>(-4.0, 1.0, -3.0), Vec<2>(1e-3, -1.0)},   // very close
      {Vec<3>(0.0, 0.0, 0.0), Vec<2>(2e4, 1.5)},       // very far
  };
  for (const auto& [robot, z] : cases) {
    INFO("robot " << robot.transpose() << ", z " << z.transpose());
    const auto report = testing::checkInverseJacobians(InverseRangeBearing{}, robot, z, 1e-6);
    INFO(report.message());
    CHECK(report.ok);
  }
}

TEST_CASE("inverse then forward model is the identity", "[measurements][laws]") {
  for (const Geometry& g : kGeometries) {
    INFO(g.name);
    const Vec<2> z = RangeBearing{}(g.robot, g.landmark);
    const Vec<2> l = InverseRangeBearing{}(g.robot, z);
    CHECK((l - g.landmark).norm() <= 1e-9 * std::max(1.0, g.landmark.norm()));
    const Vec<2> z_again = RangeBearing{}(g.robot, l);
    CHECK(RangeBearing{}.residual(z_again, z).norm() <= 1e-9 * std::max(1.0, z[0]));
  }
}

TEST_CASE("the bearing and the residual are wrapped to the half-open interval from -pi to pi", "[measurements]") {
  const Vec<2> z = RangeBearing{}(Vec<3>(0.0, 0.0, 0.0), Vec<2>(-5.0, -1e-9));
  CHECK(z[1] > -kPi);
  CHECK(z[1] <= kPi);
  CHECK(z[1] == Approx(-kPi).margin(1e-6));
  // Measured just across the seam: the innovation is small, not 2 pi.
  const Vec<2> nu = RangeBearing{}.residual(Vec<2>(5.0, kPi - 0.01), Vec<2>(5.0, -kPi + 0.01));
  CHECK(nu[1] == Approx(-0.02).margin(1e-12));
  CHECK(wrapAngle(3 * kPi) == Approx(kPi));
  CHECK(wrapAngle(-kPi) == Approx(kPi));
  CHECK(wrapAngle(7.0) == Approx(7.0 - 2 * kPi));
}

TEST_CASE("degenerate and non-finite input is rejected with a reason", "[measurements][errors]") {
  using Catch::Matchers::Contains;
  CHECK_THROWS_WITH(RangeBearing{}(Vec<3>(1.0, 1.0, 0.0), Vec<2>(1.0, 1.0)), Contains("coincides with the robot"));
  CHECK_THROWS_WITH(RangeBearing{}(Vec<3>(1.0, 1.0, 0.0), Vec<2>(std::numeric_limits<double>::quiet_NaN(), 1.0)),
                    Contains("non-finite"));
  CHECK_THROWS_WITH(InverseRangeBearing{}(Vec<3>::Zero(), Vec<2>(-1.0, 0.0)), Contains("must be > 0"));
  CHECK_THROWS_WITH(InverseRangeBearing{}(Vec<3>::Zero(), Vec<2>(1.0, INFINITY)), Contains("not finite"));
}

TEST_CASE("RangeBearing with a sensor mount: geometry, Jacobians, laws", "[measurements][jacobian][mount]") {
  const Vec<2> mounts[] = {Vec<2>(3.78, 0.5), Vec<2>(3.78, -0.5), Vec<2>(-1.0, 0.0), Vec<2>(0.0, 2.0)};
  for (const Vec<2>& m : mounts) {
    const RangeBearing model(m);
    const InverseRangeBearing inverse(m);
    for (const Geometry& g : kGeometries) {
      INFO(g.name << ", mount " << m.transpose());
      const auto report = testing::checkMeasurementJacobians(model, g.robot, g.landmark);
      INFO(report.message());
      CHECK(report.ok);
      sylva_test::checkMeasurementAgainstAutoDiff(model, g.robot, g.landmark);
      // The range is measured from the sensor: s = p + R(theta) m.
      const double c = std::cos(g.robot[2]);
      const double s = std::sin(g.robot[2]);
      const Vec<2> sensor(g.robot[0] + c * m[0] - s * m[1], g.robot[1] + s * m[0] + c * m[1]);
      const Vec<2> z = model(g.robot, g.landmark);
      CHECK(z[0] == Approx((g.landmark - sensor).norm()).epsilon(1e-12));
      // Inverse then forward is the identity; the inverse Jacobians are right too.
      const Vec<2> l = inverse(g.robot, z);
      CHECK((l - g.landmark).norm() <= 1e-9 * std::max(1.0, g.landmark.norm()));
      const auto inv = testing::checkInverseJacobians(inverse, g.robot, z, 1e-6);
      INFO(inv.message());
      CHECK(inv.ok);
    }
  }
  // A car heading north with the laser 3.78 m ahead and 0.5 m to the left sees a tree 10 m
  // ahead of the laser at bearing 0 and range 10.
  const Vec<2> z = RangeBearing(Vec<2>(3.78, 0.5))(Vec<3>(0.0, 0.0, 0.5 * kPi), Vec<2>(-0.5, 13.78));
  CHECK(z[0] == Approx(10.0));
  CHECK(z[1] == Approx(0.0).margin(1e-12));
  CHECK_THROWS_WITH(RangeBearing(Vec<2>(1.0, 0.0))(Vec<3>::Zero(), Vec<2>(1.0, 0.0)),
                    Catch::Matchers::Contains("coincides with the sensor"));
  CHECK_THROWS_WITH(RangeBearing(Vec<2>(NAN, 0.0)), Catch::Matchers::Contains("mount is not finite"));
}

TEST_CASE("a zero mount gives bit-identical results to the unmounted model", "[measurements][mount]") {
  const RangeBearing plain;
  const RangeBearing zero(Vec<2>::Zero());
  for (const Geometry& g : kGeometries) {
    Mat<2, 3> J_x, Z_x;
    Mat<2, 2> J_l, Z_l;
    const Vec<2> a = plain(g.robot, g.landmark, J_x, J_l);
    const Vec<2> b = zero(g.robot, g.landmark, Z_x, Z_l);
    CHECK((a.array() == b.array()).all());
    CHECK((J_x.array() == Z_x.array()).all());
    CHECK((J_l.array() == Z_l.array()).all());
    Mat<2, 3> I_x, K_x;
    Mat<2, 2> I_z, K_z;
    const Vec<2> l1 = InverseRangeBearing{}(g.robot, a, I_x, I_z);
    const Vec<2> l2 = InverseRangeBearing(Vec<2>::Zero())(g.robot, a, K_x, K_z);
    CHECK((l1.array() == l2.array()).all());
    CHECK((I_x.array() == K_x.array()).all());
  }
}

}  // namespace unity_measurements_range_bearing
