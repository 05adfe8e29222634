// Ackermann2DWithBias: the car with an encoder speed scale error and a steering offset as
// states. Jacobians against central differences and forward-mode automatic differentiation
// at ordinary and awkward inputs; the pose part is Ackermann2D's at the corrected control;
// the pose view and its Jacobian.

#include <cmath>

#include <sylva/diff/numeric_diff.hpp>
#include <sylva/motion/ackermann_2d.hpp>
#include <sylva/motion/ackermann_2d_with_bias.hpp>
#include <sylva/testing/check_jacobians.hpp>

#include "error_helpers.hpp"
#include "motion_autodiff.hpp"
#include "sylva_catch.hpp"

namespace unity_motion_ackermann_2d_with_bias {

using namespace sylva;

const Ackermann2DWithBias kBiasedCar(2.83, 0.76);  // Victoria Park: wheelbase L, encoder offset H

struct Case {
  const char* name;
  Vec<5> x;
  Vec<2> u;
  double dt;
};

const Case kCases[] = {
    {"ordinary", (Vec<5>() << 1.0, 2.0, 0.3, 0.02, -0.01).finished(), Vec<2>(3.0, 0.2), 0.025},
    {"no bias", (Vec<5>() << 1.0, 2.0, 0.3, 0.0, 0.0).finished(), Vec<2>(3.0, 0.2), 0.2},
    {"standing still", (Vec<5>() << 1.0, 2.0, 0.3, 0.05, 0.03).finished(), Vec<2>(0.0, 0.1), 0.025},
    {"near full lock", (Vec<5>() << -3.0, 0.5, -1.0, -0.04, 0.05).finished(), Vec<2>(2.0, -0.6), 0.2},
    {"reversing", (Vec<5>() << 0.0, 0.0, 2.0, 0.1, -0.02).finished(), Vec<2>(-1.0, 0.3), 0.2},
    {"heading at the seam", (Vec<5>() << 0.0, 0.0, kPi - 1e-3, 0.0, 0.01).finished(), Vec<2>(5.0, 0.5), 0.1},
    {"long step", (Vec<5>() << 5.0, 5.0, 2.0, 0.02, 0.02).finished(), Vec<2>(6.0, -0.4), 2.0},
    {"zero time step", (Vec<5>() << 5.0, 5.0, 2.0, 0.02, 0.02).finished(), Vec<2>(3.0, -0.2), 0.0},
};

}  // namespace unity_motion_ackermann_2d_with_bias

using namespace unity_motion_ackermann_2d_with_bias;

TEST_CASE("Ackermann2DWithBias: the pose moves as Ackermann2D under the corrected control", "[motion][ackermann]") {
  for (const Case& c : kCases) {
    INFO(c.name);
    const Vec<5> next = kBiasedCar(c.x, c.u, c.dt);
    const Vec<3> car = kBiasedCar.car()(Vec<3>(c.x.head<3>()), Vec<2>(c.u[0] * (1.0 + c.x[3]), c.u[1] + c.x[4]), c.dt);
    CHECK((next.head<3>() - car).norm() < 1e-14);
    CHECK(next[3] == c.x[3]);
    CHECK(next[4] == c.x[4]);
  }
}

TEST_CASE("Ackermann2DWithBias Jacobians match numerical and automatic differentiation",
          "[motion][jacobian][ackermann]") {
  for (const Case& c : kCases) {
    INFO(c.name);
    sylva_test::requireMotionJacobians(kBiasedCar, c.x, c.u, c.dt);
  }
}

TEST_CASE("Ackermann2DWithBias: the pose view and its Jacobian", "[motion]") {
  sylva_test::requirePlanarPoseView<Ackermann2DWithBias>(kCases[0].x);
}

TEST_CASE("Ackermann2DWithBias refuses a corrected steering outside the car's domain", "[motion][errors][ackermann]") {
  using sylva_test::throwsCode;
  // The measured steering is inside the domain, the offset takes it out.
  Vec<5> x = Vec<5>::Zero();
  x[4] = 0.4;
  CHECK(throwsCode([&] { kBiasedCar(x, Vec<2>(1.0, 1.3), 0.1); }, ErrorCode::kDegenerateGeometry));
  CHECK(throwsCode([] { Ackermann2DWithBias(-1.0); }, ErrorCode::kInvalidArgument));
}
