#pragma once
// Runs independent jobs on a pool of threads, keeps each result in its job's slot (so the
// output order never depends on scheduling), and prints progress with an ETA on stderr.

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <exception>
#include <functional>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace sylva_examples {

inline std::string formatDuration(double seconds) {
  char buf[32];
  const long s = static_cast<long>(seconds + 0.5);
  if (s >= 3600)
    std::snprintf(buf, sizeof buf, "%ldh%02ldm", s / 3600, (s % 3600) / 60);
  else
    std::snprintf(buf, sizeof buf, "%ldm%02lds", s / 60, s % 60);
  return buf;
}

/// Calls `work(i)` for i in [0, count) on `threads` threads and stores the results in order.
/// An exception in one job is rethrown after all threads stop.
template <typename Result>
std::vector<Result> runAll(int count,
                           int threads,
                           const std::function<Result(int)>& work,
                           bool progress = true) {
  std::vector<Result> results(static_cast<std::size_t>(std::max(count, 0)));
  std::atomic<int> next{0};
  std::atomic<int> done{0};
  std::mutex mutex;
  std::exception_ptr error;
  const auto start = std::chrono::steady_clock::now();
  auto last_print = start;
  const auto worker = [&] {
    for (int i = next++; i < count; i = next++) {
      try {
        results[static_cast<std::size_t>(i)] = work(i);
      } catch (...) {
        const std::lock_guard<std::mutex> lock(mutex);
        if (!error) error = std::current_exception();
        next = count;  // stop handing out jobs
      }
      const int finished = ++done;
      if (!progress) continue;
      const std::lock_guard<std::mutex> lock(mutex);
      const auto now = std::chrono::steady_clock::now();
      if (finished < count && now - last_print < std::chrono::seconds(2)) continue;
      last_print = now;
      const double elapsed = std::chrono::duration<double>(now - start).count();
      const double eta = elapsed / finished * (count - finished);
      std::fprintf(stderr,
                   "\r[%d/%d] %3d%%  elapsed %s  ETA %s   ",
                   finished,
                   count,
                   100 * finished / std::max(count, 1),
                   formatDuration(elapsed).c_str(),
                   formatDuration(eta).c_str());
      if (finished == count) std::fprintf(stderr, "\n");
    }
  };
  std::vector<std::thread> pool;
  const int n_threads = std::max(1, std::min(threads, count));
  for (int t = 0; t < n_threads; ++t) pool.emplace_back(worker);
  for (auto& t : pool) t.join();
  if (error) std::rethrow_exception(error);
  return results;
}

}  // namespace sylva_examples
