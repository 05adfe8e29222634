// sim::VerticalEdgeCamera: field of view, range, occlusion, facing, vertical extent and
// clipping, the systematic bearing error, reproducibility, bad options.

#include <limits>
#include <vector>

#include <sylva/sim/vertical_edge_camera.hpp>

#include "error_helpers.hpp"
#include "sylva_catch.hpp"

namespace unity_sim_vertical_edge_camera {

using namespace sylva;
using namespace sylva::sim;
using sylva_test::throwsCode;

VerticalEdgeCameraOptions noiseless() {
  VerticalEdgeCameraOptions o;
  o.sigma_px = 0.0;
  return o;
}

TEST_CASE("VerticalEdgeCamera reports the exact bearing and extent without noise", "[sim]") {
  const VerticalEdgeCamera cam(noiseless());
  const std::vector<VerticalEdge> edges = {{Vec<2>(4.0, 1.0), 0.0, 2.5, Vec<2>::Zero(), 7}};
  Rng rng(1);
  std::vector<EdgeDetection> out;
  cam.observe(Vec<3>(1.0, 1.0, 0.3), edges, LaserScene2D{}, rng, out);
  REQUIRE(out.size() == 1);
  const double beta = -0.3;
  CHECK(out[0].edge_id == 7);
  CHECK(out[0].line.bearing_rad == Approx(beta).margin(1e-12));
  CHECK(out[0].true_distance_m == Approx(3.0));
  const double depth = 3.0 * std::cos(beta);
  CHECK(out[0].line.image_top_y == Approx(std::max(-240.0 / 554.0, (0.59 - 2.5) / depth)));
  CHECK(out[0].line.image_bottom_y == Approx(std::min(240.0 / 554.0, 0.59 / depth)));
}

TEST_CASE("VerticalEdgeCamera hides edges outside the view, too far, occluded or facing away", "[sim]") {
  const VerticalEdgeCamera cam(noiseless());
  LaserScene2D walls;
  walls.addSegment(Vec<2>(2.0, -0.5), Vec<2>(2.0, 0.5), 1);  // a wall across the view
  const std::vector<VerticalEdge> edges = {
      {Vec<2>(3.0, 0.0), 0.0, 2.5, Vec<2>::Zero(), 0},    // behind the wall
      {Vec<2>(2.0, 0.5), 0.0, 2.5, Vec<2>::Zero(), 1},    // the wall's end: visible
      {Vec<2>(1.0, 3.0), 0.0, 2.5, Vec<2>::Zero(), 2},    // outside the 60 deg view
      {Vec<2>(-3.0, 0.0), 0.0, 2.5, Vec<2>::Zero(), 3},   // behind the camera
      {Vec<2>(9.0, 0.0), 0.0, 2.5, Vec<2>::Zero(), 4},    // beyond 8 m (and behind the wall)
      {Vec<2>(5.0, 1.2), 0.0, 2.5, Vec<2>(1.0, 0.0), 5},  // facing away
      {Vec<2>(5.0, 1.5), 0.0, 2.5, Vec<2>(-1.0, 0.0), 6},  // facing the camera
      {Vec<2>(3.0, 1.0), 0.58, 0.6, Vec<2>::Zero(), 8},   // 2 cm tall: below min_length_px
  };
  Rng rng(1);
  std::vector<EdgeDetection> out;
  cam.observe(Vec<3>::Zero(), edges, walls, rng, out);
  std::vector<Id> ids;
  for (const auto& d : out) ids.push_back(d.edge_id);
  CHECK(ids == std::vector<Id>{1, 6});
}

TEST_CASE("VerticalEdgeCamera applies the systematic error and its noise reproducibly", "[sim]") {
  VerticalEdgeCameraOptions o;
  o.distortion[0] = 0.01;
  o.distortion[3] = 0.2;
  const VerticalEdgeCamera cam(o);
  const double beta = 0.4;
  Rng a(5), b(5);
  CHECK(cam.reportedBearing(beta, a) == cam.reportedBearing(beta, b));
  VerticalEdgeCameraOptions quiet = o;
  quiet.sigma_px = 0.0;
  Rng c(5);
  CHECK(VerticalEdgeCamera(quiet).reportedBearing(beta, c) == Approx(beta + 0.01 + 0.2 * beta * beta * beta));
  // The pixel noise is sigma_px / f in bearing near the axis.
  Rng d(9);
  double sum2 = 0.0;
  for (int i = 0; i < 20000; ++i) {
    const double e = cam.reportedBearing(0.0, d) - (0.01);
    sum2 += e * e;
  }
  CHECK(std::sqrt(sum2 / 20000) == Approx(1.0 / 554.0).epsilon(0.03));
}

TEST_CASE("VerticalEdgeCamera refuses bad options and a non-finite pose", "[sim]") {
  auto bad = [](auto change) {
    VerticalEdgeCameraOptions o;
    change(o);
    return throwsCode([&] { VerticalEdgeCamera{o}; }, ErrorCode::kInvalidArgument);
  };
  CHECK(bad([](VerticalEdgeCameraOptions& o) { o.focal_px = 0.0; }));
  CHECK(bad([](VerticalEdgeCameraOptions& o) { o.sigma_px = -1.0; }));
  CHECK(bad([](VerticalEdgeCameraOptions& o) { o.detection_probability = 1.5; }));
  CHECK(bad([](VerticalEdgeCameraOptions& o) { o.distortion[2] = std::numeric_limits<double>::quiet_NaN(); }));
  const VerticalEdgeCamera cam;
  Rng rng(1);
  std::vector<EdgeDetection> out;
  CHECK(throwsCode([&] { cam.observe(Vec<3>(std::numeric_limits<double>::quiet_NaN(), 0, 0), {}, LaserScene2D{}, rng, out); },
                   ErrorCode::kNonFinite));
}

}  // namespace unity_sim_vertical_edge_camera
