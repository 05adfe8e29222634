// wrapAngle at the edges of (-pi, pi] and far outside it; kRadPerDeg.

#include <cmath>

#include <sylva/core/angles.hpp>

#include "sylva_catch.hpp"

TEST_CASE("wrapAngle keeps pi, sends -pi to pi and maps far angles by whole turns", "[core]") {
  using sylva::kPi;
  using sylva::wrapAngle;
  CHECK(wrapAngle(0.0) == 0.0);
  CHECK(wrapAngle(kPi) == Approx(kPi));
  CHECK(wrapAngle(-kPi) == Approx(kPi));  // the interval is open at -pi
  CHECK(wrapAngle(3.0 * kPi) == Approx(kPi));
  CHECK(wrapAngle(-3.0 * kPi + 0.25) == Approx(-kPi + 0.25));
  CHECK(wrapAngle(2.0 * kPi + 0.1) == Approx(0.1));
  // Many turns away: the result still lies in the interval and differs by whole turns.
  for (const double a : {1e3 + 0.3, -1e3 - 0.3, 123.456 * kPi}) {
    const double w = wrapAngle(a);
    CHECK(w > -kPi);
    CHECK(w <= kPi);
    const double turns = (a - w) / (2.0 * kPi);
    CHECK(turns == Approx(std::round(turns)).margin(1e-9));
  }
}

TEST_CASE("kRadPerDeg converts degrees to radians", "[core]") {
  CHECK(180.0 * sylva::kRadPerDeg == Approx(sylva::kPi));
  CHECK(90.0 * sylva::kRadPerDeg == Approx(sylva::kPi / 2.0));
}
