#pragma once
/// @file
/// `detail::subtractLowerRankUpdate(P, W)`: P <- P - W W^T on the lower triangle of a square
/// block P (n x n) for a tall W (n x m): the covariance update of a batched EKF update,
/// P -= (P H^T L^-T)(P H^T L^-T)^T. `subtractLowerProduct(P, X, Y)`: the same for a symmetric
/// X Y^T (the compressed EKF's global update, P_BB -= (V psi) V^T).
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

#include "sylva/core/parallel.hpp"

namespace sylva::detail {

/// Rows of P below which an update stays on the calling thread. Work is shared out in whole
/// tiles (up to 256 x 256), so a small P has too few of them to split evenly: at n = 512 two
/// threads get a quarter and three quarters of the work, and lose to one. From about n = 640
/// the rank-24 update runs clearly faster on two (bench/slam_step.cpp,
/// BM_RankUpdateWallOneThread against BM_RankUpdateWallTwoThreads).
constexpr Eigen::Index kParallelMinRows = 640;

/// Side of the square tiles for a rank-m update: the largest multiple of 8 (at most 256)
/// whose m x tile panel of doubles fits Eigen's stack allocation limit.
inline int lowerRankUpdateTile(int m) {
  constexpr int kLimitDoubles = static_cast<int>(EIGEN_STACK_ALLOCATION_LIMIT / sizeof(double));
  const int fit = kLimitDoubles / std::max(1, m);
  return std::clamp(fit / 8 * 8, 8, 256);
}

/// The tiles of the lower triangle of an n x n matrix, column block by column block and top to
/// bottom, that part `part` of `parts` takes: consecutive runs of equal work (a tile's rows
/// times its columns, half of that on the diagonal). f(i0, bi, j0, bj) is called for each.
/// Each tile is computed the same way whoever takes it, so the result does not depend on
/// `parts`.
template <typename F>
void forEachTileOfPart(Eigen::Index n, Eigen::Index tile, int part, int parts, F&& f) {
  const auto cost = [](Eigen::Index bi, Eigen::Index bj, bool diagonal) {
    return static_cast<double>(bi) * static_cast<double>(bj) * (diagonal ? 0.5 : 1.0);
  };
  const double total = 0.5 * static_cast<double>(n) * static_cast<double>(n);
  double done = 0.0;
  for (Eigen::Index j0 = 0; j0 < n; j0 += tile) {
    const Eigen::Index bj = std::min(tile, n - j0);
    for (Eigen::Index i0 = j0; i0 < n; i0 += (i0 == j0 ? bj : tile)) {
      const Eigen::Index bi = i0 == j0 ? bj : std::min(tile, n - i0);
      const double c = cost(bi, bj, i0 == j0);
      // The part whose share holds the tile's middle takes it.
      const int owner = std::min(parts - 1, static_cast<int>((done + 0.5 * c) / total * parts));
      done += c;
      if (owner == part) f(i0, bi, j0, bj);
    }
  }
}

/// Runs updateTile(i0, bi, j0, bj) over the tiles of the lower triangle of an n x n matrix:
/// on the calling thread, or shared among `parallel`'s threads when n is at least `min_rows`.
template <typename UpdateTile>
void forEachLowerTile(Eigen::Index n, Eigen::Index tile, Parallel* parallel, Eigen::Index min_rows,
                      const UpdateTile& updateTile) {
  const int parts = parallel != nullptr && n >= min_rows ? parallel->concurrency() : 1;
  if (parts <= 1) {
    forEachTileOfPart(n, tile, 0, 1, updateTile);
    return;
  }
  struct Job {
    const UpdateTile* update;
    Eigen::Index n, tile;
    int parts;
  } job{&updateTile, n, tile, parts};
  parallel->run(parts, [](void* context, int part) {
    const Job& j = *static_cast<const Job*>(context);
    forEachTileOfPart(j.n, j.tile, part, j.parts, *j.update);
  }, &job);
}

/// P <- P - W W^T, lower triangle only (the strictly upper part of P is not read; the upper
/// part of diagonal tiles is not written). P is n x n, W is n x m. With `parallel`, and n of
/// at least `min_rows`, the tiles are shared among its threads; the result is the same bit
/// for bit.
template <typename PBlock, typename WMatrix>
void subtractLowerRankUpdate(PBlock&& P, const WMatrix& W, Parallel* parallel = nullptr,
                             Eigen::Index min_rows = kParallelMinRows) {
  const auto updateTile = [&](Eigen::Index i0, Eigen::Index bi, Eigen::Index j0, Eigen::Index bj) {
    const auto W_j = W.middleRows(j0, bj);
    if (i0 == j0) {
      P.block(j0, j0, bj, bj).template selfadjointView<Eigen::Lower>().rankUpdate(W_j, -1.0);
    } else {
      P.block(i0, j0, bi, bj).noalias() -= W.middleRows(i0, bi) * W_j.transpose();
    }
  };
  forEachLowerTile(P.rows(), lowerRankUpdateTile(static_cast<int>(W.cols())), parallel, min_rows, updateTile);
}

/// P <- P - X Y^T, lower triangle only, for an X Y^T the caller knows to be symmetric (e.g.
/// X = V M, Y = V with M symmetric: no factor of M is needed). The same tiles, threads and
/// guarantees as `subtractLowerRankUpdate`; a diagonal tile costs a full product instead of
/// half of one.
template <typename PBlock, typename XMatrix, typename YMatrix>
void subtractLowerProduct(PBlock&& P, const XMatrix& X, const YMatrix& Y, Parallel* parallel = nullptr,
                          Eigen::Index min_rows = kParallelMinRows) {
  const auto updateTile = [&](Eigen::Index i0, Eigen::Index bi, Eigen::Index j0, Eigen::Index bj) {
    const auto Y_j = Y.middleRows(j0, bj);
    if (i0 == j0) {
      P.block(j0, j0, bj, bj).template triangularView<Eigen::Lower>() -= X.middleRows(j0, bj) * Y_j.transpose();
    } else {
      P.block(i0, j0, bi, bj).noalias() -= X.middleRows(i0, bi) * Y_j.transpose();
    }
  };
  forEachLowerTile(P.rows(), lowerRankUpdateTile(static_cast<int>(X.cols())), parallel, min_rows, updateTile);
}

}  // namespace sylva::detail
