// Ekf<Ackermann2D, Point2> for Python (planar_filter.hpp).
#include "sylva/motion/ackermann_2d.hpp"

#include "planar_filter.hpp"

namespace sylva_py {

void bindAckermann(py::module_& m) {
  bindPlanarFilter<sylva::Ackermann2D>(
      m,
      "Ackermann2DEkf",
      "EKF-SLAM for a car-like robot (Ackermann2D: control [v_e m/s, steering alpha rad]) with "
      "Point2 landmarks. "
      "Keyword arguments: wheelbase_m (required), encoder_offset_m (default 0).",
      [](const py::kwargs& kwargs) {
        double wheelbase = 0.0;
        double offset = 0.0;
        bool has_wheelbase = false;
        for (const auto& item : kwargs) {
          const std::string key = py::str(item.first);
          if (key == "wheelbase_m") {
            wheelbase = item.second.cast<double>();
            has_wheelbase = true;
          } else if (key == "encoder_offset_m") {
            offset = item.second.cast<double>();
          } else {
            sylva::fail(sylva::ErrorCode::kInvalidArgument,
                        "Ackermann2DEkf: unknown robot parameter '" + key +
                            "' (wheelbase_m, encoder_offset_m)");
          }
        }
        if (!has_wheelbase)
          sylva::fail(sylva::ErrorCode::kInvalidArgument, "Ackermann2DEkf needs wheelbase_m");
        return sylva::Ackermann2D(wheelbase, offset);
      });
}

}  // namespace sylva_py
