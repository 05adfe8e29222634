#pragma once
/// @file
/// The two figures of a machine limit (docs/step-limit.md), measured inside a benchmark
/// program so that a family can put its own time against them in the same run:
///   `gemmPeakGflops()`            the GEMM peak of this build and machine now
///   `lowerReadWriteSeconds(n)`    one in-place read and write of the lower triangle of an
///                                 n x n matrix of doubles (the least an update of P moves)
/// bench/slam_step.cpp's BM_GemmPeak and BM_BoundLowerReadWrite time the same work as
/// benchmark families of their own.

#include <Eigen/Core>
#include <algorithm>
#include <chrono>

namespace sylva_bench {

/// In GFLOP/s: the best of 20 products C += A B of 512 x 512 x 512.
inline double gemmPeakGflops() {
  constexpr int kSize = 512;
  const Eigen::MatrixXd A = Eigen::MatrixXd::Constant(kSize, kSize, 1e-3);
  const Eigen::MatrixXd B = Eigen::MatrixXd::Constant(kSize, kSize, 1e-3);
  Eigen::MatrixXd C = Eigen::MatrixXd::Zero(kSize, kSize);
  double best = 1e300;
  for (int k = 0; k < 20; ++k) {
    const auto t0 = std::chrono::steady_clock::now();
    C.noalias() += A * B;
    best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  volatile double sink = C(0, 0);  // keeps the products
  (void)sink;
  return 2e-9 * kSize * kSize * kSize / best;
}

/// In seconds: the best of `repeats` in-place scalings of the lower triangle of an n x n
/// matrix (the factor alternates so the values stay put).
inline double lowerReadWriteSeconds(int n, int repeats = 20) {
  Eigen::MatrixXd P = Eigen::MatrixXd::Constant(n, n, 1.0);
  double factor = 1.0 + 1e-9;
  double best = 1e300;
  for (int k = 0; k < repeats; ++k) {
    const auto t0 = std::chrono::steady_clock::now();
    for (int j = 0; j < n; ++j) P.col(j).tail(n - j) *= factor;
    best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    factor = 1.0 / factor;
  }
  volatile double sink = P(n - 1, 0);
  (void)sink;
  return best;
}

}  // namespace sylva_bench
