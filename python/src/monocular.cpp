// The monocular tree pipeline of the tree-width thesis for Python: slam::MonocularTreeSlam
// (the camera of ConstantVelocity3D with its quaternion in the covariance) with its three
// pipelines and options, and the forest simulator that feeds it. The pipeline itself is
// instantiated in monocular_pipeline.cpp, a unit of its own that compiles beside this one
// (monocular_tree_slam.hpp says why it is not header-only).

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <limits>
#include <vector>

#include "sylva/consistency/camera_pose_nees.hpp"
#include "sylva/sim/forest_scenario.hpp"
#include "sylva/slam/monocular_tree_slam.hpp"

#include "arrays.hpp"
#include "models.hpp"

extern template class sylva::slam::BasicMonocularTreeSlam<sylva::ConstantVelocity3D>;

namespace sylva_py {

namespace {

namespace slam = sylva::slam;
namespace sim = sylva::sim;
using TreeSlam = slam::MonocularTreeSlam;
using Filter = TreeSlam::Filter;

/// The landmarks of a frame from ids (n,) and Z (n, 3) = [u, v, w] pixels.
std::vector<slam::TrunkSighting> toSightings(const py::handle& ids_obj, const py::handle& Z) {
  const auto ids = toIds(ids_obj, "ids");
  const auto z = toRows<3>(Z, "Z");
  if (ids.size() != z.size())
    sylva::fail(sylva::ErrorCode::kInvalidArgument,
                "ids: " + std::to_string(ids.size()) + " ids for " + std::to_string(z.size()) +
                    " sightings");
  std::vector<slam::TrunkSighting> out(z.size());
  for (std::size_t i = 0; i < z.size(); ++i) out[i] = {ids[i], z[i]};
  return out;
}

/// Every landmark in Euclidean form (XYZ or XYZ-R): ids (n,), positions (n, 3), radii (n,)
/// (NaN for XYZ points). Inverse-depth and IDR trees, whose depth is still open, are left out.
py::tuple euclidean(const Filter& ekf) {
  std::vector<sylva::Id> ids;
  std::vector<sylva::Vec<3>> positions;
  std::vector<double> radii;
  for (const auto& s : ekf.slots()) {
    if (ekf.holds<sylva::Point3>(s.id)) {
      ids.push_back(s.id);
      positions.push_back(ekf.landmarkMean<sylva::Point3>(s.id));
      radii.push_back(std::numeric_limits<double>::quiet_NaN());
    } else if (ekf.holds<sylva::TreeXYZR>(s.id)) {
      const sylva::Vec<4> l = ekf.landmarkMean<sylva::TreeXYZR>(s.id);
      ids.push_back(s.id);
      positions.push_back(l.head<3>());
      radii.push_back(l[3]);
    }
  }
  return py::make_tuple(
      toArray(ids),
      arrayOf<double>(positions.size(), 3, [&](std::size_t i, int c) { return positions[i][c]; }),
      toArray(radii));
}

}  // namespace

void bindMonocular(py::module_& m) {
  py::class_<sylva::PinholeCamera>(
      m, "PinholeCamera", "Intrinsics fx, fy, cx, cy (pixels) and the image size.")
      .def(py::init([](double fx, double fy, double cx, double cy, int width, int height) {
             const sylva::PinholeCamera c{fx, fy, cx, cy, width, height};
             c.validate();
             return c;
           }),
           py::arg("fx") = 500.0,
           py::arg("fy") = 500.0,
           py::arg("cx") = 320.0,
           py::arg("cy") = 240.0,
           py::arg("width") = 640,
           py::arg("height") = 480)
      .def_readonly("fx", &sylva::PinholeCamera::fx)
      .def_readonly("fy", &sylva::PinholeCamera::fy)
      .def_readonly("cx", &sylva::PinholeCamera::cx)
      .def_readonly("cy", &sylva::PinholeCamera::cy)
      .def_readonly("width", &sylva::PinholeCamera::width)
      .def_readonly("height", &sylva::PinholeCamera::height);

  py::enum_<slam::WidthPipeline>(
      m, "WidthPipeline", "How the tree width w is used (the three pipelines).")
      .value("NONE", slam::WidthPipeline::kNone)
      .value("AFTER_XYZ", slam::WidthPipeline::kAfterXyz)
      .value("FROM_FIRST_SIGHT", slam::WidthPipeline::kFromFirstSight);
  py::enum_<slam::TrunkAssociation>(
      m, "TrunkAssociation", "How the sightings of a frame find their trees.")
      .value("KNOWN_IDS", slam::TrunkAssociation::kKnownIds)
      .value("NEAREST_NEIGHBOR", slam::TrunkAssociation::kNearestNeighbor);
  py::enum_<sylva::ConstantVelocity3D::VelocityFrame>(
      m, "VelocityFrame", "The frame of the camera's linear velocity.")
      .value("WORLD", sylva::ConstantVelocity3D::VelocityFrame::kWorld)
      .value("CAMERA", sylva::ConstantVelocity3D::VelocityFrame::kCamera);

  py::class_<slam::TreeSlamOptions>(
      m,
      "TreeSlamOptions",
      "Settings of the monocular tree pipeline (sylva::slam::TreeSlamOptions); the "
      "defaults are forest_slam's.")
      .def(py::init<>())
      .def_readwrite("camera", &slam::TreeSlamOptions::camera)
      .def_readwrite("pipeline", &slam::TreeSlamOptions::pipeline)
      .def_readwrite("pixel_sigma_px", &slam::TreeSlamOptions::pixel_sigma_px)
      .def_readwrite("width_sigma_px", &slam::TreeSlamOptions::width_sigma_px)
      .def_readwrite("linear_accel_sigma", &slam::TreeSlamOptions::linear_accel_sigma)
      .def_readwrite("angular_accel_sigma", &slam::TreeSlamOptions::angular_accel_sigma)
      .def_readwrite("velocity_frame", &slam::TreeSlamOptions::velocity_frame)
      .def_readwrite("initial_inverse_depth", &slam::TreeSlamOptions::initial_inverse_depth)
      .def_readwrite("inverse_depth_sigma", &slam::TreeSlamOptions::inverse_depth_sigma)
      .def_readwrite("linearity_threshold", &slam::TreeSlamOptions::linearity_threshold)
      .def_readwrite("tree_position_sigma_m", &slam::TreeSlamOptions::tree_position_sigma_m)
      .def_readwrite("gate_probability", &slam::TreeSlamOptions::gate_probability)
      .def_readwrite("conversion_given_camera", &slam::TreeSlamOptions::conversion_given_camera)
      .def_readwrite("linearization", &slam::TreeSlamOptions::linearization)
      .def_readwrite("association", &slam::TreeSlamOptions::association)
      .def_readwrite("association_gate_probability",
                     &slam::TreeSlamOptions::association_gate_probability)
      .def_readwrite("new_tree_probability", &slam::TreeSlamOptions::new_tree_probability)
      .def_readwrite("width_appearance", &slam::TreeSlamOptions::width_appearance)
      .def_readwrite("width_appearance_tolerance",
                     &slam::TreeSlamOptions::width_appearance_tolerance)
      .def_readwrite("continuity_cost", &slam::TreeSlamOptions::continuity_cost)
      .def_readwrite("continuity_edge_margin_px", &slam::TreeSlamOptions::continuity_edge_margin_px)
      .def_readwrite("loop_pairings", &slam::TreeSlamOptions::loop_pairings)
      .def_readwrite("loop_sightings", &slam::TreeSlamOptions::loop_sightings)
      .def_readwrite("unconfirmed_after_frames", &slam::TreeSlamOptions::unconfirmed_after_frames)
      .def_readwrite("confirm_sightings", &slam::TreeSlamOptions::confirm_sightings)
      .def_readwrite("fusion", &slam::TreeSlamOptions::fusion);

  py::class_<slam::FrameReport>(m, "FrameReport", "What one frame of the monocular pipeline did.")
      .def_readonly("fused", &slam::FrameReport::fused)
      .def_readonly("fused_rows", &slam::FrameReport::fused_rows)
      .def_readonly("added", &slam::FrameReport::added)
      .def_readonly("to_xyz", &slam::FrameReport::to_xyz)
      .def_readonly("to_tree", &slam::FrameReport::to_tree)
      .def_readonly("rejected", &slam::FrameReport::rejected)
      .def_readonly("hypotheses", &slam::FrameReport::hypotheses)
      .def_readonly("ambiguous", &slam::FrameReport::ambiguous)
      .def_readonly("removed", &slam::FrameReport::removed)
      .def_readonly("landmark_of",
                    &slam::FrameReport::landmark_of,
                    "per sighting: the landmark it was taken as, or -1 when dropped as ambiguous");

  m.def(
      "initial_camera_covariance",
      [] { return toArray(slam::initialCameraCovariance()); },
      "The camera prior of forest_slam (13, 13): pose known, velocity to 0.1 m/s, angular velocity "
      "to 0.05 rad/s.");

  py::class_<TreeSlam>(
      m,
      "MonocularTreeSlam",
      "Monocular EKF-SLAM with trees as landmarks (tree-width thesis Sec. 3.5, 4.1.3): the camera "
      "[position, quaternion wxyz, velocity, angular velocity] of ConstantVelocity3D; trees start "
      "as "
      "inverse-depth points and become XYZ, then XYZ-R with the width sensor.")
      .def(
          py::init(
              [](const slam::TreeSlamOptions& options, const py::handle& x0, const py::handle& P0) {
                const sylva::Mat<13, 13> P =
                    P0.is_none() ? slam::initialCameraCovariance() : toMat<13, 13>(P0, "P0");
                if (options.camera_on_manifold)
                  sylva::fail(sylva::ErrorCode::kInvalidArgument,
                              "MonocularTreeSlam: camera_on_manifold is not available from Python");
                return TreeSlam(options, toVec<13>(x0, "x0"), P);
              }),
          py::arg("options"),
          py::arg("x0"),
          py::arg("P0") = py::none(),
          "Starts at camera state x0 (13,) with covariance P0 (default: "
          "initial_camera_covariance()).")
      .def(
          "process_frame",
          [](TreeSlam& s, double dt, const py::handle& ids, const py::handle& Z) {
            return s.processFrame(dt, toSightings(ids, Z));
          },
          py::arg("dt"),
          py::arg("ids"),
          py::arg("Z"),
          "One frame: predict over dt, then the trunks seen, ids (n,) and Z (n, 3) = [u, v, w] "
          "pixels (the ids "
          "are ignored with TrunkAssociation.NEAREST_NEIGHBOR).")
      .def("count_by_type",
           &TreeSlam::countByType,
           "Landmarks per parametrization: (inverse depth, XYZ, XYZ-R, IDR).")
      .def_property_readonly("options", &TreeSlam::options)
      .def_property_readonly("camera_mean",
                             [](const TreeSlam& s) { return toArray(s.filter().robotMean()); })
      .def_property_readonly(
          "camera_covariance",
          [](const TreeSlam& s) { return toArray(s.filter().robotCovariance()); })
      .def_property_readonly("dim", [](const TreeSlam& s) { return s.filter().dim(); })
      .def(
          "euclidean_landmarks",
          [](const TreeSlam& s) { return euclidean(s.filter()); },
          "The landmarks in Euclidean form: (ids (n,), positions (n, 3), radii (n,), NaN for XYZ "
          "points).")
      .def(
          "camera_pose_error",
          [](const TreeSlam& s, const py::handle& truth) {
            const sylva::CameraPoseError e = sylva::cameraPoseError(
                s.filter().robotMean(), s.filter().robotCovariance(), toVec<13>(truth, "truth"));
            return py::make_tuple(toArray(e.e), toArray(e.S));
          },
          py::arg("truth"),
          "The camera pose error [position, orientation] (6,) against the true state and its "
          "covariance (6, 6) "
          "(sylva::cameraPoseError); sylva.nees(e, S) is the pose NEES.");

  // ---------------------------------------------------------------- the forest simulator
  py::class_<sim::ForestOptions>(
      m, "ForestOptions", "Trees on a jittered grid (tree-width thesis Sec. 4.1.1).")
      .def(py::init<>())
      .def_readwrite("x_min_m", &sim::ForestOptions::x_min_m)
      .def_readwrite("x_max_m", &sim::ForestOptions::x_max_m)
      .def_readwrite("y_min_m", &sim::ForestOptions::y_min_m)
      .def_readwrite("y_max_m", &sim::ForestOptions::y_max_m)
      .def_readwrite("grid_spacing_m", &sim::ForestOptions::grid_spacing_m)
      .def_readwrite("presence_probability", &sim::ForestOptions::presence_probability)
      .def_readwrite("jitter_sigma_m", &sim::ForestOptions::jitter_sigma_m)
      .def_readwrite("radius_mean_m", &sim::ForestOptions::radius_mean_m)
      .def_readwrite("radius_sigma_m", &sim::ForestOptions::radius_sigma_m)
      .def_readwrite("radius_min_m", &sim::ForestOptions::radius_min_m)
      .def_readwrite("radius_max_m", &sim::ForestOptions::radius_max_m)
      .def_readwrite("elevation_amplitude_m", &sim::ForestOptions::elevation_amplitude_m)
      .def_readwrite("elevation_wavelength_m", &sim::ForestOptions::elevation_wavelength_m)
      .def_readwrite("clearance_m", &sim::ForestOptions::clearance_m);
  py::class_<sim::TrajectoryOptions>(
      m, "ForestTrajectoryOptions", "The camera's loop through the forest.")
      .def(py::init<>())
      .def_readwrite("speed_mps", &sim::TrajectoryOptions::speed_mps)
      .def_readwrite("dt_s", &sim::TrajectoryOptions::dt_s)
      .def_readwrite("laps", &sim::TrajectoryOptions::laps)
      .def_readwrite("camera_height_m", &sim::TrajectoryOptions::camera_height_m)
      .def_readwrite("pitch_rad", &sim::TrajectoryOptions::pitch_rad);
  py::class_<sim::ObserverOptions>(
      m, "TreeObserverOptions", "What the camera measures of the trees.")
      .def(py::init<>())
      .def_readwrite("sigma_px", &sim::ObserverOptions::sigma_px)
      .def_readwrite("sigma_width_px", &sim::ObserverOptions::sigma_width_px)
      .def_readwrite("occlusion", &sim::ObserverOptions::occlusion)
      .def_readwrite("max_range_m", &sim::ObserverOptions::max_range_m);
  py::class_<sim::ForestScenarioOptions>(
      m, "ForestScenarioOptions", "A forest, the camera's loop and its measurements.")
      .def(py::init<>())
      .def_readwrite("camera", &sim::ForestScenarioOptions::camera)
      .def_readwrite("forest", &sim::ForestScenarioOptions::forest)
      .def_readwrite("trajectory", &sim::ForestScenarioOptions::trajectory)
      .def_readwrite("observer", &sim::ForestScenarioOptions::observer);
  py::class_<sim::ForestScenario>(
      m,
      "ForestScenario",
      "A simulated forest run (sylva::sim::makeForestScenario): the trees, the camera's "
      "frames and the noisy [u, v, w] of every tree seen in each.")
      .def(py::init([](const sim::ForestScenarioOptions& options, std::uint64_t seed) {
             return sim::makeForestScenario(options, seed);
           }),
           py::arg("options"),
           py::arg("seed"))
      .def_property_readonly(
          "tree_bases",
          [](const sim::ForestScenario& s) {
            return arrayOf<double>(
                s.trees.size(), 3, [&](std::size_t i, int c) { return s.trees[i].base[c]; });
          },
          "Base centres of the trees (n, 3); tree i has id i.")
      .def_property_readonly("tree_radii",
                             [](const sim::ForestScenario& s) {
                               return arrayOf<double>(s.trees.size(), 0, [&](std::size_t i, int) {
                                 return s.trees[i].radius_m;
                               });
                             })
      .def_property_readonly("frame_times",
                             [](const sim::ForestScenario& s) {
                               return arrayOf<double>(s.frames.size(), 0, [&](std::size_t k, int) {
                                 return s.frames[k].t_s;
                               });
                             })
      .def_property_readonly("frame_laps",
                             [](const sim::ForestScenario& s) {
                               return arrayOf<int>(s.frames.size(), 0, [&](std::size_t k, int) {
                                 return s.frames[k].lap;
                               });
                             })
      .def_property_readonly(
          "camera_states",
          [](const sim::ForestScenario& s) {
            return arrayOf<double>(
                s.frames.size(), 13, [&](std::size_t k, int c) { return s.frames[k].state[c]; });
          },
          "True camera states (frames, 13).")
      .def("__len__", [](const sim::ForestScenario& s) { return s.frames.size(); })
      .def(
          "observations",
          [](const sim::ForestScenario& s, int k) {
            if (k < 0 || k >= static_cast<int>(s.observations.size()))
              sylva::fail(sylva::ErrorCode::kInvalidArgument,
                          "ForestScenario.observations: frame " + std::to_string(k) +
                              " is outside [0, " + std::to_string(s.observations.size()) + ")");
            const auto& obs = s.observations[static_cast<std::size_t>(k)];
            return py::make_tuple(
                arrayOf<sylva::Id>(obs.size(), 0, [&](std::size_t i, int) { return obs[i].id; }),
                arrayOf<double>(obs.size(), 3, [&](std::size_t i, int c) { return obs[i].z[c]; }),
                arrayOf<double>(
                    obs.size(), 3, [&](std::size_t i, int c) { return obs[i].z_true[c]; }),
                arrayOf<double>(obs.size(), 0, [&](std::size_t i, int) { return obs[i].depth_m; }));
          },
          py::arg("frame"),
          "The trees seen in frame k: (ids (n,), Z (n, 3) noisy [u, v, w], noise-free Z, depths).");
}

}  // namespace sylva_py
