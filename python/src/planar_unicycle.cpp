// Ekf<Unicycle2D, Point2> for Python (planar_filter.hpp).
#include "sylva/motion/unicycle_2d.hpp"

#include "planar_filter.hpp"

namespace sylva_py {

void bindUnicycle(py::module_& m) {
  bindPlanarFilter<sylva::Unicycle2D>(m,
                                      "Unicycle2DEkf",
                                      "EKF-SLAM for a differential-drive robot (Unicycle2D: "
                                      "control [v m/s, omega rad/s]) with Point2 landmarks.",
                                      [](const py::kwargs& kwargs) {
                                        if (kwargs.size() != 0)
                                          sylva::fail(sylva::ErrorCode::kInvalidArgument,
                                                      "Unicycle2DEkf takes no robot parameters");
                                        return sylva::Unicycle2D();
                                      });
}

}  // namespace sylva_py
