#pragma once
// The global operator new, replaced for the test executables that count allocations (or make
// one fail): the counters here, the operators in replaced_operator_new.cpp, which
// tests/CMakeLists.txt compiles once into each executable whose files include this header
// (test_allocation, test_allocation_slow). Their files include eigen_allocation_hook.hpp
// first, so that every unit of one executable compiles Eigen with the same eigen_assert.
//
// Every allocation adds one to sylva_test::g_allocations; with sylva_test::g_fail_at = k > 0
// the k-th counted allocation of the throwing forms throws std::bad_alloc, as a full heap
// would. Every form is replaced, so that memory never crosses between this malloc and a
// sanitizer's allocator (Catch2 uses the nothrow form: counted, never failed).

#include <atomic>
#include <new>

namespace sylva_test {

inline std::atomic<long> g_allocations{0};
inline std::atomic<long> g_fail_at{0};  ///< 0: nothing fails

/// Counts one allocation; throws std::bad_alloc if it is the one chosen to fail.
inline void countAllocation() {
  const long n = ++g_allocations;
  const long fail_at = g_fail_at.load();
  if (fail_at > 0 && n == fail_at) throw std::bad_alloc();
}

}  // namespace sylva_test
