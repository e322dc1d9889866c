#pragma once
/// Temporary files removed on a fatal signal (SIGTERM, SIGINT, SIGHUP, SIGPIPE): how an output's
/// temporary file (src/output/output_files.hpp) is cleaned up when the program is killed before it
/// commits; and `condyn run`'s stop on a signal, which keeps the rows computed. Internal to src/.

#include <string>

namespace condyn {

/// A registered temporary file. Nodes live as long as the program and are reused.
struct TempNode;

/// Registers `path` for removal on a signal, before the file is created; installs the signal
/// handlers on first use. Throws OutputError when the path is longer than PATH_MAX.
[[nodiscard]] TempNode* register_temp(const std::string& path);
/// The file is gone or in place: a signal no longer removes it. Sets `node` to nullptr.
void release_temp(TempNode*& node);

/// Whether register_temp and keep_rows_on_signal install the handlers above (default true: the
/// command's own process). A host with handlers of its own (the Python module: Ctrl-C raises
/// KeyboardInterrupt) turns them off before any output; its temporary files are then removed by
/// their OutputPlan (on every return and exception), not on a fatal signal.
void use_signal_handlers(bool on);

/// While `on` (a run integrating, whose rows are worth keeping): the first SIGINT, SIGTERM or
/// SIGHUP does not end the process but asks the run to stop (request_stop,
/// dae/interface/interrupt.hpp), which then ends as a failed run and keeps its rows in the partial
/// file; a second one ends the process at once, as without (temporary files removed). Installs the
/// handlers on first use.
void keep_rows_on_signal(bool on);
/// The signal a run was stopped by (0: none). Once the command has written what it kept and
/// released its temporary files, main ends the process by it (end_by_signal).
[[nodiscard]] int stopped_by_signal();
/// Ends the process by `signal`, as its default action does, so the caller sees the signal (a
/// shell's status 128 + N: 130 for SIGINT, 143 for SIGTERM, 129 for SIGHUP).
[[noreturn]] void end_by_signal(int signal);

}  // namespace condyn
