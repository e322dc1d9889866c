// condyn stress: generated stiff and extreme scenes under every scheme (docs/validation.md).

#include <algorithm>
#include <iostream>
#include <iterator>
#include <memory>
#include <string>
#include <vector>

#include "src/cli/cli_flags.hpp"
#include "src/cli/commands.hpp"
#include "src/output/output_files.hpp"
#include "src/reports/report_format.hpp"
#include "src/reports/stress_output.hpp"
#include "validation/studies/stress.hpp"

namespace condyn {

namespace {

struct StressArgs {
  std::string dir, families, schemes;
  bool no_plots = false;
};

/// --schemes: among the schemes stress runs (kSchemes; the fixed-step family is not one).
std::vector<Scheme> stress_schemes(const std::string& schemes) {
  std::vector<Scheme> out = parse_scheme_list("--schemes", schemes);
  for (Scheme s : out) {
    if (std::find(std::begin(kSchemes), std::end(kSchemes), s) == std::end(kSchemes)) {
      std::string names;
      for (Scheme k : kSchemes) names += std::string(names.empty() ? "" : ", ") + to_string(k);
      throw CLI::ValidationError("--schemes", "stress does not run '" + std::string(to_string(s)) +
                                                  "' (it runs " + names + ")");
    }
  }
  return out;
}

int stress(const StressArgs& args) {
  StressOptions options;
  if (!args.families.empty()) {  // not given: every family (given as '', refused by its check)
    for (const auto& f : split_list("--families", args.families)) options.families.push_back(f);
  }
  if (!args.schemes.empty()) options.schemes = stress_schemes(args.schemes);
  std::vector<StressCase> cases;
  try {
    cases = stress_cases(options.families);  // unknown family names are usage errors
  } catch (const std::invalid_argument& e) {
    throw CLI::ValidationError("--families", e.what());
  }
  if (!options.schemes.empty() &&
      std::none_of(cases.begin(), cases.end(),
                   [&](const StressCase& c) { return !stress_runs(c, options.schemes).empty(); })) {
    throw CLI::ValidationError(
        "--schemes", "no case of the families asked for runs under '" + args.schemes + "'");
  }
  const std::string dir = args.dir.empty() ? "condyn-out/stress" : args.dir;
  OutputPlan plan;  // the folder and its files, checked before the runs
  plan_stress_files(plan, dir, cases);
  plan.check();
  options.progress = [](const std::string& line) { std::cerr << line << std::endl; };
  const StressResult result = run_stress(options);
  print_stress_report(std::cout, result);
  write_stress_files(plan, dir, result);
  std::cout << "\nwrote stress.csv, stress.json, summary.txt and scenes/*.toml to " << dir << "\n";
  if (!args.no_plots) std::cout << run_plot_script("plot_stress.py", dir) << "\n";
  return 0;
}

}  // namespace

Command add_stress_command(CLI::App& app) {
  auto args = std::make_shared<StressArgs>();
  auto* cmd = app.add_subcommand(
      "stress", "stiff and extreme generated scenes under every scheme: where each holds, breaks");
  cmd->add_option("--out-dir", args->dir, "output folder (default: condyn-out/stress)")
      ->check(non_empty_check());
  cmd->add_option("--families", args->families,
                  "comma-separated families (default: all): stiffness, mass_ratio, "
                  "penalty_weight, baumgarte_gains, long_horizon, redundancy, dead_point, "
                  "high_frequency")
      ->check(non_empty_check());
  cmd->add_option("--schemes", args->schemes,
                  "comma-separated schemes (default: every scheme each case lists)")
      ->check(non_empty_check());
  cmd->add_flag("--no-plots", args->no_plots, "do not call the plotting script");
  return {cmd, [args] { return stress(*args); }};
}

}  // namespace condyn
