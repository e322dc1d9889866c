#pragma once
/// A second thread that runs one task beside the caller's: `run(a, b)` runs `b` on a worker
/// thread and `a` on the calling thread, and returns when both are done. What the two tasks
/// compute must not depend on which thread runs them (they write disjoint data): with one lane
/// (CONDYN_NUM_THREADS=1, or a machine with one core) `run` calls `a` then `b` on the caller, and
/// the results are the same bit for bit.
///
/// Written here rather than taken from OpenMP: condyn is not built with OpenMP (CHOLMOD's loops
/// are kept on the calling thread, models/core/fixed_pattern_cholmod.cpp), and task pairs of a
/// millisecond or more need nothing more than a worker that sleeps between them (a futex wait,
/// std::atomic::wait: polling before it gained nothing measurable), so that an idle run or a
/// busy machine loses no core to it.

#include <atomic>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>

namespace condyn {

class SecondLane {
 public:
  /// With lanes == 2 starts the worker; with 1 runs every task pair on the caller.
  explicit SecondLane(int lanes);
  ~SecondLane();
  SecondLane(const SecondLane&) = delete;
  SecondLane& operator=(const SecondLane&) = delete;

  /// The process's lane (allowed_lanes() lanes), started at the first call, which condyn's
  /// solves, products and vector operations share.
  static SecondLane& shared();

  /// Runs `on_caller` here and `on_worker` on the worker (both here, in that order, with one
  /// lane, or while another thread's run holds the worker: any thread may call it); rethrows the
  /// first exception either threw, after both ended.
  void run(const std::function<void()>& on_caller, const std::function<void()>& on_worker);
  /// 2 with a worker, else 1.
  [[nodiscard]] int lanes() const { return worker_.joinable() ? 2 : 1; }

 private:
  void work();
  std::thread worker_;
  std::mutex busy_;
  long owner_;  ///< the process that started the worker (a forked child runs tasks itself)
  const std::function<void()>* task_ = nullptr;
  std::exception_ptr worker_error_;
  /// Tasks posted so far; the worker has finished the k-th when done_ == k.
  std::atomic<unsigned> posted_{0};
  std::atomic<unsigned> done_{0};
  std::atomic<bool> stop_{false};
};

/// SecondLane::shared() (declared beside the classes that take a lane by default).
SecondLane& default_lane();

/// The lanes condyn's own parallel loops use: 1 when CONDYN_NUM_THREADS is set to 1 or the
/// machine has one core, else 2 (more are not used: see docs/benchmarks.md).
[[nodiscard]] int allowed_lanes();

}  // namespace condyn
