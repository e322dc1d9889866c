#include "dae/interface/interrupt.hpp"

#include <atomic>
#include <chrono>
#include <csignal>
#include <mutex>

namespace condyn {

namespace {

std::mutex& poll_mutex() {
  static std::mutex m;
  return m;
}

std::function<bool()>& installed_poll() {
  static std::function<bool()> poll;
  return poll;
}

/// Set from a signal handler: a lock-free atomic, so the store is async-signal-safe.
std::atomic<int> g_stop_signal{0};
static_assert(std::atomic<int>::is_always_lock_free, "a signal handler stores it");

}  // namespace

void request_stop(int signal) noexcept { g_stop_signal.store(signal); }

int stop_requested() noexcept { return g_stop_signal.load(); }

std::string signal_name(int signal) {
  switch (signal) {
    case SIGINT:
      return "SIGINT (Ctrl-C)";
    case SIGTERM:
      return "SIGTERM";
    case SIGHUP:
      return "SIGHUP";
    default:
      return "signal " + std::to_string(signal);
  }
}

void set_interrupt_poll(std::function<bool()> poll) {
  const std::lock_guard lock(poll_mutex());
  installed_poll() = std::move(poll);
}

void check_interrupt() {
  using Clock = std::chrono::steady_clock;
  thread_local Clock::time_point last_poll{};
  const auto now = Clock::now();
  if (std::chrono::duration<double>(now - last_poll).count() < kInterruptPollSeconds) return;
  last_poll = now;
  std::function<bool()> poll;
  {
    const std::lock_guard lock(poll_mutex());
    poll = installed_poll();
  }
  if (poll && poll()) throw Interrupted{};
}

}  // namespace condyn
