#pragma once
// The global operator new, replaced for the test executables that count allocations (or make
// one fail). Include it in exactly one translation unit: tests/CMakeLists.txt builds a file
// that includes it as an executable of its own, outside the unity builds.
//
// Every allocation adds one to sylva_test::g_allocations; with sylva_test::g_fail_at = k > 0
// the k-th counted allocation of the throwing forms throws std::bad_alloc, as a full heap
// would. Every form is replaced, so that memory never crosses between this malloc and a
// sanitizer's allocator (Catch2 uses the nothrow form: counted, never failed).

#include <atomic>
#include <cstdlib>
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

void* operator new(std::size_t size) {
  sylva_test::countAllocation();
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t size) { return operator new(size); }
void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
  ++sylva_test::g_allocations;
  return std::malloc(size == 0 ? 1 : size);
}
void* operator new[](std::size_t size, const std::nothrow_t& tag) noexcept { return operator new(size, tag); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }
