// Ackermann2D: the car model of the Victoria Park experiments; Jacobians against central
// differences at ordinary and awkward inputs; the encoder-offset correction; the domain.

#include <cmath>

#include <sylva/filter/ekf.hpp>
#include <sylva/landmarks/point2.hpp>
#include <sylva/motion/ackermann_2d.hpp>
#include <sylva/motion/unicycle_2d.hpp>
#include <sylva/testing/check_jacobians.hpp>

#include "error_helpers.hpp"
#include "motion_autodiff.hpp"
#include "sylva_catch.hpp"

namespace unity_motion_ackermann_2d {

using namespace sylva;

const Ackermann2D kCar(2.83, 0.76);  // Victoria Park: wheelbase L, encoder offset H

}  // namespace unity_motion_ackermann_2d

using namespace unity_motion_ackermann_2d;

TEST_CASE("Ackermann2D: axle speed and turn rate of the encoder-offset model", "[motion][ackermann]") {
  double v_c = 0.0, omega = 0.0;
  kCar.axleMotion(2.0, 0.3, v_c, omega);
  const double t = std::tan(0.3);
  CHECK(v_c == Approx(2.0 / (1.0 - t * 0.76 / 2.83)));
  CHECK(omega == Approx(v_c * t / 2.83));
  // A left turn makes the left (inner) wheel slower than the axle centre.
  CHECK(v_c > 2.0);
  // Straight driving: the axle moves at the encoder speed; with H = 0 always.
  kCar.axleMotion(2.0, 0.0, v_c, omega);
  CHECK(v_c == 2.0);
  CHECK(omega == 0.0);
  Ackermann2D(2.83).axleMotion(2.0, 0.3, v_c, omega);
  CHECK(v_c == 2.0);
  // The motion itself is the unicycle's with v = v_c and omega = v_c tan(alpha) / L.
  const Vec<3> x(1.0, -2.0, 0.4);
  kCar.axleMotion(3.0, -0.2, v_c, omega);
  const Vec<3> car = kCar(x, Vec<2>(3.0, -0.2), 0.25);
  const Vec<3> unicycle = Unicycle2D{}(x, Vec<2>(v_c, omega), 0.25);
  CHECK((car - unicycle).norm() < 1e-14);
}

TEST_CASE("Ackermann2D Jacobians match numerical and automatic differentiation", "[motion][jacobian][ackermann]") {
  struct Case {
    const char* name;
    Vec<3> x;
    Vec<2> u;
    double dt;
  };
  const Case cases[] = {
      {"ordinary", Vec<3>(1.0, 2.0, 0.3), Vec<2>(3.0, 0.2), 0.025},
      {"standing still", Vec<3>(1.0, 2.0, 0.3), Vec<2>(0.0, 0.1), 0.025},
      {"full right lock", Vec<3>(-3.0, 0.5, -1.0), Vec<2>(2.0, -0.6), 0.2},
      {"full left lock", Vec<3>(-3.0, 0.5, -1.0), Vec<2>(2.0, 0.6), 0.2},
      {"reversing", Vec<3>(0.0, 0.0, 2.0), Vec<2>(-1.0, 0.3), 0.2},
      {"heading at the seam", Vec<3>(0.0, 0.0, kPi - 1e-3), Vec<2>(5.0, 0.5), 0.1},
      {"long step", Vec<3>(5.0, 5.0, 2.0), Vec<2>(6.0, -0.4), 2.0},
      {"zero time step", Vec<3>(5.0, 5.0, 2.0), Vec<2>(3.0, -0.2), 0.0},
  };
  for (const Ackermann2D& car : {kCar, Ackermann2D(2.83), Ackermann2D(1.5, -0.6)}) {
    for (const Case& c : cases) {
      INFO(c.name << ", L " << car.wheelbase() << ", H " << car.encoderOffset());
      sylva_test::requireMotionJacobians(car, c.x, c.u, c.dt);
    }
  }
}

TEST_CASE("Ackermann2D refuses steering outside its domain and bad parameters", "[motion][errors][ackermann]") {
  using sylva_test::throwsCode;
  CHECK(throwsCode([] { kCar(Vec<3>::Zero(), Vec<2>(1.0, 1.6), 0.1); }, ErrorCode::kDegenerateGeometry));
  // tan(alpha) H / L >= 1: the encoder wheel would stop (alpha >= atan(L / H) = 74.97 deg).
  CHECK(throwsCode([] { kCar(Vec<3>::Zero(), Vec<2>(1.0, 1.32), 0.1); }, ErrorCode::kDegenerateGeometry));
  CHECK_NOTHROW(kCar(Vec<3>::Zero(), Vec<2>(1.0, -1.32), 0.1));  // the right turn is fine
  CHECK(throwsCode([] { kCar(Vec<3>::Zero(), Vec<2>(1.0, NAN), 0.1); }, ErrorCode::kNonFinite));
  CHECK(throwsCode([] { Ackermann2D(0.0); }, ErrorCode::kInvalidArgument));
  CHECK(throwsCode([] { Ackermann2D(2.0, INFINITY); }, ErrorCode::kInvalidArgument));

  // In the filter: a refused prediction leaves it bit-identical.
  Ekf<Ackermann2D, Point2> ekf(Vec<3>(1.0, 2.0, 0.3), Mat<3, 3>::Identity() * 0.01, kCar);
  const auto noise = Gaussian<2>::sigmas(Vec<2>(0.1, 0.01));
  ekf.predict(Vec<2>(2.0, 0.1), 0.1, noise);
  const Eigen::VectorXd mean = ekf.mean();
  const Eigen::MatrixXd cov = ekf.covariance();
  CHECK(throwsCode([&] { ekf.predict(Vec<2>(2.0, 1.4), 0.1, noise); }, ErrorCode::kDegenerateGeometry));
  CHECK((ekf.mean().array() == mean.array()).all());
  CHECK((ekf.covariance().array() == cov.array()).all());
}
