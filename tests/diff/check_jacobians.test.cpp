// The Jacobian checker itself (sylva/testing/check_jacobians.hpp): its bound is relative to
// each entry's scale, so a 0.1% error fails whether the entries are of size 1e-3 or 1e3, while
// exact Jacobians pass at awkward scale: tiny and huge entries, exact zeros, inputs far from
// the origin, functions with large values, and near a singularity where the central
// differences' truncation error exceeds the tolerance.

#include "sylva_catch.hpp"

#include <cmath>
#include <string>

#include <sylva/core/jacobian_ref.hpp>
#include <sylva/core/types.hpp>
#include <sylva/testing/check_jacobians.hpp>

// Own namespace: the tests of a folder are compiled as one unity translation unit.
namespace unity_diff_check_jacobians {

using sylva::JacobianRef;
using sylva::Mat;
using sylva::Vec;

struct TwoStates {
  static constexpr int kDim = 2;
};

/// z = offset + scale * g(x, l), g smooth with entries of size ~1 at inputs of size ~1. The
/// analytic Jacobian can carry a planted relative error in one entry of J_z_l. g[2] does not
/// depend on x[1] nor l[0] (exact zeros), and dg[2]/dx[0] = 2 x[0] vanishes at x[0] = 0.
struct ScaledModel {
  using Robot = TwoStates;
  using Landmark = TwoStates;
  static constexpr int kDim = 3;

  double scale = 1.0;
  double offset = 0.0;
  double planted_error = 0.0;  ///< relative error put into J_z_l(1, 1)

  template <typename T>
  Vec<3, T> predict(const Vec<2, T>& x, const Vec<2, T>& l) const {
    using std::cos;
    using std::exp;
    using std::sin;
    Vec<3, T> g;
    g[0] = sin(x[0]) * l[0] + x[1] * l[1];
    g[1] = exp(0.5 * x[1]) - cos(l[0]) * l[1];
    g[2] = x[0] * x[0] + l[1];
    return Vec<3, T>::Constant(T(offset)) + T(scale) * g;
  }

  Vec<3> operator()(const Vec<2>& x,
                    const Vec<2>& l,
                    JacobianRef<3, 2> J_z_x = {},
                    JacobianRef<3, 2> J_z_l = {}) const {
    if (J_z_x) {
      *J_z_x << std::cos(x[0]) * l[0], l[1],  //
          0.0, 0.5 * std::exp(0.5 * x[1]),    //
          2.0 * x[0], 0.0;
      *J_z_x *= scale;
    }
    if (J_z_l) {
      *J_z_l << std::sin(x[0]), x[1],                                      //
          std::sin(l[0]) * l[1], -std::cos(l[0]) * (1.0 + planted_error),  //
          0.0, 1.0;
      *J_z_l *= scale;
    }
    return predict<double>(x, l);
  }
};

ScaledModel scaled(double scale, double offset = 0.0, double planted_error = 0.0) {
  ScaledModel model;
  model.scale = scale;
  model.offset = offset;
  model.planted_error = planted_error;
  return model;
}

/// z = [1 / (x[0] - l[0])]: near x[0] = l[0] the step h = 1e-6 is no longer small against
/// the distance d, and the central difference is off by ~(h / d)^2 relative.
struct NearPole {
  using Robot = TwoStates;
  using Landmark = TwoStates;
  static constexpr int kDim = 1;
  double planted_error = 0.0;

  template <typename T>
  Vec<1, T> predict(const Vec<2, T>& x, const Vec<2, T>& l) const {
    return Vec<1, T>(T(1.0) / (x[0] - l[0]) + x[1] * l[1]);
  }
  Vec<1> operator()(const Vec<2>& x,
                    const Vec<2>& l,
                    JacobianRef<1, 2> J_z_x = {},
                    JacobianRef<1, 2> J_z_l = {}) const {
    const double d = x[0] - l[0];
    if (J_z_x) *J_z_x << -(1.0 + planted_error) / (d * d), l[1];
    if (J_z_l) *J_z_l << 1.0 / (d * d), x[1];
    return predict<double>(x, l);
  }
};

/// z = [(x[0] - 1)^3, x[1] - l[1] + l[0]]: at x[0] = 1 the derivative is exactly 0 while the
/// central difference is h^2 = 1e-12 (pure truncation: the output rounds to nothing), which
/// the Richardson term |D(2h) - D(h)| = 3 h^2 covers.
struct CubicZero {
  using Robot = TwoStates;
  using Landmark = TwoStates;
  static constexpr int kDim = 2;
  template <typename T>
  Vec<2, T> predict(const Vec<2, T>& x, const Vec<2, T>& l) const {
    const T d = x[0] - T(1.0);
    return Vec<2, T>(d * d * d, x[1] - l[1] + l[0]);
  }
  Vec<2> operator()(const Vec<2>& x,
                    const Vec<2>& l,
                    JacobianRef<2, 2> J_z_x = {},
                    JacobianRef<2, 2> J_z_l = {}) const {
    const double d = x[0] - 1.0;
    if (J_z_x) *J_z_x << 3.0 * d * d, 0.0, 0.0, 1.0;
    if (J_z_l) *J_z_l << 0.0, 0.0, 1.0, -1.0;
    return predict<double>(x, l);
  }
};

const Vec<2> kRobot(0.7, -0.4);
const Vec<2> kLandmark(1.3, 0.9);

TEST_CASE("the Jacobian checker fails a 0.1% error in entries of size 1e-3 and 1e3",
          "[diff][jacobian][checker]") {
  for (const double scale : {1e-3, 1e3}) {
    INFO("entries of size ~" << scale);
    const auto good = sylva::testing::checkMeasurementJacobians(scaled(scale), kRobot, kLandmark);
    INFO(good.message());
    CHECK(good.ok);
    // |analytic - numeric| is 1e-3 of the entry: 8e-7 for scale 1e-3, which the former metric
    // |a - n| / max(1, |n|) <= 1e-6 let through.
    const auto bad =
        sylva::testing::checkMeasurementJacobians(scaled(scale, 0.0, 1e-3), kRobot, kLandmark);
    INFO(bad.message());
    CHECK_FALSE(bad.ok);
    CHECK(bad.block == "J_z_l");
    CHECK(bad.row == 1);
    CHECK(bad.col == 1);
    CHECK(bad.max_error > 10.0);  // not a near miss: the bound is far below the planted error
    // The message names the entry and gives both values, the estimate and the bound.
    const std::string text = bad.message();
    CHECK(text.find("MISMATCH in J_z_l(1, 1)") != std::string::npos);
    CHECK(text.find("numeric error estimate") != std::string::npos);
    CHECK(text.find("allowed") != std::string::npos);
  }
}

TEST_CASE("the Jacobian checker passes exact Jacobians at awkward scale",
          "[diff][jacobian][checker]") {
  struct Case {
    const char* name;
    double scale;
    Vec<2> robot;
    Vec<2> landmark;
  };
  // x[0] = 0 makes dg[2]/dx[0] = 0 at the point (besides the identically zero entries).
  const Case cases[] = {
      {"ordinary", 1.0, kRobot, kLandmark},
      {"tiny entries (1e-12)", 1e-12, kRobot, kLandmark},
      {"huge entries (1e12)", 1e12, kRobot, kLandmark},
      {"an entry zero at the point", 1.0, Vec<2>(0.0, -0.4), kLandmark},
      {"inputs far from the origin", 1.0, Vec<2>(3.0e4, -2.0), Vec<2>(-5.0e3, 1.5)},
      {"tiny entries far from the origin", 1e-9, Vec<2>(3.0e4, -2.0), Vec<2>(-5.0e3, 1.5)},
  };
  for (const Case& c : cases) {
    INFO(c.name);
    const auto exact =
        sylva::testing::checkMeasurementJacobians(scaled(c.scale), c.robot, c.landmark);
    INFO(exact.message());
    CHECK(exact.ok);
    // The bound is not vacuous at these scales: the same 0.1% error still fails.
    const auto planted =
        sylva::testing::checkMeasurementJacobians(scaled(c.scale, 0.0, 1e-3), c.robot, c.landmark);
    INFO(planted.message());
    CHECK_FALSE(planted.ok);
  }
}

TEST_CASE("the Jacobian checker passes exact Jacobians of functions with large values",
          "[diff][jacobian][checker]") {
  // An output of 1e6 rounds to ~1e-10, so central differences with step 1e-6 resolve its
  // derivative of size ~1 only to ~1e-4: the round-off term allows for that (with the margin
  // of kRoundoffFactor), and an error well above it (10%) still fails.
  const auto exact = sylva::testing::checkMeasurementJacobians(scaled(1.0, 1e6), kRobot, kLandmark);
  INFO(exact.message());
  CHECK(exact.ok);
  const auto planted =
      sylva::testing::checkMeasurementJacobians(scaled(1.0, 1e6, 0.1), kRobot, kLandmark);
  INFO(planted.message());
  CHECK_FALSE(planted.ok);
  // Large values with derivatives to match (z ~ 1e8 exp(...)) are relative again: 0.1% fails.
  const auto large = sylva::testing::checkMeasurementJacobians(scaled(1e8, 1e8), kRobot, kLandmark);
  INFO(large.message());
  CHECK(large.ok);
  const auto large_planted =
      sylva::testing::checkMeasurementJacobians(scaled(1e8, 1e8, 1e-3), kRobot, kLandmark);
  INFO(large_planted.message());
  CHECK_FALSE(large_planted.ok);
}

TEST_CASE("the Jacobian checker estimates the truncation error of the central differences",
          "[diff][jacobian][checker]") {
  SECTION("near a pole the truncation error exceeds the tolerance; the estimate covers it") {
    // d = 2e-3, h = 1e-6: the central difference is ~(h / d)^2 = 2.5e-7 relative off, so
    // with tolerance 1e-8 only the estimate lets the exact Jacobian pass.
    const Vec<2> x(1.002, 0.5);
    const Vec<2> l(1.0, 2.0);
    const auto exact = sylva::testing::checkMeasurementJacobians(NearPole{}, x, l, 1e-8);
    INFO(exact.message());
    CHECK(exact.ok);
    NearPole wrong;
    wrong.planted_error = 1e-3;
    const auto bad = sylva::testing::checkMeasurementJacobians(wrong, x, l, 1e-8);
    INFO(bad.message());
    CHECK_FALSE(bad.ok);
    CHECK(bad.block == "J_z_x");
    CHECK(bad.row == 0);
    CHECK(bad.col == 0);
  }
  SECTION("an exact zero whose central difference is h^2") {
    // Tolerance 0: the error estimate alone carries the exact Jacobian.
    const auto report = sylva::testing::checkMeasurementJacobians(
        CubicZero{}, Vec<2>(1.0, 3.0), Vec<2>(0.5, 0.25), 0.0);
    INFO(report.message());
    CHECK(report.ok);
  }
}

}  // namespace unity_diff_check_jacobians
