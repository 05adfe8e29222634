// interpolateLaserRange (eq. 3.4'): exact on a flat wall at any resolution and incidence,
// derivatives against central differences, degenerate input.

#include <cmath>
#include <limits>

#include <sylva/core/angles.hpp>
#include <sylva/laser_camera/range_interpolation.hpp>

#include "error_helpers.hpp"
#include "sylva_catch.hpp"

namespace unity_measurements_laser_camera_interpolation {

using namespace sylva;
using sylva_test::throwsCode;

/// Range along bearing phi to the line n . p = d (n unit normal): d / (n . u(phi)).
double wallRange(double phi, double normal_angle, double distance) {
  return distance / std::cos(phi - normal_angle);
}

TEST_CASE("interpolateLaserRange is exact on a flat wall at any resolution", "[measurements][laser_camera]") {
  const double deg = kPi / 180.0;
  for (double resolution : {0.25 * deg, 0.5 * deg, 1.0 * deg, 5.0 * deg, 20.0 * deg}) {
    for (double normal : {0.0, 30.0 * deg, -60.0 * deg, 75.0 * deg}) {
      for (double a_i : {-10.0 * deg, 0.0, 12.3 * deg}) {
        const double a_j = a_i + resolution;
        if (std::cos(a_i - normal) < 0.05 || std::cos(a_j - normal) < 0.05) continue;
        const double r_i = wallRange(a_i, normal, 3.0);
        const double r_j = wallRange(a_j, normal, 3.0);
        for (double t : {0.0, 0.1, 0.5, 0.77, 1.0}) {
          const double phi = a_i + t * resolution;
          INFO("resolution " << resolution / deg << " deg, normal " << normal / deg << " deg, t " << t);
          const auto ir = interpolateLaserRange(phi, a_i, r_i, a_j, r_j);
          CHECK(ir.range_m == Approx(wallRange(phi, normal, 3.0)).epsilon(1e-12));
          CHECK(ir.incidence_rad == Approx(std::abs(wrapAngle(phi - normal))).margin(1e-9));
          // Beam order does not matter.
          CHECK(interpolateLaserRange(phi, a_j, r_j, a_i, r_i).range_m == Approx(ir.range_m).epsilon(1e-12));
        }
      }
    }
  }
}

TEST_CASE("interpolateLaserRange derivatives match central differences", "[measurements][laser_camera]") {
  struct Case {
    double phi, a_i, r_i, a_j, r_j;
  };
  const double d = 0.5 * kPi / 180.0;
  const Case cases[] = {
      {0.1 + 0.3 * d, 0.1, 4.0, 0.1 + d, 4.1},   // ordinary
      {-0.7 + 0.5 * d, -0.7, 2.0, -0.7 + d, 2.0},  // equal readings
      {0.2 + 1.4 * d, 0.2, 3.0, 0.2 + d, 3.05},   // extrapolation beyond a_j
      {0.0, -d, 1.0, d, 1.3},                      // oblique surface
  };
  for (const Case& c : cases) {
    const auto ir = interpolateLaserRange(c.phi, c.a_i, c.r_i, c.a_j, c.r_j);
    const double h = 1e-6;
    const double dphi = (interpolateLaserRange(c.phi + h, c.a_i, c.r_i, c.a_j, c.r_j).range_m -
                         interpolateLaserRange(c.phi - h, c.a_i, c.r_i, c.a_j, c.r_j).range_m) / (2 * h);
    const double dri = (interpolateLaserRange(c.phi, c.a_i, c.r_i + h, c.a_j, c.r_j).range_m -
                        interpolateLaserRange(c.phi, c.a_i, c.r_i - h, c.a_j, c.r_j).range_m) / (2 * h);
    const double drj = (interpolateLaserRange(c.phi, c.a_i, c.r_i, c.a_j, c.r_j + h).range_m -
                        interpolateLaserRange(c.phi, c.a_i, c.r_i, c.a_j, c.r_j - h).range_m) / (2 * h);
    CHECK(ir.J_r_input[0] == Approx(dphi).margin(1e-5));
    CHECK(ir.J_r_input[1] == Approx(dri).margin(1e-6));
    CHECK(ir.J_r_input[2] == Approx(drj).margin(1e-6));
  }
}

TEST_CASE("interpolateLaserRange refuses degenerate and non-finite input", "[measurements][laser_camera]") {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  CHECK(throwsCode([&] { interpolateLaserRange(nan, 0.0, 1.0, 0.01, 1.0); }, ErrorCode::kNonFinite));
  CHECK(throwsCode([&] { interpolateLaserRange(0.0, 0.0, std::numeric_limits<double>::infinity(), 0.01, 1.0); },
                   ErrorCode::kNonFinite));
  CHECK(throwsCode([&] { interpolateLaserRange(0.0, 0.0, 1.0, 0.0, 1.0); }, ErrorCode::kDegenerateGeometry));
  CHECK(throwsCode([&] { interpolateLaserRange(0.0, 0.0, -1.0, 0.01, 1.0); }, ErrorCode::kDegenerateGeometry));
  // Extrapolating far beyond the beams along a surface that runs away from the ray.
  CHECK(throwsCode([&] { interpolateLaserRange(0.5, 0.0, 1.0, 0.01, 1.5); }, ErrorCode::kDegenerateGeometry));
}

}  // namespace unity_measurements_laser_camera_interpolation
