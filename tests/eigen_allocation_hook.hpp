#pragma once
// For the test files that count or fail allocations (they also include
// replaced_operator_new.hpp): Eigen's own heap allocations go through malloc, not operator new,
// so they are caught through EIGEN_RUNTIME_NO_MALLOC, whose check is an eigen_assert. This header
// routes eigen_assert to a handler that works in Release (NDEBUG) builds too: a "heap allocation
// is forbidden" failure is counted as one allocation (sylva_test::countAllocation, which throws
// std::bad_alloc at the allocation a fault-injection test chose), any other failed Eigen
// assertion is counted in g_other_eigen_asserts and printed. Include it before any Eigen header;
// tests/CMakeLists.txt compiles a folder's files that do so as one executable of their own.

#include <atomic>
#include <cstdio>
#include <cstring>

#include "replaced_operator_new.hpp"

namespace sylva_test {

inline std::atomic<long> g_other_eigen_asserts{0};

inline void onEigenAssert(const char* what) {
  if (std::strstr(what, "heap allocation is forbidden") != nullptr) {
    countAllocation();
  } else {
    ++g_other_eigen_asserts;
    std::fprintf(stderr, "eigen_assert failed: %s\n", what);
  }
}

}  // namespace sylva_test

#define EIGEN_RUNTIME_NO_MALLOC
#define eigen_assert(x) ((x) ? static_cast<void>(0) : ::sylva_test::onEigenAssert(#x))
