#pragma once
/// @file
/// `Parallel`: how the filter spreads the large parts of an update over threads. The filter
/// runs serially unless one is set (`Ekf::setParallel`); `ThreadPool` (thread_pool.hpp) is
/// the one sylva ships, and a program that already has threads (OpenMP, TBB, its own pool)
/// can implement this interface on them instead.

namespace sylva {

class Parallel {
 public:
  virtual ~Parallel() = default;

  /// How many parts run at once (1: serially).
  virtual int concurrency() const = 0;

  /// Calls task(context, part) once for each part in [0, parts), possibly several at once,
  /// and returns when every call has returned. `task` must not throw. An implementation must
  /// not allocate here: the filter calls it inside updates, which allocate nothing in steady
  /// state.
  virtual void run(int parts, void (*task)(void* context, int part), void* context) = 0;
};

/// Calls f(first, last) for `parts` contiguous ranges that cover [0, count), through
/// `parallel`; on the calling thread alone, as f(0, count), when there is none or one part.
template <typename F>
void runRanges(Parallel* parallel, int count, int parts, const F& f) {
  if (parallel == nullptr || parts <= 1 || count <= 1) {
    f(0, count);
    return;
  }
  struct Job {
    const F* f;
    int count, parts;
  } job{&f, count, parts};
  parallel->run(parts, [](void* context, int part) {
    const Job& j = *static_cast<const Job*>(context);
    (*j.f)(j.count * part / j.parts, j.count * (part + 1) / j.parts);
  }, &job);
}

}  // namespace sylva
