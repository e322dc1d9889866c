// `condyn sweep SWEEP.toml [--workers N] [--scheduler ADDRESS] [--out DIR]` (docs/sweep.md): a
// study of many runs on Dask. The sweep is the Python module's (python/condyn/sweep_run.py: Dask
// is a Python library), so this command replaces itself with `/usr/bin/python3 -m
// condyn.sweep_cli ...`, the module found in the folder it was built into (CONDYN_PYTHON_DIR).
// exec, not a child: Ctrl-C and SIGTERM reach the sweep itself, and its exit code is condyn's.

#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "src/cli/commands.hpp"

#ifndef CONDYN_PYTHON_DIR
#define CONDYN_PYTHON_DIR ""
#endif

namespace condyn {

namespace {

struct SweepArgs {
  std::string file, workers, scheduler, out;
};

/// Runs the module's sweep in place of this process; returns only when that cannot be done (1,
/// said on standard error). The Python side checks the arguments (exit 2 for bad ones).
int exec_sweep(const SweepArgs& args) {
  const std::string module_dir = CONDYN_PYTHON_DIR;
  if (module_dir.empty()) {
    std::cerr << "error: condyn sweep runs on the Python module, and this condyn was built "
                 "without it (it needs pybind11-dev and python3-dev: apt-get install them and "
                 "build again)\n";
    return 1;
  }
  if (!std::filesystem::exists(std::filesystem::path(module_dir) / "condyn" / "sweep_cli.py")) {
    std::cerr << "error: condyn sweep needs the Python module built beside this condyn, in "
              << module_dir << ", which has no condyn/sweep_cli.py (build the target "
              << "condyn_python_package)\n";
    return 1;
  }
  const char* old_path = std::getenv("PYTHONPATH");
  const std::string path =
      module_dir + (old_path != nullptr && *old_path != '\0' ? ":" + std::string(old_path) : "");
  if (setenv("PYTHONPATH", path.c_str(), 1) != 0) {
    std::cerr << "error: condyn sweep: cannot set PYTHONPATH: " << std::strerror(errno) << "\n";
    return 1;
  }
  std::vector<std::string> words = {"/usr/bin/python3", "-m", "condyn.sweep_cli", args.file};
  for (const auto& [flag, value] :
       {std::pair<const char*, const std::string&>{"--workers", args.workers},
        {"--scheduler", args.scheduler},
        {"--out", args.out}}) {
    if (!value.empty()) words.insert(words.end(), {flag, value});
  }
  std::vector<char*> argv;
  argv.reserve(words.size() + 1);
  for (auto& w : words) argv.push_back(w.data());
  argv.push_back(nullptr);
  std::cout.flush();
  std::cerr.flush();
  execv(argv[0], argv.data());
  std::cerr << "error: condyn sweep needs Debian's python3 (/usr/bin/python3: "
            << std::strerror(errno) << "), python3-dask and python3-distributed: apt-get "
            << "install them\n";
  return 1;
}

}  // namespace

Command add_sweep_command(CLI::App& app) {
  auto args = std::make_shared<SweepArgs>();
  auto* cmd = app.add_subcommand(
      "sweep",
      "runs a study of many runs (the product of a sweep file's axes) on Dask and "
      "writes DIR/results.csv (docs/sweep.md)");
  cmd->add_option("sweep", args->file, "the sweep file (TOML)")->required();
  cmd->add_option("--workers", args->workers,
                  "worker processes of the local Dask cluster (default: one per core)");
  cmd->add_option("--scheduler", args->scheduler,
                  "the address of a running Dask scheduler (tcp://host:8786) whose workers run "
                  "the sweep");
  cmd->add_option("--out", args->out,
                  "the results folder (default: the sweep file's name without extension)");
  return {cmd, [args] { return exec_sweep(*args); }, [args] { return args->file; }};
}

}  // namespace condyn
