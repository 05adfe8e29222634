#pragma once
// everyAllocationFails: the fault-injection loop of tests/filter/fault_injection*.test.cpp.
// Include it after eigen_allocation_hook.hpp (which includes replaced_operator_new.hpp), in a
// file that tests/CMakeLists.txt builds into an allocation-counting executable.

#include <functional>

#include <Eigen/Core>

#include "filter_snapshot.hpp"
#include "replaced_operator_new.hpp"
#include "sylva_catch.hpp"

namespace sylva_test {

/// Runs `operation` on copies of `filter`, failing its 1st, 2nd, ... allocation until it
/// completes. After each failure the copy must equal `filter` (mean, covariance, slots, and
/// `unchanged(copy)` for what a snapshot does not see), and the operation repeated on it
/// without a fault must give exactly what it gives on a fresh copy. Returns the number of
/// allocations the operation made.
template <typename Filter>
long everyAllocationFails(const Filter& filter, const std::function<void(Filter&)>& operation,
                          const std::function<bool(const Filter&)>& unchanged = nullptr) {
  Filter reference = filter;
  operation(reference);
  const Snapshot expected(reference);
  const Snapshot before(filter);
  for (long k = 1; k < 10000; ++k) {
    Filter copy = filter;
    bool failed = false;
    g_allocations = 0;
    g_fail_at = k;
    Eigen::internal::set_is_malloc_allowed(false);
    try {
      operation(copy);
    } catch (const std::bad_alloc&) {
      failed = true;
    }
    Eigen::internal::set_is_malloc_allowed(true);
    g_fail_at = 0;
    if (!failed) return k - 1;
    INFO("allocation " << k << " failed");
    CHECK(Snapshot(copy) == before);
    if (unchanged) CHECK(unchanged(copy));
    operation(copy);
    CHECK(Snapshot(copy) == expected);
  }
  FAIL("the operation never completed");
  return -1;
}

}  // namespace sylva_test
