#pragma once
/// @file
/// `sim::generateForest`: a random forest of tree trunks for the monocular tree-SLAM
/// simulator (tree-width thesis, Sec. 4.1.1, Fig. 4.1). Trees stand on a regular grid; each
/// cell holds a tree with probability `presence_probability`, placed at the cell centre plus
/// Gaussian jitter, with a radius drawn from a Gaussian (clamped to [radius_min_m,
/// radius_max_m]) and its base on a smooth ground surface
///
///   z(x, y) = A ( 0.6 sin(2 pi x / L) + 0.4 cos(2 pi y / (0.8 L)) ),
///
/// A = `elevation_amplitude_m`, L = `elevation_wavelength_m`. Trees closer than
/// `clearance_m` + radius to any point of `keep_clear` (the camera's path) are left out, so the
/// camera never drives through a trunk. Ids are 0..N-1 in grid order (x outer, y inner)
/// among the trees kept. Every cell draws the same number of random numbers whether or not
/// it holds a tree, so changing one option does not reshuffle the whole forest.

#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

#include "sylva/core/error.hpp"
#include "sylva/core/types.hpp"
#include "sylva/sim/random.hpp"

namespace sylva::sim {

struct ForestOptions {
  double x_min_m = -20.0, x_max_m = 20.0;  ///< extent of the grid
  double y_min_m = -20.0, y_max_m = 20.0;
  double grid_spacing_m = 3.0;
  double presence_probability = 0.6;
  double jitter_sigma_m = 0.6;  ///< Gaussian jitter of a tree about its cell centre
  double radius_mean_m = 0.25;
  double radius_sigma_m = 0.07;
  double radius_min_m = 0.08;
  double radius_max_m = 0.6;
  double elevation_amplitude_m = 0.5;
  double elevation_wavelength_m = 30.0;
  double clearance_m = 1.5;  ///< free space between the path and a trunk's surface

  /// Throws kInvalidArgument (naming the option) for a malformed setting.
  void validate() const {
    auto bad = [](const char* what, double value) {
      std::ostringstream os;
      os << "ForestOptions: " << what << " = " << value;
      fail(ErrorCode::kInvalidArgument, os.str());
    };
    const double all[] = {x_min_m, x_max_m, y_min_m, y_max_m, grid_spacing_m, presence_probability, jitter_sigma_m,
                          radius_mean_m, radius_sigma_m, radius_min_m, radius_max_m, elevation_amplitude_m,
                          elevation_wavelength_m, clearance_m};
    for (double v : all)
      if (!std::isfinite(v)) bad("a value is not finite", v);
    if (!(x_max_m > x_min_m)) bad("x_max_m must exceed x_min_m, x_max_m", x_max_m);
    if (!(y_max_m > y_min_m)) bad("y_max_m must exceed y_min_m, y_max_m", y_max_m);
    if (!(grid_spacing_m > 0.0)) bad("grid_spacing_m must be > 0, got", grid_spacing_m);
    if (!(presence_probability >= 0.0 && presence_probability <= 1.0))
      bad("presence_probability must be in [0, 1], got", presence_probability);
    if (jitter_sigma_m < 0.0) bad("jitter_sigma_m must be >= 0, got", jitter_sigma_m);
    if (radius_sigma_m < 0.0) bad("radius_sigma_m must be >= 0, got", radius_sigma_m);
    if (!(radius_min_m > 0.0 && radius_min_m <= radius_max_m)) bad("need 0 < radius_min_m <= radius_max_m, radius_min_m", radius_min_m);
    if (!(elevation_wavelength_m > 0.0)) bad("elevation_wavelength_m must be > 0, got", elevation_wavelength_m);
    if (clearance_m < 0.0) bad("clearance_m must be >= 0, got", clearance_m);
  }

  /// Height of the ground (m) at (x, y).
  double groundElevation(double x, double y) const {
    constexpr double kTwoPi = 6.283185307179586;
    return elevation_amplitude_m * (0.6 * std::sin(kTwoPi * x / elevation_wavelength_m) +
                                    0.4 * std::cos(kTwoPi * y / (0.8 * elevation_wavelength_m)));
  }
};

/// One trunk: the centre of its base circle (on the ground) and its radius.
struct Tree {
  Id id;
  Vec<3> base;
  double radius_m;

  /// The `TreeXYZR` landmark [x, y, z, r].
  Vec<4> xyzr() const { return Vec<4>(base.x(), base.y(), base.z(), radius_m); }
};

/// The forest of `options`, avoiding the points `keep_clear` (x, y; z ignored) by
/// `clearance_m` + radius.
inline std::vector<Tree> generateForest(const ForestOptions& options, Rng& rng, const std::vector<Vec<2>>& keep_clear = {}) {
  options.validate();
  std::vector<Tree> trees;
  const int nx = static_cast<int>(std::floor((options.x_max_m - options.x_min_m) / options.grid_spacing_m + 1e-9));
  const int ny = static_cast<int>(std::floor((options.y_max_m - options.y_min_m) / options.grid_spacing_m + 1e-9));
  for (int i = 0; i < nx; ++i) {
    for (int j = 0; j < ny; ++j) {
      const double present = rng.uniform01();
      const double dx = rng.normal(0.0, options.jitter_sigma_m);
      const double dy = rng.normal(0.0, options.jitter_sigma_m);
      const double r = rng.normal(options.radius_mean_m, options.radius_sigma_m);
      if (!(present < options.presence_probability)) continue;
      const double x = options.x_min_m + (i + 0.5) * options.grid_spacing_m + dx;
      const double y = options.y_min_m + (j + 0.5) * options.grid_spacing_m + dy;
      const double radius = std::clamp(r, options.radius_min_m, options.radius_max_m);
      bool clear = true;
      for (const Vec<2>& p : keep_clear) {
        if ((p - Vec<2>(x, y)).norm() < options.clearance_m + radius) {
          clear = false;
          break;
        }
      }
      if (!clear) continue;
      trees.push_back(Tree{static_cast<Id>(trees.size()), Vec<3>(x, y, options.groundElevation(x, y)), radius});
    }
  }
  return trees;
}

}  // namespace sylva::sim
