#pragma once
/// @file
/// `detail::LowerCovariance`: the filter's covariance storage and the block operations its
/// predict and update are made of.
///
/// Storage: a capacity x capacity column-major matrix of which the top-left n x n corner is
/// in use and only its lower triangle is authoritative (the entries above the diagonal are
/// never read). Growing allocates new storage and copies the lower triangle; nothing else
/// here allocates.
///
/// Every operation is a template on block sizes only: the robot's rows R, a landmark's rows
/// L, a measurement's rows M. Filters that share those sizes share their instantiations, so
/// a program with several filter types (an Ekf and a JosephEkf of the same robot, or two
/// robots of three coordinates) compiles each kernel once (docs/build-time.md). The class is a
/// template only so that its bodies are compiled where it is used (core/deferred.hpp): the
/// filter names it `LowerCovariance<Deferred<void, Filter>>`, which is `LowerCovariance<void>`
/// for every filter.

#include <Eigen/Core>
#include <algorithm>

#include "sylva/core/deferred.hpp"
#include "sylva/core/types.hpp"

namespace sylva::detail {

template <typename Tag = void>
class LowerCovariance {
 public:
  using Matrix = Deferred<Eigen::MatrixXd, Tag>;

  /// Rows and columns in use (n).
  int dim() const { return n_; }
  void setDim(int n) { n_ = n; }
  int capacity() const { return capacity_; }

  /// P(i, j), read from the lower triangle.
  double operator()(int i, int j) const { return i >= j ? m_(i, j) : m_(j, i); }

  /// The stored matrix: its lower triangle's top-left n x n corner is P.
  Matrix& stored() { return m_; }
  const Matrix& stored() const { return m_; }

  /// The n x n corner in use (only its lower triangle is P).
  auto inUse() { return m_.topLeftCorner(n_, n_); }
  auto inUse() const { return m_.topLeftCorner(n_, n_); }

  /// The R x C block of the full symmetric P starting at (row, col), for blocks that are
  /// either on the diagonal or entirely off it.
  /// Plain loops rather than Eigen block expressions: each (R, C) would instantiate its own
  /// block and transpose types (docs/build-time.md), for a copy of at most a few hundred
  /// numbers.
  template <int R, int C>
  Mat<R, C> block(int row, int col) const {
    Mat<R, C> out;
    if (row >= col + C) {  // entirely below the diagonal: stored as is
      for (int j = 0; j < C; ++j)
        for (int i = 0; i < R; ++i) out(i, j) = m_(row + i, col + j);
    } else if (col >= row + R) {  // entirely above: its transpose is stored
      for (int j = 0; j < C; ++j)
        for (int i = 0; i < R; ++i) out(i, j) = m_(col + j, row + i);
    } else {  // on the diagonal
      for (int j = 0; j < C; ++j)
        for (int i = 0; i < R; ++i) out(i, j) = (*this)(row + i, col + j);
    }
    return out;
  }

  /// New storage of `capacity` holding the lower triangle in use: allocates, and changes
  /// nothing here (hand it to `adopt`).
  Matrix grown(int capacity) const {
    Matrix out = Matrix::Zero(capacity, capacity);
    out.topLeftCorner(n_, n_).template triangularView<Eigen::Lower>() = m_.topLeftCorner(n_, n_);
    return out;
  }
  void adopt(Matrix& storage) {
    m_.swap(storage);
    capacity_ = static_cast<int>(m_.rows());
  }

  /// Deletes rows and columns [off, off + d), moving the blocks after them up in place
  /// (std::copy runs forwards, so an overlap is safe): no temporary, so it cannot fail.
  void erase(int off, int d) {
    const int tail = n_ - off - d;
    if (tail > 0) {
      // Columns left of the block: move their lower rows up by d.
      for (int j = 0; j < off; ++j) {
        double* col = m_.col(j).data();
        std::copy(col + off + d, col + n_, col + off);
      }
      // Columns right of the block: move left by d and up by d.
      for (int j = off; j < off + tail; ++j) {
        const double* src = m_.col(j + d).data() + j + d;
        double* dst = m_.col(j).data() + j;
        std::copy(src, src + (n_ - j - d), dst);
      }
    }
    n_ -= d;
  }

  /// Opens d zero rows and columns before row `off`, moving the blocks from `off` on down
  /// and right in place (backwards, so an overlap is safe). Needs capacity for n + d; cannot
  /// fail.
  void insert(int off, int d) {
    // Columns left of the gap: their rows from `off` on move down by d.
    for (int j = 0; j < off; ++j) {
      double* col = m_.col(j).data();
      std::copy_backward(col + off, col + n_, col + n_ + d);
      std::fill(col + off, col + off + d, 0.0);
    }
    // Columns from `off` on move right by d and down by d, the last one first.
    for (int j = n_ - 1; j >= off; --j) {
      const double* src = m_.col(j).data() + j;
      double* dst = m_.col(j + d).data() + j + d;
      std::copy(src, src + (n_ - j), dst);
    }
    // The gap's own columns.
    for (int j = off; j < off + d; ++j) std::fill(m_.col(j).data() + j, m_.col(j).data() + n_ + d, 0.0);
    n_ += d;
  }

  /// Exchanges the d rows and columns at i with the d at j (i + d <= j): P <- Pi P Pi^T for
  /// the permutation that swaps the two blocks. O(n d) moves; cannot fail.
  void swapBlocks(int i, int j, int d) {
    const auto at = [this](int r, int c) -> double& { return r >= c ? m_(r, c) : m_(c, r); };
    for (int k = 0; k < n_; ++k) {
      if ((k >= i && k < i + d) || (k >= j && k < j + d)) continue;
      for (int t = 0; t < d; ++t) std::swap(at(k, i + t), at(k, j + t));
    }
    for (int t = 0; t < d; ++t)
      for (int s = t; s < d; ++s) std::swap(m_(i + s, i + t), m_(j + s, j + t));
    // The block between the two, stored at rows j.., columns i.., becomes its transpose.
    for (int t = 0; t < d; ++t)
      for (int s = t + 1; s < d; ++s) std::swap(m_(j + s, i + t), m_(j + t, i + s));
  }

  /// P <- P(perm, perm): row and column i of the result are perm[i] of P (perm: a
  /// permutation of 0..n-1). The result is written into `spare`, a matrix of the storage's
  /// size, which then becomes the storage (the old storage is handed back in `spare`), so
  /// nothing is allocated. Each column is copied in runs of rows that stay consecutive.
  template <typename Perm>
  void permute(const Perm& perm, Matrix& spare) {
    for (int j = 0; j < n_; ++j) {
      const int pj = perm[j];
      double* dst = spare.col(j).data();
      for (int i = j; i < n_;) {
        const int r0 = perm[i];
        int k = 1;
        while (i + k < n_ && perm[i + k] == r0 + k) ++k;
        if (r0 >= pj) {  // stored in column pj, below its diagonal
          const double* src = m_.col(pj).data() + r0;
          std::copy(src, src + k, dst + i);
        } else {  // above the diagonal (all or part): read the transposed entries
          for (int t = 0; t < k; ++t) dst[i + t] = (*this)(r0 + t, pj);
        }
        i += k;
      }
    }
    m_.swap(spare);
  }

  /// P_rr <- P_rr_next (symmetrized), P_mr <- P_mr F^T: the robot block (the first R rows)
  /// and its cross-covariances through a robot-only Jacobian F (eq. 2.27). O(n).
  template <int R>
  void transformRobotBlock(const Mat<R, R>& F, const Mat<R, R>& P_rr_next) {
    m_.template topLeftCorner<R, R>() = 0.5 * (P_rr_next + P_rr_next.transpose());
    // Lower storage holds P_mr (m x r).
    for (int row = R; row < n_; ++row) {
      const Vec<R> p = m_.row(row).template head<R>().transpose();
      m_.row(row).template head<R>() = (F * p).transpose();
    }
  }

  /// out(:, col0 .. col0 + M) += P H^T for one observation whose H has the blocks J_z_x
  /// (the robot's R columns) and J_z_l (the landmark's L columns at offset o), reading the
  /// robot and landmark columns of P from the lower triangle in three pieces each. O(n M).
  template <int R, int L, typename Jx, typename Jl, typename Out>
  void addTimesHt(const Jx& J_z_x, const Jl& J_z_l, int o, Out& out, int col0) const {
    constexpr int M = Jx::RowsAtCompileTime;
    auto dest = out.template middleCols<M>(col0);
    // Robot columns of P (offset 0): rows [0, R) are the robot block, rows [R, n) are stored.
    dest.template topRows<R>().noalias() += block<R, R>(0, 0) * J_z_x.transpose();
    const int below_robot = n_ - R;
    dest.bottomRows(below_robot).noalias() += m_.block(R, 0, below_robot, R) * J_z_x.transpose();
    // Landmark columns of P at offset o: rows [0, o) are the transposed stored row block,
    // rows [o, o + L) the diagonal block, rows [o + L, n) are stored.
    dest.topRows(o).noalias() += m_.block(o, 0, L, o).transpose() * J_z_l.transpose();
    dest.template middleRows<L>(o).noalias() += block<L, L>(o, o) * J_z_l.transpose();
    const int below = n_ - o - L;
    dest.bottomRows(below).noalias() += m_.block(o + L, o, below, L) * J_z_l.transpose();
  }

  /// H_a P H_b^T for two observations, each with a robot block (R columns) and one landmark
  /// block (La columns at offset oa, Lb at ob): the cross term of a joint innovation
  /// covariance, and with a = b the H P H^T of one. O(1) in n.
  template <int R, typename JaX, typename JaL, typename JbX, typename JbL>
  Mat<JaX::RowsAtCompileTime, JbX::RowsAtCompileTime> crossCovariance(const JaX& Ja_x, const JaL& Ja_l, int oa,
                                                                      const JbX& Jb_x, const JbL& Jb_l, int ob) const {
    constexpr int La = JaL::ColsAtCompileTime;
    constexpr int Lb = JbL::ColsAtCompileTime;
    const auto P_rr = block<R, R>(0, 0);
    const auto P_rb = block<R, Lb>(0, ob);
    const auto P_ar = block<La, R>(oa, 0);
    const auto P_ab = block<La, Lb>(oa, ob);
    return Ja_x * (P_rr * Jb_x.transpose() + P_rb * Jb_l.transpose()) +
           Ja_l * (P_ar * Jb_x.transpose() + P_ab * Jb_l.transpose());
  }

 private:
  Matrix m_;
  int n_ = 0;
  int capacity_ = 0;
};

}  // namespace sylva::detail
