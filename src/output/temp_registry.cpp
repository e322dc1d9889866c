#include "src/output/temp_registry.hpp"

#include <unistd.h>

#include <atomic>
#include <climits>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <iostream>

#include "dae/interface/interrupt.hpp"
#include "src/output/output_files.hpp"

namespace condyn {

// Temporary files removed on a fatal signal. The handler may run at any point of the program, so
// it reads only a list that is never freed and lock-free atomic flags, and calls only unlink,
// signal and raise (async-signal-safe). Nodes are reused, never deleted.

struct TempNode {
  char path[PATH_MAX] = {};
  std::atomic<bool> live{false};  ///< the handler removes `path`
  bool in_use = false;            ///< owned by an output (main program only)
  TempNode* next = nullptr;
};

namespace {

std::atomic<TempNode*> g_temps{nullptr};
/// keep_rows_on_signal: the first SIGINT, SIGTERM or SIGHUP stops the run instead.
std::atomic<bool> g_keep_rows{false};
/// use_signal_handlers: false in a host that keeps its own handlers.
bool g_use_handlers = true;

extern "C" void remove_temps_and_reraise(int sig) {
  if (sig != SIGPIPE && g_keep_rows.load() && stop_requested() == 0) {
    request_stop(sig);  // the run ends at its next step and keeps its rows
    return;
  }
  for (TempNode* n = g_temps.load(); n != nullptr; n = n->next) {
    if (n->live.load()) ::unlink(n->path);
  }
  // The default action (termination) happens when the handler returns: the signal is blocked
  // while it runs, so the raise stays pending until then.
  std::signal(sig, SIG_DFL);
  std::raise(sig);
}

void install_signal_handlers() {
  static bool installed = false;
  if (installed || !g_use_handlers) return;
  installed = true;
  for (int sig : {SIGTERM, SIGINT, SIGHUP, SIGPIPE}) {
    struct sigaction old {};
    // A signal the caller ignores (nohup, a shell's SIGPIPE policy) stays ignored.
    if (::sigaction(sig, nullptr, &old) == 0 && old.sa_handler == SIG_IGN) continue;
    struct sigaction action {};
    action.sa_handler = remove_temps_and_reraise;
    action.sa_flags = SA_RESTART;  // a deferred stop must not fail a write in progress (EINTR)
    sigfillset(&action.sa_mask);   // one cleanup at a time
    ::sigaction(sig, &action, nullptr);
  }
}

}  // namespace

/// Registers `path` for removal on a signal before the file is created, so no temporary file
/// ever exists unregistered.
TempNode* register_temp(const std::string& path) {
  static_assert(std::atomic<bool>::is_always_lock_free, "the signal handler reads these flags");
  if (path.size() >= PATH_MAX) throw OutputError(path + ": the path is too long");
  install_signal_handlers();
  TempNode* node = nullptr;
  for (TempNode* n = g_temps.load(); n != nullptr && node == nullptr; n = n->next) {
    if (!n->in_use) node = n;
  }
  if (node == nullptr) {
    node = new TempNode;  // NOLINT(cppcoreguidelines-owning-memory): lives as long as the program
    node->next = g_temps.load();
    g_temps.store(node);
  }
  node->in_use = true;
  std::memcpy(node->path, path.c_str(), path.size() + 1);
  node->live.store(true);
  return node;
}

void keep_rows_on_signal(bool on) {
  static_assert(std::atomic<bool>::is_always_lock_free, "the signal handler reads it");
  if (on) install_signal_handlers();
  g_keep_rows.store(on);
}

void use_signal_handlers(bool on) { g_use_handlers = on; }

int stopped_by_signal() { return stop_requested(); }

void end_by_signal(int signal) {
  std::cout.flush();
  std::cerr.flush();
  std::signal(signal, SIG_DFL);
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, signal);
  ::sigprocmask(SIG_UNBLOCK, &set, nullptr);
  std::raise(signal);
  std::_Exit(128 + signal);  // not reached: the default action of these signals ends the process
}

void release_temp(TempNode*& node) {
  if (node == nullptr) return;
  node->live.store(false);
  node->in_use = false;
  node = nullptr;
}

}  // namespace condyn
