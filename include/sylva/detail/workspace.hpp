#pragma once
/// @file
/// Growing a workspace without breaking the strong guarantee. Eigen's `resize` frees the old
/// buffer before it allocates the new one, so when that allocation fails the object is left
/// pointing at freed memory (freed again when it is destroyed). These allocate the new buffer
/// first and then swap it in: if the allocation fails, the workspace is as it was.

#include <Eigen/Core>

namespace sylva::detail {

/// Makes `m` rows x cols (contents unspecified), allocating only if its size changes.
template <typename Dense>
void resizeWorkspace(Dense& m, Eigen::Index rows, Eigen::Index cols) {
  if (m.rows() == rows && m.cols() == cols) return;
  Dense fresh(rows, cols);
  m.swap(fresh);
}

/// Gives the vector `v` at least `size` entries (contents unspecified), allocating only if it
/// has fewer.
template <typename Vector>
void growWorkspace(Vector& v, Eigen::Index size) {
  if (v.size() >= size) return;
  Vector fresh(size);
  v.swap(fresh);
}

}  // namespace sylva::detail
