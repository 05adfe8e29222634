#pragma once
/// @file
/// `detail::subtractLowerRankUpdate(P, W)`: P <- P - W W^T on the lower triangle of a square
/// block P (n x n) for a tall W (n x m): the covariance update of a batched EKF update,
/// P -= (P H^T L^-T)(P H^T L^-T)^T.
///
/// Why not Eigen's `selfadjointView<Lower>().rankUpdate(W, -1)` on the whole matrix: Eigen
/// packs its GEMM panels (kc x mc and kc x nc doubles) on the stack only while each panel is
/// under EIGEN_STACK_ALLOCATION_LIMIT bytes (128 KiB by default) and on the heap above it, so
/// for a map of a few hundred landmarks every batched update would allocate. Here the lower
/// triangle is cut into square tiles small enough that Eigen's panels stay on the stack:
///   diagonal tiles     P_jj -= W_j W_j^T   (Eigen's symmetric rank update, lower part only)
///   tiles below them   P_ij -= W_i W_j^T   (a plain GEMM)
/// Each tile of P is read and written once, as in the one-call version, and nothing is
/// allocated. Tiles are taken column block by column block, top to bottom, so consecutive
/// tiles walk down the same columns of the column-major storage.

#include <Eigen/Core>
#include <algorithm>

namespace sylva::detail {

/// Side of the square tiles for a rank-m update: the largest multiple of 8 (at most 256)
/// whose m x tile panel of doubles fits Eigen's stack allocation limit.
inline int lowerRankUpdateTile(int m) {
  constexpr int kLimitDoubles = static_cast<int>(EIGEN_STACK_ALLOCATION_LIMIT / sizeof(double));
  const int fit = kLimitDoubles / std::max(1, m);
  return std::clamp(fit / 8 * 8, 8, 256);
}

/// P <- P - W W^T, lower triangle only (the strictly upper part of P is not read; the upper
/// part of diagonal tiles is not written). P is n x n, W is n x m.
template <typename PBlock, typename WMatrix>
void subtractLowerRankUpdate(PBlock&& P, const WMatrix& W) {
  const Eigen::Index n = P.rows();
  const Eigen::Index tile = lowerRankUpdateTile(static_cast<int>(W.cols()));
  for (Eigen::Index j0 = 0; j0 < n; j0 += tile) {
    const Eigen::Index bj = std::min(tile, n - j0);
    const auto W_j = W.middleRows(j0, bj);
    P.block(j0, j0, bj, bj).template selfadjointView<Eigen::Lower>().rankUpdate(W_j, -1.0);
    for (Eigen::Index i0 = j0 + bj; i0 < n; i0 += tile) {
      const Eigen::Index bi = std::min(tile, n - i0);
      P.block(i0, j0, bi, bj).noalias() -= W.middleRows(i0, bi) * W_j.transpose();
    }
  }
}

}  // namespace sylva::detail
