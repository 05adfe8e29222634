#pragma once
/// @file
/// The narrow interface through which `BasicEkf` runs the compressed EKF
/// (filter/compression.hpp). The filter's predict, update, add, remove and reads call these
/// hooks only when compression is on, through a pointer: what compression does is compiled
/// once per filter type, and only in a program that calls `setCompression`, never for every
/// predict and every measurement size (docs/build-time.md).

#include <cstddef>
#include <type_traits>

#include <Eigen/Core>

#include "sylva/core/types.hpp"

namespace sylva::detail {

/// An update's terms, as raw column-major views into the filter's workspaces.
struct CompressedUpdateTerms {
  /// H, observation by observation: its m x R robot block at lins + i * stride, then its m x L
  /// landmark block (stride = m (R + L)); the landmark's rows start at offsets[i].
  const double* lins;
  const int* offsets;
  int count;
  int m;
  int landmark_dim;
  /// The Cholesky factor L of S (count m square, in the lower triangle), leading dimension.
  const double* factor;
  Eigen::Index factor_stride;
  /// The innovation (count m).
  const double* nu;
  /// The active rows' gain, a x (count m), contiguous: W = P_AA H^T L^-T (symmetric form) or
  /// K_A = P_AA H^T S^-1 (`gain_is_k`: the Joseph form).
  const double* gain;
  bool gain_is_k;
};

/// What the filter asks of the compressed EKF. `Ekf` is the filter type; the implementation
/// (detail::Compression<Ekf>) is its friend and reads its storage.
template <typename Ekf>
class CompressionHooks {
 public:
  virtual ~CompressionHooks() = default;
  /// A copy, allocated with new (ClonePtr owns it).
  virtual CompressionHooks* clone() const = 0;

  /// The active part: the first activeDim() rows of the state.
  virtual int activeDim() const = 0;
  /// Local steps since the last global update (0: the stored state is current).
  virtual long steps() const = 0;
  virtual long globalUpdates() const = 0;

  /// The global update: the whole stored state made current. No estimate changes.
  virtual void synchronize(Ekf& ekf) = 0;
  /// A global update, then a new region: the landmarks the selector chooses, and those of
  /// `forced` (count ids), lead the state. No estimate changes.
  virtual void enterRegion(Ekf& ekf, const Id* forced, std::size_t count) = 0;

  /// Enters a new region if the rule says the robot has left this one (before a predict).
  virtual void enterRegionIfLeft(Ekf& ekf) = 0;

  /// The active rows moved by F (kRobotDim square, column-major: the robot's rows of phi).
  virtual void predictRobot(const double* F) = 0;
  /// An update of the active part: staged (may allocate, changes nothing), then committed.
  virtual void stageUpdate(const Ekf& ekf, const CompressedUpdateTerms& terms) = 0;
  virtual void commitUpdate(Ekf& ekf) = 0;
  /// A landmark added at the end of the active part, J_robot (rows x kRobotDim, column-major)
  /// its Jacobian with respect to the robot.
  virtual void stageExtend(const double* J_robot, int rows) = 0;
  virtual void commitExtend() = 0;
  /// A fresh region of `a` rows (after a global update).
  virtual void stageBegin(int a) = 0;
  virtual void commitBegin() = 0;

  /// The current rows x cols block of P at (row, col) (column-major into out), where it
  /// involves the passive part.
  virtual void currentBlock(const Ekf& ekf, int row, int col, int rows, int cols, double* out) const = 0;
  /// out (rows) += the passive part's mean correction for the rows at `offset` (>= activeDim).
  virtual void correctMean(const Ekf& ekf, int offset, int rows, double* out) const = 0;
  /// Brings a copy of the stored covariance (n x n, both triangles) up to date.
  virtual void correctCovariance(const Ekf& ekf, Eigen::MatrixXd& full) const = 0;
};

/// The implementation, in filter/compression.hpp: include it to call `setCompression`.
template <typename Ekf>
class Compression;

/// Whether T is a complete type where this is first asked (for a clear error).
template <typename T, typename = void>
struct IsDefined : std::false_type {};
template <typename T>
struct IsDefined<T, std::void_t<decltype(sizeof(T))>> : std::true_type {};

/// An owning pointer that copies by `clone()` (a copied filter gets its own region). Written
/// out rather than wrapping std::unique_ptr: <memory> costs every translation unit of the
/// filter more than this does.
template <typename T>
class ClonePtr {
 public:
  ClonePtr() = default;
  ClonePtr(const ClonePtr& other) : p_(other.p_ ? other.p_->clone() : nullptr) {}
  ClonePtr(ClonePtr&& other) noexcept : p_(other.p_) { other.p_ = nullptr; }
  ClonePtr& operator=(const ClonePtr& other) {
    if (this != &other) reset(other.p_ ? other.p_->clone() : nullptr);  // cloned first: the strong guarantee
    return *this;
  }
  ClonePtr& operator=(ClonePtr&& other) noexcept {
    if (this != &other) {
      reset(other.p_);
      other.p_ = nullptr;
    }
    return *this;
  }
  ~ClonePtr() { delete p_; }

  T* operator->() const { return p_; }
  explicit operator bool() const { return p_ != nullptr; }
  /// Takes ownership of `p` (a `new` object, or nullptr) and deletes the one held before.
  void reset(T* p = nullptr) noexcept {
    T* old = p_;
    p_ = p;
    delete old;
  }

 private:
  T* p_ = nullptr;
};

}  // namespace sylva::detail
