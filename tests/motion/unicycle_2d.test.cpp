// Unicycle2D: eq. 2.12-2.14, Jacobians against central differences at ordinary and awkward
// inputs (standing still, turning on the spot, heading at the +-pi seam, long steps).

#include <sylva/motion/unicycle_2d.hpp>
#include <sylva/testing/check_jacobians.hpp>

#include "motion_autodiff.hpp"
#include "sylva_catch.hpp"

using namespace sylva;

TEST_CASE("Unicycle2D follows eq. 2.12-2.14", "[motion]") {
  const Vec<3> next = Unicycle2D{}(Vec<3>(1.0, 2.0, 0.5), Vec<2>(2.0, 0.4), 0.5);
  const double heading = 0.5 + 0.5 * 0.5 * 0.4;
  CHECK(next[0] == Approx(1.0 + 0.5 * 2.0 * std::cos(heading)));
  CHECK(next[1] == Approx(2.0 + 0.5 * 2.0 * std::sin(heading)));
  CHECK(next[2] == Approx(0.5 + 0.5 * 0.4));
  // Crossing the seam keeps theta in (-pi, pi].
  const Vec<3> wrapped = Unicycle2D{}(Vec<3>(0.0, 0.0, 3.1), Vec<2>(0.0, 1.0), 0.1);
  CHECK(wrapped[2] == Approx(3.2 - 2 * kPi));
}

TEST_CASE("Unicycle2D Jacobians match numerical and automatic differentiation", "[motion][jacobian]") {
  struct Case {
    const char* name;
    Vec<3> x;
    Vec<2> u;
    double dt;
  };
  const Case cases[] = {
      {"ordinary", Vec<3>(1.0, 2.0, 0.3), Vec<2>(1.0, 0.2), 0.1},
      {"standing still", Vec<3>(1.0, 2.0, 0.3), Vec<2>(0.0, 0.0), 0.1},
      {"turning on the spot", Vec<3>(-3.0, 0.5, -1.0), Vec<2>(0.0, 1.5), 0.2},
      {"heading at the seam", Vec<3>(0.0, 0.0, kPi - 1e-3), Vec<2>(2.0, 0.5), 0.1},
      {"long step", Vec<3>(5.0, 5.0, 2.0), Vec<2>(3.0, -2.0), 2.0},
      {"zero time step", Vec<3>(5.0, 5.0, 2.0), Vec<2>(3.0, -2.0), 0.0},
  };
  for (const Case& c : cases) {
    INFO(c.name);
    sylva_test::requireMotionJacobians(Unicycle2D{}, c.x, c.u, c.dt);
  }
}

namespace unity_motion_unicycle_2d_checker {

/// A unicycle whose mean prediction drifts 1 mm from its own propagate (what the filter runs
/// would then not be what the Jacobians describe).
struct DriftingUnicycle : sylva::Unicycle2D {
  State operator()(const State& x, const Control& u, double dt, sylva::JacobianRef<3, 3> J_x = {},
                   sylva::JacobianRef<3, 2> J_n = {}) const {
    State next = Unicycle2D::operator()(x, u, dt, J_x, J_n);
    next[0] += 1e-3;
    return next;
  }
};

}  // namespace unity_motion_unicycle_2d_checker

TEST_CASE("checkMotionJacobians flags a mean prediction that is not the model's propagate", "[motion][jacobian]") {
  const sylva::Vec<3> x(1.0, 2.0, 0.3);
  const sylva::Vec<2> u(1.0, 0.2);
  const auto good = sylva::testing::checkMotionJacobians(sylva::Unicycle2D{}, x, u, 0.1);
  CHECK(good.ok);
  const auto bad = sylva::testing::checkMotionJacobians(unity_motion_unicycle_2d_checker::DriftingUnicycle{}, x, u, 0.1);
  INFO(bad.message());
  CHECK_FALSE(bad.ok);
  CHECK(bad.block == "f - propagate");
}
