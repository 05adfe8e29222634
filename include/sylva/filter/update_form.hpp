#pragma once
/// @file
/// Covariance update forms, chosen at compile time (`BasicEkf<UpdateForm, Robot, ...>`).
///
/// - `SymmetricUpdate` (default): P -= W W^T with W = P H^T L^-T, L the Cholesky factor of
///   the innovation covariance S. It is the textbook P - P H^T S^-1 H P written so that the
///   subtracted term is symmetric positive semi-definite by construction; only the lower
///   triangle of P is touched (the filter keeps the lower triangle authoritative).
/// - `JosephUpdate`: P = (I - K H) P (I - K H)^T + K R K^T, which stays symmetric positive
///   semi-definite even for a sub-optimal gain. It is computed in product form on the full
///   matrix: mirror the lower triangle, A = (I - K H) P, then A - (A H^T) K^T + K R K^T, i.e.
///   several full passes over P instead of half of one (several times the symmetric form's
///   time: docs/update-benchmarks.md, column "Joseph / efficient update").
///
/// Each form's kernels are templates on the measurement size M only (Eigen::Dynamic for a
/// batch), not on the filter: every filter type with the same M shares them. The filter
/// runs them around its own hooks (the invariant and observability-constrained corrections,
/// the landmarks' domain checks), so that nothing of it is written before the last thing that
/// can fail:
///   increment(PHt, llt, nu, workspace, delta)   delta = P H^T S^-1 nu, and the W or K the
///                                               covariance step needs; workspaces only
///   (the filter's hooks, which may refuse the update)
///   JosephUpdate::posterior(...)                the Joseph posterior, into a workspace
///   (the filter writes its mean)
///   SymmetricUpdate::downdate(P, W), or the Joseph posterior copied into P

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <algorithm>
#include <vector>

#include "sylva/core/deferred.hpp"
#include "sylva/core/parallel.hpp"
#include "sylva/detail/lower_rank_update.hpp"
#include "sylva/detail/workspace.hpp"

namespace sylva {
namespace detail {

/// Reusable buffers of an update (innovation, S, R, L^-1 nu, L^-1, the linearizations, the
/// landmark iterates of an iterated update, the gain's n x cols matrix, the Joseph form's
/// n x n posterior). Each grows only when a larger state or batch is seen, so an update
/// allocates nothing in steady state. A template only so that its bodies are compiled where it
/// is used (core/deferred.hpp); every filter's is `BatchWorkspace<void>`.
template <typename Tag = void>
struct BatchWorkspace {
  using Vector = Deferred<Eigen::VectorXd, Tag>;
  using Matrix = Deferred<Eigen::MatrixXd, Tag>;
  enum Slot { kInnovation, kInnovationCovariance, kNoise, kWhitenedInnovation, kInverseFactor, kIterates, kSlotCount };
  Vector buffers[kSlotCount];
  Vector lins;
  std::vector<int> offsets;
  Vector gain;    ///< W = P H^T L^-T (a batch) or K = P H^T S^-1 (Joseph), n x cols
  Vector joseph;  ///< the Joseph form's n x n posterior, before it is copied into P

  Eigen::Map<Vector> vector(Slot slot, int size) { return Eigen::Map<Vector>(grown(buffers[slot], size), size); }
  Eigen::Map<Matrix> matrix(Slot slot, int rows) {
    return Eigen::Map<Matrix>(grown(buffers[slot], static_cast<Eigen::Index>(rows) * rows), rows, rows);
  }
  /// The gain's n x cols matrix (cols = M, or `cols` for M = Eigen::Dynamic).
  template <int M>
  Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, M>> gainMatrix(int n, int cols) {
    return Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, M>>(grown(gain, static_cast<Eigen::Index>(n) * cols), n, cols);
  }
  Eigen::Map<Matrix> josephMatrix(int n) { return Eigen::Map<Matrix>(grown(joseph, static_cast<Eigen::Index>(n) * n), n, n); }

 private:
  static double* grown(Vector& buffer, Eigen::Index size) {
    growWorkspace(buffer, size);
    return buffer.data();
  }
};

}  // namespace detail

struct SymmetricUpdate {
  static constexpr const char* kName = "SymmetricUpdate";

  /// How a batch (M = Eigen::Dynamic) forms W = P H^T L^-T:
  ///   BySolve = false: L^-1 explicitly (small, k x k), then the product P H^T (L^-1)^T;
  ///   BySolve = true:  a triangular solve with L^T on the right, in place on a copy of P H^T.
  /// BM_PairedGain (bench/slam_step.cpp; scripts/step_limit_report.sh reports it) times both
  /// from the same factor, paired: with SSE2's two-double packets (the baseline x86-64 build)
  /// the solve takes about half to two thirds of the product's time; with AVX's wider packets
  /// it takes longer, up to twice at large n. The filter takes the product in every build for
  /// now: the solve changes the last bits of a baseline build's results, which moves every
  /// published figure of the baseline build (and some decisions that flip on them), so it is
  /// to be switched on, for SSE2 only, together with a regeneration of all of them. The two
  /// agree to round-off (tests/filter/fusion.test.cpp). Skipping L^-1's zeros does not keep
  /// the product's bits either: Eigen's triangular product, and a sum over l = 0..j column by
  /// column, each differed from it in about a third of the shapes tried from k = 8 on (rows
  /// 1-256, k 1-64; clang++ and g++ -O3, baseline x86-64; 2026-12-02).
  static constexpr bool kGainBySolve = false;

  /// delta = W L^-1 nu with W = P H^T L^-T (L: the Cholesky factor of S), returning W for
  /// `downdate`. `PHt` (n x M) is P H^T; for a fixed M it is overwritten by W.
  /// With `parallel`, a batch's rows of W are shared among its threads (the same result).
  template <int M, bool BySolve = kGainBySolve, typename PHtMap, typename Llt, typename Nu, typename Workspace,
            typename Delta>
  static Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, M>> increment(PHtMap& PHt, const Llt& llt, const Nu& nu,
                                                                         Workspace& ws, Delta& delta,
                                                                         Parallel* parallel = nullptr) {
    const int n = static_cast<int>(PHt.rows());
    if constexpr (M == Eigen::Dynamic) {
      // Row blocks of W (BySolve says how each is formed) keep Eigen's packed panels on
      // the stack.
      const int cols = static_cast<int>(PHt.cols());
      auto L_inv = ws.matrix(Workspace::kInverseFactor, BySolve ? 0 : cols);
      if constexpr (!BySolve) {
        L_inv.setIdentity();
        llt.matrixL().solveInPlace(L_inv);
      }
      auto W = ws.template gainMatrix<Eigen::Dynamic>(n, cols);
      const int block = detail::lowerRankUpdateTile(cols);
      const int blocks = (n + block - 1) / block;
      const auto rowBlocks = [&](int first, int last) {
        for (int b = first; b < last; ++b) {
          const int r0 = b * block;
          const int rows = std::min(block, n - r0);
          auto W_rows = W.middleRows(r0, rows);
          if constexpr (BySolve) {
            W_rows = PHt.middleRows(r0, rows);
            llt.matrixU().template solveInPlace<Eigen::OnTheRight>(W_rows);
          } else {
            W_rows.noalias() = PHt.middleRows(r0, rows) * L_inv.transpose();  // L^-1 has zeros above
          }
        }
      };
      const int parts = parallel != nullptr && n >= detail::kParallelMinRows ? parallel->concurrency() : 1;
      runRanges(parallel, blocks, parts, rowBlocks);
      auto v = ws.vector(Workspace::kWhitenedInnovation, cols);
      if constexpr (BySolve) {
        v = nu;
        llt.matrixL().solveInPlace(v);
      } else {
        v.noalias() = L_inv * nu;
      }
      delta.noalias() = W * v;
      return W;
    } else {
      llt.matrixU().template solveInPlace<Eigen::OnTheRight>(PHt);
      const Eigen::Matrix<double, M, 1> v = llt.matrixL().solve(nu);
      delta.noalias() = PHt * v;
      return Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, M>>(PHt.data(), n, M);
    }
  }

  /// P -= W W^T on the lower triangle of P (n x n).
  /// With `parallel`, a batch's tiles of P are shared among its threads (the same result).
  template <int M, typename PBlock>
  static void downdate(PBlock&& P, const Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, M>>& W,
                       Parallel* parallel = nullptr) {
    if constexpr (M == Eigen::Dynamic) {
      detail::subtractLowerRankUpdate(P, W, parallel);  // a tiled symmetric rank-km update
    } else {
      // One column at a time: a fixed-size GEMV per column, one pass over half of P.
      const int n = static_cast<int>(P.rows());
      for (int j = 0; j < n; ++j) {
        const Eigen::Matrix<double, M, 1> w_j = W.row(j).transpose();
        P.col(j).tail(n - j).noalias() -= W.bottomRows(n - j) * w_j;
      }
    }
  }
};

struct JosephUpdate {
  static constexpr const char* kName = "JosephUpdate";

  /// delta = K nu with K = P H^T S^-1, returning K (kept in the workspace) for `posterior`.
  template <int M, typename PHtMap, typename Llt, typename Nu, typename Workspace, typename Delta>
  static Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, M>> increment(const PHtMap& PHt, const Llt& llt, const Nu& nu,
                                                                         Workspace& ws, Delta& delta,
                                                                         Parallel* /*parallel: serial*/ = nullptr) {
    auto K = ws.template gainMatrix<M>(static_cast<int>(PHt.rows()), static_cast<int>(PHt.cols()));
    K = PHt;
    llt.matrixU().template solveInPlace<Eigen::OnTheRight>(K);
    llt.matrixL().template solveInPlace<Eigen::OnTheRight>(K);
    delta.noalias() = K * nu;
    return K;
  }

  /// The posterior (I - K H) P (I - K H)^T + K R K^T, full n x n, in the workspace: nothing of
  /// the filter is written (copy its lower triangle into P). `applyHt(A, out)` writes
  /// out = A H^T for an n x n matrix A; `PHt` is reused for it. Every product is taken here,
  /// before the filter writes anything: R K^T allocates (M x n), and for a large state the
  /// n x n products make Eigen take its packing buffers from the heap.
  template <int M, typename PBlock, typename PHtMap, typename RMat, typename Workspace, typename ApplyHt>
  static Eigen::Map<Eigen::MatrixXd> posterior(const PBlock& P, const Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, M>>& K,
                                               PHtMap& PHt, const RMat& R, Workspace& ws, ApplyHt&& applyHt) {
    const Eigen::Matrix<double, M, Eigen::Dynamic> RKt = R * K.transpose();
    auto A = ws.josephMatrix(static_cast<int>(P.rows()));
    // A = (I - K H) P = P - K (P H^T)^T on the full matrix.
    A = P.template selfadjointView<Eigen::Lower>();
    A.noalias() -= K * PHt.transpose();
    // B = A H^T, in the PHt workspace.
    applyHt(A, PHt);
    // A - B K^T + K R K^T = (I - K H) P (I - K H)^T + K R K^T
    A.noalias() -= PHt * K.transpose();
    A.noalias() += K * RKt;
    return A;
  }
};

}  // namespace sylva
