#pragma once
/// @file
/// `sim::Rng`: the one source of randomness of sylva's simulators. It wraps
/// `std::mt19937_64` (whose output sequence the C++ standard fixes) and draws uniform and
/// standard normal numbers with its own arithmetic, so the same seed gives the same numbers
/// bit for bit with libstdc++, libc++ and MSVC. (`std::normal_distribution` and
/// `std::uniform_real_distribution` are implementation-defined and differ between them.)
///
///   uniform01()  = (top 53 bits of the engine output) * 2^-53,   in [0, 1)
///   normal()     = Marsaglia's polar method: draw (a, b) uniform in the unit disc
///                  (rejecting s = a^2 + b^2 >= 1 or s = 0), return a * sqrt(-2 ln s / s)
///                  and keep b * sqrt(-2 ln s / s) for the next call.
///
/// `deriveSeed(seed, stream)` gives independent-looking seeds for Monte Carlo run i from one
/// user seed (SplitMix64 finalizer), so run i is reproducible on its own.
///
/// Common mistakes: copying an `Rng` copies its state, so both copies then produce the same
/// numbers; pass it by reference. Never seed from `std::random_device` in sylva code.

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <sstream>

#include "sylva/core/error.hpp"
#include "sylva/core/types.hpp"
#include "sylva/noise/gaussian.hpp"

namespace sylva::sim {

/// SplitMix64 finalizer of `seed + (stream + 1) * golden gamma`: a well-mixed 64-bit seed for
/// stream `stream` (e.g. Monte Carlo run index) derived from one user seed.
inline std::uint64_t deriveSeed(std::uint64_t seed, std::uint64_t stream) {
  std::uint64_t z = seed + (stream + 1) * 0x9E3779B97F4A7C15ULL;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

class Rng {
 public:
  using Engine = std::mt19937_64;

  explicit Rng(std::uint64_t seed) : engine_(seed), seed_(seed) {}

  /// The seed this generator was constructed with.
  std::uint64_t seed() const { return seed_; }

  /// The underlying engine, for code that needs raw 64-bit draws.
  Engine& engine() { return engine_; }

  /// Uniform in [0, 1) with 53 random bits.
  double uniform01() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }

  /// Uniform in [lo, hi). Throws kInvalidArgument unless lo < hi and both are finite.
  double uniform(double lo, double hi) {
    if (!std::isfinite(lo) || !std::isfinite(hi) || !(lo < hi)) {
      std::ostringstream os;
      os << "Rng::uniform: need finite lo < hi, got lo = " << lo << ", hi = " << hi;
      fail(ErrorCode::kInvalidArgument, os.str());
    }
    const double x = lo + (hi - lo) * uniform01();
    // Rounding can land exactly on hi; keep the interval half-open.
    return x < hi ? x : std::nextafter(hi, lo);
  }

  /// A standard normal N(0, 1) sample (Marsaglia polar method, see the file comment).
  double normal() {
    if (has_spare_) {
      has_spare_ = false;
      return spare_;
    }
    double a = 0.0;
    double b = 0.0;
    double s = 0.0;
    do {
      a = 2.0 * uniform01() - 1.0;
      b = 2.0 * uniform01() - 1.0;
      s = a * a + b * b;
    } while (s >= 1.0 || s == 0.0);
    const double scale = std::sqrt(-2.0 * std::log(s) / s);
    spare_ = b * scale;
    has_spare_ = true;
    return a * scale;
  }

  /// N(mean, sigma^2). Throws kInvalidArgument unless sigma >= 0 and both are finite.
  double normal(double mean, double sigma) {
    if (!std::isfinite(mean) || !std::isfinite(sigma) || sigma < 0.0) {
      std::ostringstream os;
      os << "Rng::normal: need finite mean and sigma >= 0, got mean = " << mean
         << ", sigma = " << sigma;
      fail(ErrorCode::kInvalidArgument, os.str());
    }
    return mean + sigma * normal();
  }

  /// A sample of zero-mean Gaussian noise (through its Cholesky factor).
  template <int N>
  Vec<N> sample(const Gaussian<N>& noise) {
    return noise.sample([this]() { return normal(); });
  }

 private:
  Engine engine_;
  std::uint64_t seed_;
  double spare_ = 0.0;
  bool has_spare_ = false;
};

}  // namespace sylva::sim
