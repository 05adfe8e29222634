// predict and update allocate nothing once the filter has seen its largest state: counted
// with a replaced global operator new (Eigen's own allocations go through malloc, so they
// are checked as well through EIGEN_RUNTIME_NO_MALLOC).

#define EIGEN_RUNTIME_NO_MALLOC
#include <atomic>
#include <cstdlib>
#include <new>

#include <sylva/sylva.hpp>

#include "sylva_catch.hpp"

namespace {
std::atomic<long> g_allocations{0};
}

void* operator new(std::size_t size) {
  ++g_allocations;
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
// Every form is replaced, so that memory never crosses between our malloc and a sanitizer's
// allocator (Catch2 uses the nothrow form).
void* operator new[](std::size_t size) { return operator new(size); }
void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
  ++g_allocations;
  return std::malloc(size == 0 ? 1 : size);
}
void* operator new[](std::size_t size, const std::nothrow_t& tag) noexcept { return operator new(size, tag); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }

using namespace sylva;

TEMPLATE_TEST_CASE("predict and a single update do not allocate in steady state", "[filter][allocation]",
                   (Ekf<Unicycle2D, Point2>)) {
  TestType ekf(Vec<3>(0.0, 0.0, 0.1), Mat<3, 3>::Identity() * 0.01);
  const auto r = Gaussian<2>::sigmas(Vec<2>(0.05, 0.02));
  const auto q = Gaussian<2>::sigmas(Vec<2>(0.05, 0.02));
  for (int i = 0; i < 200; ++i) ekf.add(i, InverseRangeBearing{}, Vec<2>(3.0 + 0.05 * i, -1.5 + 0.015 * i), r);
  ekf.update(RangeBearing{}, 0, Vec<2>(3.0, -1.4), r);  // warm-up: sizes the workspace

  const long before = g_allocations.load();
  Eigen::internal::set_is_malloc_allowed(false);
  for (int step = 0; step < 20; ++step) {
    ekf.predict(Vec<2>(0.5, 0.05), 0.1, q);
    for (Id id : {3, 50, 120, 199}) {
      const Vec<2> z = RangeBearing{}(ekf.robotMean(), ekf.template landmarkMean<Point2>(id)) + Vec<2>(0.01, -0.002);
      ekf.update(RangeBearing{}, id, z, r);
    }
  }
  Eigen::internal::set_is_malloc_allowed(true);
  CHECK(g_allocations.load() - before == 0);
}
