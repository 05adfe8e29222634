#pragma once
/// @file
/// `JacobianRef<R, C>`: an optional, non-owning, fixed-size view of a Jacobian that a
/// model fills only when the caller asked for it (`if (J) { ... }`). Pass a fixed-size
/// matrix, a block of a larger column-major matrix, or `sylva::skip` / `{}` for "not needed".

#include <Eigen/Core>
#include <cassert>

#include "sylva/core/deferred.hpp"

namespace sylva {

/// Placeholder meaning "I do not need this Jacobian".
struct Skip {};
inline constexpr Skip skip{};

template <int Rows_, int Cols_, typename Scalar_ = double>
class JacobianRef {
 public:
  static constexpr int kRows = Rows_;
  static constexpr int kCols = Cols_;
  using Matrix = Eigen::Matrix<Scalar_, Rows_, Cols_>;
  using View = Eigen::Map<Matrix, Eigen::Unaligned, Eigen::OuterStride<>>;

  JacobianRef() = default;
  JacobianRef(Skip) {}  // NOLINT(google-explicit-constructor): `J = skip` reads naturally
  JacobianRef(Matrix& m) : data_(m.data()), outer_stride_(Rows_) {}  // NOLINT

  /// A writable column-major block (e.g. `H.block<2, 3>(0, 0)` or `H.middleCols(...)`).
  template <typename Derived>
  JacobianRef(Eigen::DenseBase<Derived>& block)  // NOLINT
      : data_(block.derived().data()), outer_stride_(block.derived().outerStride()) {
    static_assert(!(Derived::Flags & Eigen::RowMajorBit) || Rows_ == 1 || Cols_ == 1,
                  "JacobianRef needs a column-major matrix or block");
    assert(block.rows() == Rows_ && block.cols() == Cols_);
  }
  template <typename XprType, int BlockRows, int BlockCols, bool InnerPanel>
  JacobianRef(Eigen::Block<XprType, BlockRows, BlockCols, InnerPanel>&& block)  // NOLINT
      : data_(block.data()), outer_stride_(block.outerStride()) {
    assert(block.rows() == Rows_ && block.cols() == Cols_);
  }

  /// True when the caller wants this Jacobian.
  explicit operator bool() const { return data_ != nullptr; }

  /// The Jacobian as a writable fixed-size Eigen expression.
  View operator*() const {
    assert(data_ != nullptr);
    return View(data_, Rows_, Cols_, Eigen::OuterStride<>(outer_stride_));
  }

 private:
  Scalar_* data_ = nullptr;
  Eigen::Index outer_stride_ = Rows_;
};

/// `JacobianRef<Rows, Cols>` as a parameter of a function template declared
/// `template <typename Tag = void>`: the same type, spelled so that the body that writes the
/// Jacobian compiles only where the function is called (core/deferred.hpp). The models use it
/// for their Jacobian outputs; a model of your own may take `JacobianRef` as well, and then
/// costs its includers a little more compile time.
template <int Rows, int Cols, typename Tag>
using JacobianArg = detail::Deferred<JacobianRef<Rows, Cols>, Tag>;

}  // namespace sylva
