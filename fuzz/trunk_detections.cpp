// Fuzz target: the trunk-detection and camera loaders (sylva/datasets/trunk_detections.hpp).
//
// Input: one byte that picks the loader by its value modulo 2 ('0' detections, '1' camera),
// then the file.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <sylva/datasets/trunk_detections.hpp>

#include "fuzz_common.hpp"

namespace {

using namespace sylva::datasets;
using sylva_fuzz::require;

void check(const std::vector<TrunkDetectionFrame>& frames) {
  require(!frames.empty(), "no frames");
  for (std::size_t k = 0; k < frames.size(); ++k) {
    require(std::isfinite(frames[k].t_s) && (k == 0 || frames[k - 1].t_s < frames[k].t_s),
            "frame times do not increase");
    for (const TrunkDetection& d : frames[k].detections) {
      require(d.z.allFinite() && d.z[2] > 0.0, "a detection is not finite or its width not positive");
      require(!d.id || *d.id >= 0, "a negative id");
    }
  }
}

void check(const CameraIntrinsics& c) {
  require(c.fx > 0.0 && c.fy > 0.0 && std::isfinite(c.fx) && std::isfinite(c.fy) && std::isfinite(c.cx) &&
              std::isfinite(c.cy) && c.width > 0 && c.height > 0,
          "the camera is out of bounds");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace sylva_fuzz;
  static const Scratch dir("trunk_detections");
  if (size < 1) return 0;
  const std::string_view text = asText(data + 1, size - 1);
  if (data[0] % 2 == 0) {
    const std::string path = dir.write("detections.csv", text);
    return run([&] { check(readTrunkDetections(path)); });
  }
  const std::string path = dir.write("camera.csv", text);
  return run([&] { check(readCameraIntrinsics(path)); });
}
