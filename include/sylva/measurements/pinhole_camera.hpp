#pragma once
/// @file
/// `PinholeCamera`: intrinsics of an ideal pinhole camera (no distortion) and its image size.
///
///   K = [ fx  0  cx ]      a camera-frame point p_C = (x, y, z), z > 0 along the optical
///       [  0 fy  cy ]      axis, x right, y down, maps to the pixel
///       [  0  0   1 ]      (u, v) = (cx + fx x / z, cy + fy y / z)
///
/// Pixels: u to the right, v down, origin at the top-left corner of the image; the image
/// covers [0, width] x [0, height]. Focal lengths and principal point are in pixels.
///
/// `PinholeCamera` is an aggregate, `PinholeCamera{fx, fy, cx, cy, width, height}`; models
/// that take one call `validate()`, which throws `kInvalidArgument` (`kNonFinite` for NaN or
/// Inf) unless the focal lengths and the image size are positive.

#include <cmath>
#include <sstream>

#include "sylva/core/error.hpp"
#include "sylva/core/scalar.hpp"
#include "sylva/core/types.hpp"

namespace sylva {

struct PinholeCamera {
  double fx;   ///< focal length along u (pixels)
  double fy;   ///< focal length along v (pixels)
  double cx;   ///< principal point u (pixels)
  double cy;   ///< principal point v (pixels)
  int width;   ///< image width (pixels)
  int height;  ///< image height (pixels)

  /// Throws unless fx, fy, cx, cy are finite, fx, fy > 0 and width, height > 0.
  void validate() const {
    if (!std::isfinite(fx) || !std::isfinite(fy) || !std::isfinite(cx) || !std::isfinite(cy)) {
      std::ostringstream os;
      os << "PinholeCamera: intrinsics must be finite, got fx = " << fx << ", fy = " << fy
         << ", cx = " << cx << ", cy = " << cy;
      fail(ErrorCode::kNonFinite, os.str());
    }
    if (!(fx > 0.0) || !(fy > 0.0) || width <= 0 || height <= 0) {
      std::ostringstream os;
      os << "PinholeCamera: focal lengths and image size must be positive, got fx = " << fx
         << ", fy = " << fy << ", width = " << width << ", height = " << height;
      fail(ErrorCode::kInvalidArgument, os.str());
    }
  }

  /// The calibration matrix K.
  Mat<3, 3> matrix() const {
    Mat<3, 3> K;
    K << fx, 0.0, cx,  //
        0.0, fy, cy,   //
        0.0, 0.0, 1.0;
    return K;
  }

  /// Pixel (u, v) of a camera-frame point. The caller checks that the depth p_C.z() is > 0;
  /// here it only has to be nonzero.
  template <typename T>
  Vec<2, T> project(const Vec<3, T>& p_C) const {
    return Vec<2, T>(T(cx) + T(fx) * p_C[0] / p_C[2], T(cy) + T(fy) * p_C[1] / p_C[2]);
  }

  /// True when the pixel (u, v) lies inside the image, [0, width] x [0, height].
  bool contains(double u, double v) const {
    return u >= 0.0 && u <= static_cast<double>(width) && v >= 0.0 &&
           v <= static_cast<double>(height);
  }
};

}  // namespace sylva
