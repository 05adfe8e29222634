// A short laser_camera_slam run: reproducible, and the fused sensor maps more landmarks than
// laser corners alone; posters are rejected by the laser-plane test.

#include "laser_camera_slam/run.hpp"
#include "sylva_catch.hpp"

namespace unity_laser_camera_slam_run {

using namespace laser_camera_slam;

TEST_CASE("laser_camera_slam: a short run maps more landmarks with the fused sensor", "[laser_camera_slam]") {
  Options o;
  o.laps = 0.5;
  const Simulation sim = simulate(o);
  const VariantResult corners = runVariant(sim, o, Variant::kLaserCorners);
  const VariantResult lasercam = runVariant(sim, o, Variant::kLaserCamera);
  const VariantResult fused = runVariant(sim, o, Variant::kFused);
  CHECK(fused.landmarks > corners.landmarks);
  CHECK(lasercam.landmarks > corners.landmarks);
  // The final position error is within what the filter claims: 4 of its own sigmas per axis
  // (a consistent filter exceeds that with probability 6e-5), and the claim is not vacuous:
  // those sigmas are below 0.1 m.
  REQUIRE(!fused.records.empty());
  const StepRecord& last = fused.records.back();
  INFO("final error " << last.error.transpose() << ", sigmas " << last.sigma.transpose());
  for (int i = 0; i < 2; ++i) {
    CHECK(std::abs(last.error[i]) < 4.0 * last.sigma[i]);
    CHECK(last.sigma[i] < 0.1);
  }
  // Posters (above the laser plane) are rejected as not crossing it.
  CHECK(sim.status_counts[static_cast<std::size_t>(sylva::LaserCameraStatus::kMissesLaserPlane)] > 0);
  // The calibration curve removes the camera's systematic bearing error.
  CHECK(sim.calibrated_bearing_rms_rad < 0.1 * sim.uncalibrated_bearing_rms_rad);
  // Bit for bit reproducible from the seed.
  const Simulation again = simulate(o);
  const VariantResult fused_again = runVariant(again, o, Variant::kFused);
  CHECK(fused_again.final_position_error_m == fused.final_position_error_m);
  CHECK(fused_again.landmarks == fused.landmarks);
}

TEST_CASE("laser_camera_slam: the corridor world has its features", "[laser_camera_slam]") {
  const auto world = makeIndoorWorld(sylva::sim::LoopPath2D::withPerimeter(40.0, 2.0, 1.5));
  CHECK(world.doors > 0);
  CHECK(world.posters > 0);
  CHECK(world.pillars > 0);
  CHECK(world.edges.size() == static_cast<std::size_t>(8 + 2 * world.doors + 2 * world.posters + 4 * world.pillars));
}

}  // namespace unity_laser_camera_slam_run
