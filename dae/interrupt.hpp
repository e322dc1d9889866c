#pragma once
/// Stopping a run from outside: Ctrl-C in Python. Long loops ask the installed poll, at most
/// every 0.1 s of wall time, whether the user asked to stop, and throw Interrupted when so.
/// Interrupted is deliberately not a std::exception: nothing that turns failures into data (a
/// failed run, a compare row, a check's verdict) catches it, so it ends the whole call. The poll
/// is process-wide, as signals are; without one (the CLI: Ctrl-C ends the process) nothing is
/// asked (a clock read per call is the whole cost).

#include <functional>

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

/// How often a running integration asks (a tenth of a second: the wait feels immediate, the
/// cost is one clock read per step and ten polls a second).
inline constexpr double kInterruptPollSeconds = 0.1;

}  // namespace condyn
