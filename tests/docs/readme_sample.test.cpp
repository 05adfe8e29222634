// The code sample of README.md, compiled and run. The lines between the two markers are
// quoted verbatim, as the body of main(), in README.md; the last test case checks that.
#include "sylva_catch.hpp"

#include <Eigen/LU>
#include <sylva/consistency/chi_square.hpp>
#include <sylva/sylva.hpp>

#include "doc_snippets.hpp"

TEST_CASE("README sample: add, predict, update") {
  // [readme-sample begin]
  using namespace sylva;

  // Robot [x, y, theta] at the origin, known exactly; map landmarks are 2D points.
  Ekf<Unicycle2D, Point2> ekf(Vec<3>::Zero(), Mat<3, 3>::Zero());
  const auto odometry_noise = Gaussian<2>::sigmas({0.05, 0.02});  // [v m/s, omega rad/s]
  const auto sensor_noise = Gaussian<2>::sigmas({0.10, 0.01});    // [range m, bearing rad]

  // First sighting of landmark 7: 5 m away, 0.6435 rad to the left (it is at (4, 3)).
  ekf.add(7, InverseRangeBearing{}, Vec<2>(5.0, 0.6435), sensor_noise);

  // Drive 1 m straight ahead, then see landmark 7 again.
  ekf.predict(Vec<2>(1.0, 0.0), 1.0, odometry_noise);  // control [v, omega], dt in s
  const auto innovation = ekf.update(RangeBearing{}, 7, Vec<2>(4.243, 0.7854), sensor_noise);

  const Vec<3> pose = ekf.robotMean();                  // [x, y, theta]
  const Vec<2> landmark = ekf.landmarkMean<Point2>(7);  // [x, y]
  const Mat<2, 2> landmark_cov = ekf.landmarkCovariance<Point2>(7);
  // [readme-sample end]

  CHECK(pose.isApprox(Vec<3>(1.0, 0.0, 0.0), 0.05));
  CHECK((landmark - Vec<2>(4.0, 3.0)).norm() < 0.05);
  CHECK(innovation.nis() < chiSquareGate(2, 0.99));
  // The second sighting shrinks the landmark's uncertainty.
  const Mat<2, 2> initial_cov = [&] {
    Ekf<Unicycle2D, Point2> fresh(Vec<3>::Zero(), Mat<3, 3>::Zero());
    fresh.add(7, InverseRangeBearing{}, Vec<2>(5.0, 0.6435), sensor_noise);
    return fresh.landmarkCovariance<Point2>(7);
  }();
  CHECK(landmark_cov.trace() < initial_cov.trace());
  CHECK(landmark_cov.determinant() > 0.0);
}

TEST_CASE("README.md quotes the sample verbatim") {
  const std::string sample = sylva_docs::markedRegion(__FILE__, "readme-sample", false);
  REQUIRE(sample.size() > 200);
  const std::string readme = sylva_docs::fileText(sylva_docs::repositoryRoot() + "/README.md");
  REQUIRE(!readme.empty());
  CHECK(readme.find(sample) != std::string::npos);
}
