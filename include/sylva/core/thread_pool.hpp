#pragma once
/// @file
/// `ThreadPool`: a fixed set of threads for `Parallel` (parallel.hpp). The threads are made
/// by the constructor and wait between runs; `run` hands them parts without allocating.
///
///   auto pool = std::make_shared<sylva::ThreadPool>(2);
///   ekf.setParallel(pool);   // updates of large states spread their rank-k step over 2 threads
///
/// One run at a time: filters that share a pool (copies of one filter) take turns. A program
/// that uses it links the platform's threads (CMake: find_package(Threads) and
/// Threads::Threads).

#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "sylva/core/error.hpp"
#include "sylva/core/parallel.hpp"

namespace sylva {

class ThreadPool final : public Parallel {
 public:
  /// `threads` parts at once: the calling thread and threads - 1 workers (1: no workers).
  explicit ThreadPool(int threads) : threads_(threads) {
    if (threads < 1 || threads > 1024)
      fail(ErrorCode::kInvalidArgument, "ThreadPool: threads must be in [1, 1024], got " + std::to_string(threads));
    workers_.reserve(static_cast<std::size_t>(threads - 1));
    try {
      for (int w = 1; w < threads; ++w) workers_.emplace_back([this, w] { work(w); });
    } catch (...) {
      stopWorkers();
      throw;
    }
  }
  ~ThreadPool() override { stopWorkers(); }
  ThreadPool(const ThreadPool&) = delete;
  ThreadPool& operator=(const ThreadPool&) = delete;

  int concurrency() const override { return threads_; }

  void run(int parts, void (*task)(void*, int), void* context) override {
    if (parts <= 0) return;
    std::lock_guard<std::mutex> one_run(run_mutex_);
    if (workers_.empty() || parts == 1) {
      for (int p = 0; p < parts; ++p) task(context, p);
      return;
    }
    {
      std::lock_guard<std::mutex> lock(mutex_);
      task_ = task;
      context_ = context;
      parts_ = parts;
      busy_ = static_cast<int>(workers_.size());
      ++generation_;
    }
    start_.notify_all();
    runShare(0, task, context, parts);  // the caller takes parts 0, threads, 2 threads, ...
    std::unique_lock<std::mutex> lock(mutex_);
    done_.wait(lock, [this] { return busy_ == 0; });
  }

 private:
  void runShare(int first, void (*task)(void*, int), void* context, int parts) const {
    for (int p = first; p < parts; p += threads_) task(context, p);
  }

  void work(int index) {
    std::uint64_t seen = 0;
    for (;;) {
      void (*task)(void*, int) = nullptr;
      void* context = nullptr;
      int parts = 0;
      {
        std::unique_lock<std::mutex> lock(mutex_);
        start_.wait(lock, [&] { return stop_ || generation_ != seen; });
        if (stop_) return;
        seen = generation_;
        task = task_;
        context = context_;
        parts = parts_;
      }
      runShare(index, task, context, parts);
      std::lock_guard<std::mutex> lock(mutex_);
      if (--busy_ == 0) done_.notify_one();
    }
  }

  void stopWorkers() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stop_ = true;
    }
    start_.notify_all();
    for (std::thread& t : workers_) t.join();
    workers_.clear();
  }

  int threads_;
  std::mutex run_mutex_;  ///< one run at a time
  std::mutex mutex_;      ///< guards everything below
  std::condition_variable start_, done_;
  std::uint64_t generation_ = 0;
  bool stop_ = false;
  void (*task_)(void*, int) = nullptr;
  void* context_ = nullptr;
  int parts_ = 0;
  int busy_ = 0;  ///< workers still running the current generation
  std::vector<std::thread> workers_;
};

}  // namespace sylva
