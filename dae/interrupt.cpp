#include "dae/interrupt.hpp"

#include <chrono>
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

}  // namespace

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
