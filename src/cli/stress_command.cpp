// condyn stress: generated stiff and extreme scenes under every scheme (docs/validation.md).

#include <iostream>
#include <memory>

#include "src/cli/cli_flags.hpp"
#include "src/cli/commands.hpp"
#include "src/output/output_files.hpp"
#include "src/reports/report_format.hpp"
#include "src/reports/stress_output.hpp"
#include "validation/studies/stress.hpp"

namespace condyn {

namespace {

struct StressArgs {
  std::string dir, families;
  bool no_plots = false;
};

int stress(std::string dir, const std::string& families, bool no_plots) {
  StressOptions options;
  if (!families.empty()) {  // not given: every family (given as '', refused by its check)
    for (const auto& f : split_list("--families", families)) options.families.push_back(f);
  }
  try {
    (void)stress_cases(options.families);  // unknown family names are usage errors
  } catch (const std::invalid_argument& e) {
    throw CLI::ValidationError("--families", e.what());
  }
  if (dir.empty()) dir = "condyn-out/stress";
  OutputPlan plan;  // the folder and its files, checked before the runs
  plan_stress_files(plan, dir, stress_cases(options.families));
  plan.check();
  options.progress = [](const std::string& line) { std::cerr << line << std::endl; };
  const StressResult result = run_stress(options);
  print_stress_report(std::cout, result);
  write_stress_files(plan, dir, result);
  std::cout << "\nwrote stress.csv, stress.json, summary.txt and scenes/*.toml to " << dir << "\n";
  if (!no_plots) std::cout << run_plot_script("plot_stress.py", dir) << "\n";
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
  cmd->add_flag("--no-plots", args->no_plots, "do not call the plotting script");
  return {cmd, [args] { return stress(args->dir, args->families, args->no_plots); }};
}

}  // namespace condyn
