#pragma once
/// The commands of condyn (run, info, compare, check, plot, stress, validate, sweep, modes), one
/// file each (src/cli/*_command.cpp): each adds its sub-command and options to the command line and
/// says what it does once the line is parsed. main.cpp parses, dispatches and turns what a command
/// throws into an exit code (docs/cli.md).

#include <CLI/CLI.hpp>
#include <functional>
#include <string>

namespace condyn {

struct Command {
  /// The sub-command with its options; true (`*options`) once the command line names it.
  CLI::App* options = nullptr;
  /// Carries out the command on its parsed options and returns the exit code (0 done, 1 a run
  /// or check failed, 2 bad input). Bad input may also be thrown (SceneError,
  /// CLI::ValidationError, OutputError, SchemeNotApplicable): main says so and exits 2.
  std::function<int()> act;
  /// The scene the command processes, to name it in errors that arise after parsing ("" for a
  /// command of no one scene).
  std::function<std::string()> scene = [] { return std::string(); };
};

/// Each adds its command to `app`, in the order `condyn --help` lists them.
[[nodiscard]] Command add_run_command(CLI::App& app);
[[nodiscard]] Command add_info_command(CLI::App& app);
[[nodiscard]] Command add_compare_command(CLI::App& app);
[[nodiscard]] Command add_check_command(CLI::App& app);
[[nodiscard]] Command add_plot_command(CLI::App& app);
[[nodiscard]] Command add_stress_command(CLI::App& app);
[[nodiscard]] Command add_validate_command(CLI::App& app);
[[nodiscard]] Command add_sweep_command(CLI::App& app);
[[nodiscard]] Command add_modes_command(CLI::App& app);

}  // namespace condyn
