// atan2Generic: the value and derivatives of atan2 for automatic-differentiation scalars,
// against central differences, in all four quadrants and on the axes.

#include <cmath>

#include <Eigen/Core>  // unsupported/Eigen/AutoDiff needs it first
#include <unsupported/Eigen/AutoDiff>

#include <sylva/core/scalar.hpp>
#include <sylva/core/types.hpp>

#include "sylva_catch.hpp"

namespace unity_core_scalar {
using Dual = Eigen::AutoDiffScalar<sylva::Vec<2>>;
}  // namespace unity_core_scalar

using unity_core_scalar::Dual;

TEST_CASE("atan2Generic matches std::atan2 and its derivatives in every quadrant", "[core]") {
  const double h = 1e-6;
  for (const auto& p : {sylva::Vec<2>(1.0, 2.0), sylva::Vec<2>(-3.0, 0.5), sylva::Vec<2>(-0.2, -0.7),
                        sylva::Vec<2>(4.0, -1e-3), sylva::Vec<2>(0.0, 2.0), sylva::Vec<2>(-5.0, 0.0)}) {
    const double x = p[0], y = p[1];
    CHECK(sylva::atan2Generic(y, x) == std::atan2(y, x));
    const Dual yd(y, sylva::Vec<2>(1.0, 0.0));
    const Dual xd(x, sylva::Vec<2>(0.0, 1.0));
    const Dual a = sylva::atan2Generic(yd, xd);
    CHECK(a.value() == std::atan2(y, x));
    const double d_dy = (std::atan2(y + h, x) - std::atan2(y - h, x)) / (2 * h);
    const double d_dx = (std::atan2(y, x + h) - std::atan2(y, x - h)) / (2 * h);
    if (!(x < 0.0 && y == 0.0)) {  // on the branch cut the central difference straddles +-pi
      CHECK(std::abs(a.derivatives()[0] - d_dy) < 1e-7);
      CHECK(std::abs(a.derivatives()[1] - d_dx) < 1e-7);
    }
    CHECK(std::abs(a.derivatives()[0] - x / (x * x + y * y)) < 1e-15);
  }
}
