// condyn info: classify a scene's constraints and size its model under each scheme (docs/cli.md).

#include <malloc.h>
#include <iostream>
#include <limits>
#include <memory>
#include <optional>

#include "models/assembly/build_model.hpp"
#include "models/scene/scene_parser.hpp"
#include "src/cli/cli_flags.hpp"
#include "src/cli/commands.hpp"
#include "src/reports/info_report.hpp"
#include "validation/studies/user_checks.hpp"

namespace condyn {

namespace {

struct InfoArgs {
  std::string scene, scheme, constraints;
  std::optional<double> step;  ///< --step: the Newmark family's fixed step
  bool all_constraints = false;
};

/// info builds a formulation per scheme and drops it. glibc serves each large block by mmap and
/// unmaps it at free, so the next build would fault it in again, zeroed page by page: on large
/// models most of info's time. Served from the heap and kept for reuse instead (figures in
/// docs/benchmarks.md). Runs gain nothing from it: their large blocks live to the end.
void keep_freed_memory() {
  mallopt(M_MMAP_MAX, 0);
  mallopt(M_TRIM_THRESHOLD, std::numeric_limits<int>::max());
}

int info(const InfoArgs& args) {
  keep_freed_memory();
  SceneSpec spec = parse_scene_file(args.scene);
  std::string set_aside;
  if (!args.scheme.empty())
    set_aside =
        spec.solve.override_scheme(parse_scheme_flag("--scheme", args.scheme), {"--scheme", 0});
  if (!args.constraints.empty()) {  // info sizes every scheme unless --scheme names one
    spec.solve.treatment = parse_treatment_flag(
        args.constraints, args.scheme.empty() ? Scheme::automatic : spec.solve.scheme);
  }
  if (args.step) spec.solve.step = *args.step;
  check_settings(args.scene, spec.solve);
  BuildReport report;
  const Model model = build_model(spec, report);
  if (!set_aside.empty()) report.warnings.insert(report.warnings.begin(), set_aside);
  // A bad [[check]] is bad input here as in run and check.
  if (!spec.checks.empty()) (void)CheckEvaluator(model, spec.checks, args.scene);
  release_model_input(spec);
  print_info(std::cout, model, report, spec.solve, args.all_constraints);
  return 0;
}

}  // namespace

Command add_info_command(CLI::App& app) {
  auto args = std::make_shared<InfoArgs>();
  auto* cmd = app.add_subcommand("info", "classify the constraints and size the model");
  cmd->add_option("scene", args->scene, "scene file (TOML)")->required();
  cmd->add_option("--scheme", args->scheme, "scheme to report on (default: the scene's)")
      ->check(non_empty_check());
  add_step_option(cmd, args->step);
  cmd->add_option("--constraints", args->constraints,
                  "mixed or multipliers (default: the scene's [solve] constraints)")
      ->check(non_empty_check());
  cmd->add_flag("--all-constraints", args->all_constraints,
                "list every constraint (default: above 60, the first 40 and a count per "
                "class)");
  return {cmd, [args] { return info(*args); }, [args] { return args->scene; }};
}

}  // namespace condyn
