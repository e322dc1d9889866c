// condyn: constrained dynamic systems with constraints as algebraic equations.
// Commands: run, info, validate, compare, check, stress, plot, sweep (one file each,
// src/cli/commands.hpp). See README.md and docs/cli.md. Here: the command line parsed, the command
// dispatched, and what it throws turned into an exit code (0 done, 1 a run failed, 2 bad input).

#include <CLI/CLI.hpp>
#include <cerrno>
#include <cstring>
#include <iostream>
#include <new>
#include <optional>
#include <vector>

#include "dae/interface/scheme_not_applicable.hpp"
#include "models/scene/scene_parser.hpp"
#include "src/cli/commands.hpp"
#include "src/output/escaped_streams.hpp"
#include "src/output/output_files.hpp"
#include "src/output/temp_registry.hpp"

namespace {

using namespace condyn;

/// An option before the command that condyn does not have (-x, --versio), or a first word that
/// names no command: CLI11 would say only "A subcommand is required". Says what is wrong and
/// returns 2; nothing when the first word is fine.
std::optional<int> refuse_first_word(CLI::App& app, int argc, char** argv) {
  if (argc > 1 && argv[1][0] == '-') {
    const std::string first = argv[1];
    if (first != "-h" && first != "--help" && first != "--version") {
      std::cerr << "error: unknown option '" << first
                << "' (condyn takes --help and --version before a command; condyn --help lists "
                   "the commands)\n";
      return 2;
    }
  }
  if (argc > 1 && argv[1][0] != '-') {
    std::string names;
    bool known = false;
    for (const auto* sub : app.get_subcommands({})) {
      names += (names.empty() ? "" : ", ") + sub->get_name();
      known = known || sub->get_name() == argv[1];
    }
    if (!known) {
      std::cerr << "error: '" << argv[1] << "' is not a command (the commands: " << names
                << "; condyn --help says what each does)\n";
      return 2;
    }
  }
  return std::nullopt;
}

/// Parses the command line into the commands' options: nothing when a command is to run, else
/// the exit code (0 after --help or --version, 2 for a usage error, said on standard error).
std::optional<int> parse(CLI::App& app, int argc, char** argv) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::ArgumentMismatch& e) {
    // CLI11 says "--rtol: At Most 1 required but received 2" of an option given twice.
    const std::string what = e.what();
    const std::string said = ": At Most 1 required but received ";
    if (const auto at = what.find(said); at != std::string::npos) {
      std::cerr << "error: " << what.substr(0, at) << " is given " << what.substr(at + said.size())
                << " times; give it once\n";
      return 2;
    }
    return app.exit(e) == 0 ? 0 : 2;
  } catch (const CLI::ParseError& e) {
    // --help prints and succeeds; every other command-line error is a usage error: exit 2, as the
    // contract says (CLI11's own codes are 100+).
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;
  }
  return std::nullopt;
}

/// Carries out the parsed command: its exit code, or, for what it throws, the message on standard
/// error and 2 (bad input) or 1 (a failure).
int act(const Command& command) {
  // The scene being processed, to name it in errors that arise after parsing.
  const std::string scene = command.scene();
  try {
    return command.act();
  } catch (const SceneError& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 2;
  } catch (const CLI::ValidationError& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 2;
  } catch (const OutputError& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 2;
  } catch (const SchemeNotApplicable& e) {
    std::cerr << "error: " << scene_message(scene, e.where(), e.what()) << "\n";
    return 2;
  } catch (const std::bad_alloc&) {
    // What() is "std::bad_alloc": say what it means (a memory limit, ulimit -v, or a model
    // beyond the machine's memory).
    std::cerr << "error: " << (scene.empty() ? "" : scene + ": ")
              << "out of memory: the process could not allocate what this run needs (the "
                 "machine's memory, or a limit such as ulimit -v)\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "error: " << (scene.empty() ? "" : scene + ": ") << e.what() << "\n";
    return 1;
  }
}

int run_command(int argc, char** argv) {
  CLI::App app{"condyn: constrained dynamic systems, constraints as algebraic equations"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("condyn ") + CONDYN_VERSION);
  const std::vector<Command> commands = {
      add_run_command(app),      add_info_command(app),  add_compare_command(app),
      add_check_command(app),    add_plot_command(app),  add_stress_command(app),
      add_validate_command(app), add_sweep_command(app), add_modes_command(app)};
  if (const auto code = refuse_first_word(app, argc, argv)) return *code;
  if (const auto code = parse(app, argc, argv)) return *code;
  for (const auto& command : commands) {
    if (*command.options) return act(command);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  condyn::escape_standard_streams();
  const int code = run_command(argc, argv);
  // What a command printed to standard output (info's report, compare's table) is its product:
  // a write that failed (a full disk, /dev/full, a closed pipe) is a failure, not exit 0.
  const bool written = static_cast<bool>(std::cout << std::flush);
  if (!written)
    std::cerr << "error: writing standard output failed (" << std::strerror(errno) << ")\n";
  // A run stopped by a signal kept its rows; every temporary file is gone: the process now ends
  // by that signal, as it would have at once, so a shell sees 130 (SIGINT) or 143 (SIGTERM).
  condyn::keep_rows_on_signal(false);
  if (const int signal = condyn::stopped_by_signal(); signal != 0) condyn::end_by_signal(signal);
  if (!written) return code == 0 ? 1 : code;
  return code;
}
