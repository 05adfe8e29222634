// The code sample of docs/slam.md, compiled and run: a SLAM loop on slam::FrontEnd. The
// lines between the markers are quoted verbatim in docs/slam.md; the last test case checks
// that.
#include "sylva_catch.hpp"

#include <cmath>
#include <iostream>
#include <vector>

#include <sylva/filter/ekf.hpp>
#include <sylva/landmarks/point2.hpp>
#include <sylva/measurements/range_bearing.hpp>
#include <sylva/motion/unicycle_2d.hpp>
#include <sylva/slam/front_end.hpp>
#include <sylva/slam/reach.hpp>

#include "doc_snippets.hpp"

namespace unity_docs_slam_step {

using sylva::Vec;

// A robot driving a circle of radius 5 m among six posts; readings without ids.
struct Scan {
  Vec<2> odometry;  // [v, omega]
  std::vector<Vec<2>> readings;
};

std::vector<Scan> simulate(int steps) {
  const std::vector<Vec<2>> posts = {{8.0, 0.0}, {0.0, 9.0}, {-7.0, 3.0}, {-2.0, -8.0}, {5.0, 7.0}, {4.0, -6.0}};
  std::vector<Scan> scans;
  Vec<3> pose(0.0, -5.0, 0.0);
  const Vec<2> u(1.0, 0.2);
  for (int k = 0; k < steps; ++k) {
    pose = sylva::Unicycle2D{}(pose, u, 0.5);
    Scan scan{u, {}};
    for (const Vec<2>& p : posts) {
      const Vec<2> z = sylva::RangeBearing{}(pose, p);
      if (z[0] < 10.0 && std::abs(z[1]) < 1.6) scan.readings.push_back(z);
    }
    scans.push_back(scan);
  }
  return scans;
}

TEST_CASE("docs/slam.md sample: a SLAM loop on slam::FrontEnd", "[slam][docs]") {
  const std::vector<Scan> scans = simulate(80);
  const double dt = 0.5;
  // [slam-step begin]
  using namespace sylva;
  using Filter = Ekf<Unicycle2D, Point2>;
  Filter ekf(Vec<3>(0.0, -5.0, 0.0), Mat<3, 3>::Zero());
  const auto odometry_noise = Gaussian<2>::sigmas({0.05, 0.02});
  const auto sensor_noise = Gaussian<2>::sigmas({0.05, 0.01});

  // JCBB on the landmarks within 11 m and 100 deg of the heading; a landmark is mapped
  // after 3 sightings of the same place, not at the first one.
  slam::FrontEndOptions options;
  options.association = slam::Association::kJcbb;
  options.new_landmarks = slam::NewLandmarks::kTentative;
  options.tentative = {3, 0.5, 2.0};  // sightings, radius (m), timeout (s)
  slam::FrontEnd<Filter, RangeBearing, InverseRangeBearing> front_end(
      RangeBearing{}, InverseRangeBearing{}, options,
      slam::candidatesInReach<Point2>(RangeBearing{}, {11.0, 100.0 * kRadPerDeg}));

  int paired = 0;
  for (std::size_t k = 0; k < scans.size(); ++k) {
    std::vector<slam::Reading<2>> readings;
    for (const Vec<2>& z : scans[k].readings) readings.push_back({z, sensor_noise});
    const slam::StepReport& report =
        front_end.step(ekf, scans[k].odometry, dt, odometry_noise, readings, dt * (k + 1));
    paired += report.count(slam::Outcome::kPaired);
    for (const slam::ReadingResult& r : report.readings)
      if (r.outcome == slam::Outcome::kRefused) std::cerr << "refused: " << r.why << "\n";
  }
  // [slam-step end]
  CHECK(ekf.landmarkCount() == 6);
  CHECK(paired > 100);
  CHECK(front_end.lastReport().count(slam::Outcome::kAmbiguous) == 0);
}

TEST_CASE("docs/slam.md quotes the sample verbatim", "[slam][docs]") {
  const std::string sample = sylva_docs::markedRegion(__FILE__, "slam-step");
  REQUIRE(sample.size() > 200);
  const std::string page = sylva_docs::fileText(sylva_docs::repositoryRoot() + "/docs/slam.md");
  REQUIRE(!page.empty());
  CHECK(page.find(sample) != std::string::npos);
}

}  // namespace unity_docs_slam_step
