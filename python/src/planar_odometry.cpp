// Ekf<Odometry2D, Point2> for Python (planar_filter.hpp).
#include "sylva/motion/odometry_2d.hpp"

#include "planar_filter.hpp"

namespace sylva_py {

void bindOdometry(py::module_& m) {
  bindPlanarFilter<sylva::Odometry2D>(m,
                                      "Odometry2DEkf",
                                      "EKF-SLAM for a robot driven by odometry increments "
                                      "(Odometry2D: control [dx, dy, dtheta] in the robot frame "
                                      "before the motion) with Point2 landmarks.",
                                      [](const py::kwargs& kwargs) {
                                        if (kwargs.size() != 0)
                                          sylva::fail(sylva::ErrorCode::kInvalidArgument,
                                                      "Odometry2DEkf takes no robot parameters");
                                        return sylva::Odometry2D();
                                      });
}

}  // namespace sylva_py
