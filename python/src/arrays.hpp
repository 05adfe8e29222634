#pragma once
// Conversions between Python array-likes and sylva's fixed-size Eigen types. Every argument
// that crosses into the library passes through here, so a wrong shape or dtype is refused
// with sylva's own error (kInvalidArgument, kNonFinite is left to the library) naming the
// argument, before any filter is touched.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <sstream>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "sylva/core/error.hpp"
#include "sylva/core/types.hpp"

namespace sylva_py {

namespace py = pybind11;

/// "(3,)" or "(2, 2)": a shape as numpy prints it.
inline std::string shapeText(const py::array& a) {
  std::ostringstream os;
  os << '(';
  for (py::ssize_t i = 0; i < a.ndim(); ++i) os << (i ? ", " : "") << a.shape(i);
  os << (a.ndim() == 1 ? ",)" : ")");
  return os.str();
}

/// `obj` as a float64 numpy array. Integers and floats of any width are taken (converted
/// exactly or rounded as numpy does); bool, complex, strings and objects are refused.
inline py::array_t<double> asDoubleArray(const py::handle& obj, const std::string& what) {
  py::array a;
  try {
    a = py::array::ensure(obj);
  } catch (const py::error_already_set&) {
  }
  if (!a)
    sylva::fail(sylva::ErrorCode::kInvalidArgument,
                what + ": expected an array of numbers, got a " +
                    std::string(py::str(py::type::of(obj).attr("__name__"))));
  const char kind = a.dtype().kind();
  if (kind != 'f' && kind != 'i' && kind != 'u') {
    sylva::fail(sylva::ErrorCode::kInvalidArgument,
                what + ": expected real numbers (a float or integer dtype), got dtype " +
                    std::string(py::str(a.dtype())));
  }
  return py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(a);
}

/// A fixed-size vector from an array of shape (N,).
template <int N>
sylva::Vec<N> toVec(const py::handle& obj, const std::string& what) {
  const auto a = asDoubleArray(obj, what);
  if (a.ndim() != 1 || a.shape(0) != N)
    sylva::fail(sylva::ErrorCode::kInvalidArgument,
                what + ": expected shape (" + std::to_string(N) + ",), got " + shapeText(a));
  sylva::Vec<N> v;
  for (int i = 0; i < N; ++i) v[i] = a.at(i);
  return v;
}

/// A fixed-size matrix from an array of shape (R, C).
template <int R, int C>
sylva::Mat<R, C> toMat(const py::handle& obj, const std::string& what) {
  const auto a = asDoubleArray(obj, what);
  if (a.ndim() != 2 || a.shape(0) != R || a.shape(1) != C)
    sylva::fail(sylva::ErrorCode::kInvalidArgument,
                what + ": expected shape (" + std::to_string(R) + ", " + std::to_string(C) +
                    "), got " + shapeText(a));
  sylva::Mat<R, C> m;
  for (int i = 0; i < R; ++i)
    for (int j = 0; j < C; ++j) m(i, j) = a.at(i, j);
  return m;
}

/// Rows of an array of shape (n, N), n >= 0 (a list of N-vectors). An empty list is taken as
/// no rows.
template <int N>
std::vector<sylva::Vec<N>> toRows(const py::handle& obj, const std::string& what) {
  const auto a = asDoubleArray(obj, what);
  if (a.ndim() == 1 && a.shape(0) == 0) return {};
  if (a.ndim() != 2 || a.shape(1) != N)
    sylva::fail(sylva::ErrorCode::kInvalidArgument,
                what + ": expected shape (n, " + std::to_string(N) + "), got " + shapeText(a));
  std::vector<sylva::Vec<N>> rows(static_cast<std::size_t>(a.shape(0)));
  for (py::ssize_t r = 0; r < a.shape(0); ++r)
    for (int i = 0; i < N; ++i) rows[static_cast<std::size_t>(r)][i] = a.at(r, i);
  return rows;
}

/// Integer ids from a sequence or an integer array of shape (n,).
inline std::vector<sylva::Id> toIds(const py::handle& obj, const std::string& what) {
  py::array a;
  try {
    a = py::array::ensure(obj);
  } catch (const py::error_already_set&) {
  }
  if (!a)
    sylva::fail(sylva::ErrorCode::kInvalidArgument, what + ": expected a sequence of integer ids");
  if (a.ndim() == 1 && a.shape(0) == 0) return {};
  const char kind = a.dtype().kind();
  if (kind != 'i' && kind != 'u')
    sylva::fail(sylva::ErrorCode::kInvalidArgument,
                what + ": expected integer ids, got dtype " + std::string(py::str(a.dtype())));
  if (a.ndim() != 1)
    sylva::fail(sylva::ErrorCode::kInvalidArgument,
                what + ": expected shape (n,), got " + shapeText(a));
  const auto ids = py::array_t<sylva::Id, py::array::c_style | py::array::forcecast>::ensure(a);
  return std::vector<sylva::Id>(ids.data(), ids.data() + ids.shape(0));
}

/// A numpy array of n values (cols == 0) or of n rows of `cols` values, entry (i, c) being
/// get(i, c): how the bindings turn a list of C++ records into one array per field.
template <typename T, typename Get>
py::array_t<T> arrayOf(std::size_t n, int cols, Get&& get) {
  const auto rows = static_cast<py::ssize_t>(n);
  if (cols == 0) {
    py::array_t<T> out(rows);
    for (py::ssize_t i = 0; i < rows; ++i) out.mutable_at(i) = get(static_cast<std::size_t>(i), 0);
    return out;
  }
  py::array_t<T> out({rows, static_cast<py::ssize_t>(cols)});
  for (py::ssize_t i = 0; i < rows; ++i)
    for (int c = 0; c < cols; ++c) out.mutable_at(i, c) = get(static_cast<std::size_t>(i), c);
  return out;
}

/// A numpy copy of a std::vector of numbers.
template <typename T>
py::array_t<T> toArray(const std::vector<T>& v) {
  return py::array_t<T>(static_cast<py::ssize_t>(v.size()), v.data());
}

/// A numpy copy of any Eigen vector or matrix (a vector comes out 1-D).
template <typename Derived>
py::array_t<double> toArray(const Eigen::MatrixBase<Derived>& m) {
  if (Derived::ColsAtCompileTime == 1) {
    py::array_t<double> out(static_cast<py::ssize_t>(m.rows()));
    for (Eigen::Index i = 0; i < m.rows(); ++i) out.mutable_at(i) = m(i, 0);
    return out;
  }
  py::array_t<double> out({static_cast<py::ssize_t>(m.rows()), static_cast<py::ssize_t>(m.cols())});
  for (Eigen::Index i = 0; i < m.rows(); ++i)
    for (Eigen::Index j = 0; j < m.cols(); ++j) out.mutable_at(i, j) = m(i, j);
  return out;
}

}  // namespace sylva_py
