#pragma once
/// Stopping a run from outside, two ways.
/// - Abort (Ctrl-C in Python): long loops ask the installed poll, at most every 0.1 s of wall
///   time, whether the user asked to stop, and throw Interrupted when so. Interrupted is
///   deliberately not a std::exception: nothing that turns failures into data (a failed run, a
///   compare row, a check's verdict) catches it, so it ends the whole call. The poll is
///   process-wide, as signals are; without one nothing is asked (a clock read per call is the
///   whole cost).
/// - Stop and keep (`condyn run` under SIGINT, SIGTERM, SIGHUP): request_stop, and the step
///   driver ends the run as a failure at its next step, with the rows computed so far.

#include <functional>
#include <string>

namespace condyn {

/// Thrown by check_interrupt when the poll says the user asked to stop.
struct Interrupted {};

/// Installs the poll (an empty function removes it). It is called from the thread that runs the
/// integration; it returns true to stop the run.
void set_interrupt_poll(std::function<bool()> poll);

/// Throws Interrupted when a poll is installed, at least kInterruptPollSeconds have passed since
/// this thread last asked it, and it returns true. Long loops call it once per iteration (the
/// step driver per step, the exact reference per output time).
void check_interrupt();

/// A stop asked from outside the process (the CLI's handler of SIGINT, SIGTERM and SIGHUP,
/// src/output/temp_registry.hpp), unlike the poll not an abort: the run in progress ends at its
/// next step as a failed run (FailureKind::interrupted), keeping the rows it computed, and the
/// caller decides what follows. `signal` is the signal's number (not 0). Async-signal-safe: a
/// lock-free atomic store, callable from a signal handler.
void request_stop(int signal) noexcept;
/// The signal of the stop asked, 0 when none (one atomic load: the step driver asks every step).
[[nodiscard]] int stop_requested() noexcept;
/// "SIGINT (Ctrl-C)", "SIGTERM", "SIGHUP", else "signal N": the stop's cause in messages.
[[nodiscard]] std::string signal_name(int signal);

/// How often a running integration asks (a tenth of a second: the wait feels immediate, the
/// cost is one clock read per step and ten polls a second).
inline constexpr double kInterruptPollSeconds = 0.1;

}  // namespace condyn
