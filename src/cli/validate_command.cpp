// condyn validate: the built-in validation suite (docs/validation.md).

#include <iostream>
#include <memory>

#include "src/cli/commands.hpp"
#include "validation/references/suite.hpp"

namespace condyn {

Command add_validate_command(CLI::App& app) {
  auto options = std::make_shared<ValidationOptions>();
  auto* cmd = app.add_subcommand("validate", "run the built-in validation suite");
  cmd->add_flag("--quiet", options->quiet, "print only the summary tables");
  return {cmd, [options] { return run_validation(std::cout, *options) ? 0 : 1; }};
}

}  // namespace condyn
