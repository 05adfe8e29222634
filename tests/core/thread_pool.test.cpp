// ThreadPool: every part runs once per run, runs do not overlap, and bad sizes are refused.

#include <atomic>
#include <thread>
#include <vector>

#include <sylva/core/thread_pool.hpp>

#include "error_helpers.hpp"
#include "sylva_catch.hpp"

namespace unity_core_thread_pool {

using sylva::ThreadPool;
using sylva_test::throwsCode;

namespace {
struct Tally {
  std::vector<std::atomic<int>> calls;
  explicit Tally(int parts) : calls(static_cast<std::size_t>(parts)) {}
  static void count(void* context, int part) {
    static_cast<Tally*>(context)->calls[static_cast<std::size_t>(part)].fetch_add(1);
  }
};
}  // namespace

TEST_CASE("ThreadPool runs every part exactly once per run") {
  for (int threads : {1, 2, 3, 4}) {
    ThreadPool pool(threads);
    CHECK(pool.concurrency() == threads);
    for (int parts : {0, 1, 2, 3, 5, 9}) {
      INFO("threads " << threads << ", parts " << parts);
      Tally tally(parts);
      const int runs = 200;
      for (int r = 0; r < runs; ++r) pool.run(parts, &Tally::count, &tally);
      for (int p = 0; p < parts; ++p) CHECK(tally.calls[static_cast<std::size_t>(p)].load() == runs);
    }
  }
}

TEST_CASE("ThreadPool returns only when every part has finished, and runs one caller at a time") {
  ThreadPool pool(3);
  struct Shared {
    std::atomic<int> inside{0};
    std::atomic<int> most{0};
    std::atomic<long> finished{0};
  } shared;
  const auto task = [](void* context, int) {
    auto& s = *static_cast<Shared*>(context);
    const int now = s.inside.fetch_add(1) + 1;
    int most = s.most.load();
    while (now > most && !s.most.compare_exchange_weak(most, now)) {
    }
    std::this_thread::yield();
    s.inside.fetch_sub(1);
    s.finished.fetch_add(1);
  };
  // Two callers share the pool: their runs take turns, so at most 3 parts run at once.
  // (Catch2's assertions are for the test's own thread: the other caller counts its misses.)
  std::atomic<int> early_returns{0};
  const auto caller = [&] {
    for (int r = 0; r < 300; ++r) {
      const long before = shared.finished.load();
      pool.run(3, task, &shared);
      if (shared.finished.load() - before < 3) early_returns.fetch_add(1);
    }
  };
  std::thread other(caller);
  caller();
  other.join();
  CHECK(early_returns.load() == 0);
  CHECK(shared.finished.load() == 2 * 300 * 3);
  CHECK(shared.most.load() <= 3);
  CHECK(shared.inside.load() == 0);
}

TEST_CASE("ThreadPool refuses a thread count below 1 or above 1024") {
  CHECK(throwsCode([] { ThreadPool pool(0); }, sylva::ErrorCode::kInvalidArgument));
  CHECK(throwsCode([] { ThreadPool pool(-3); }, sylva::ErrorCode::kInvalidArgument));
  CHECK(throwsCode([] { ThreadPool pool(1025); }, sylva::ErrorCode::kInvalidArgument));
}

}  // namespace unity_core_thread_pool
