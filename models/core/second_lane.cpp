// A worker thread for one task beside the caller's (models/core/second_lane.hpp).

#include "models/core/second_lane.hpp"

#include <cstdlib>
#include <cstring>
#include <new>
#include <utility>

#include <unistd.h>

namespace condyn {

namespace {

/// Waits until `a` differs from `old` (a futex wait: no core spins meanwhile).
void await_change(const std::atomic<unsigned>& a, unsigned old) {
  while (a.load(std::memory_order_acquire) == old) a.wait(old, std::memory_order_acquire);
}

}  // namespace

int allowed_lanes() {
  const char* env = std::getenv("CONDYN_NUM_THREADS");
  if (env != nullptr && std::strcmp(env, "1") == 0) return 1;
  return std::thread::hardware_concurrency() >= 2 ? 2 : 1;
}

SecondLane& SecondLane::shared() {
  static SecondLane lane(allowed_lanes());
  return lane;
}

SecondLane& default_lane() { return SecondLane::shared(); }

SecondLane::SecondLane(int lanes) : owner_(getpid()) {
  if (lanes >= 2) worker_ = std::thread([this] { work(); });
}

SecondLane::~SecondLane() {
  if (!worker_.joinable()) return;
  if (getpid() != owner_) {
    // A forked child's copy: no worker to stop or join, and neither join nor detach applies to a
    // thread of another process; the handle is left, unowned.
    try {
      new std::thread(std::move(worker_));  // NOLINT(cppcoreguidelines-owning-memory)
    } catch (const std::bad_alloc&) {
      worker_.detach();  // no memory even for the handle: let it go
    }
    return;
  }
  stop_.store(true, std::memory_order_release);
  posted_.fetch_add(1, std::memory_order_release);
  posted_.notify_one();
  worker_.join();
}

void SecondLane::work() {
  unsigned seen = 0;
  for (;;) {
    await_change(posted_, seen);
    seen = posted_.load(std::memory_order_acquire);
    if (stop_.load(std::memory_order_acquire)) return;
    try {
      (*task_)();
    } catch (...) {
      worker_error_ = std::current_exception();
    }
    done_.store(seen, std::memory_order_release);
    done_.notify_one();
  }
}

void SecondLane::run(const std::function<void()>& on_caller,
                     const std::function<void()>& on_worker) {
  std::unique_lock<std::mutex> hold(busy_, std::try_to_lock);
  // In a child forked after the worker started (Python's multiprocessing, a shell-out) the worker
  // did not follow: its tasks run here (a copy of a held lock fails try_lock likewise).
  if (!worker_.joinable() || !hold.owns_lock() || getpid() != owner_) {
    on_caller();
    on_worker();
    return;
  }
  task_ = &on_worker;
  worker_error_ = nullptr;
  const unsigned ticket = posted_.fetch_add(1, std::memory_order_release) + 1;
  posted_.notify_one();
  std::exception_ptr caller_error;
  try {
    on_caller();
  } catch (...) {
    caller_error = std::current_exception();
  }
  for (unsigned d = done_.load(std::memory_order_acquire); d != ticket;
       d = done_.load(std::memory_order_acquire)) {
    await_change(done_, d);
  }
  if (caller_error) std::rethrow_exception(caller_error);
  if (worker_error_) std::rethrow_exception(worker_error_);
}

}  // namespace condyn
