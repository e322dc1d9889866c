// condyn compare: a scene under every scheme across a tolerance sweep (docs/cli.md,
// validation/compare-output.md).

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <limits>
#include <memory>
#include <optional>

#include "models/scene/scene_parser.hpp"
#include "src/cli/cli_flags.hpp"
#include "src/cli/commands.hpp"
#include "src/output/output_files.hpp"
#include "src/reports/compare_output.hpp"
#include "validation/references/embedded_scenes.hpp"
#include "validation/studies/compare.hpp"

namespace condyn {

namespace {

struct CompareArgs {
  std::string scene, dir, tolerances, schemes;
  std::optional<double> step;  ///< --step: the Newmark family's fixed step
  bool no_plots = false, allow_failures = false;
  CompareOptions options;
};

/// The options with the sweep's tolerances and schemes the flags list, checked.
void apply_lists(CompareOptions& options, const std::string& tolerances,
                 const std::string& schemes) {
  if (!tolerances.empty()) {
    options.tolerances.clear();
    for (const auto& t : split_list("--tolerances", tolerances)) {
      const double rtol = parse_rtol_flag("--tolerances", t);
      const auto& listed = options.tolerances;
      if (std::find(listed.begin(), listed.end(), rtol) != listed.end()) {
        throw CLI::ValidationError("--tolerances", "'" + t + "' is listed twice in '" + tolerances +
                                                       "' (the same number)");
      }
      options.tolerances.push_back(rtol);
    }
  }
  if (!schemes.empty()) options.schemes = parse_scheme_list("--schemes", schemes);
  try {
    options.validate();
  } catch (const std::invalid_argument& e) {
    throw CLI::ValidationError("compare", e.what());
  }
}

/// The exit code of a finished comparison: 1 when runs failed (unless --allow-failures) or, with
/// --fail-above, missed their target by more than its factor; each said on standard error.
int verdict(const CompareResult& result, const CompareOptions& options, const std::string& dir,
            bool allow_failures, bool fail_above) {
  if (const int failed = result.failed_runs(); failed > 0) {
    // The sweep's runs are rows of runs.csv; the drift-history runs are in runs.json.
    const int history =
        failed - static_cast<int>(std::count_if(result.runs.begin(), result.runs.end(),
                                                [](const auto& r) { return !r.ok; }));
    std::cerr << (allow_failures ? "warning: " : "error: ") << failed << " run"
              << (failed == 1 ? "" : "s") << " of the comparison failed (see FAILED above and "
              << dir << "/runs.csv"
              << (history > 0 ? ", and for the " + std::to_string(history) + " drift-history run" +
                                    (history == 1 ? "" : "s") + " " + dir + "/runs.json"
                              : std::string())
              << ")"
              << (allow_failures ? "; tolerated by --allow-failures"
                                 : "; --allow-failures tolerates them")
              << "\n";
    if (!allow_failures) return 1;
  }
  // Runs far beyond their tolerance fail only when asked (--fail-above): they are marked anyway.
  if (const int over = result.over_tolerance_runs(); over > 0 && fail_above) {
    std::cerr << "error: " << over << " run" << (over == 1 ? "" : "s")
              << " of the comparison missed the target by more than --fail-above "
              << options.mark_factor << " (marked OVER above and in " << dir << "/runs.csv)\n";
    return 1;
  }
  return 0;
}

int compare(const std::string& scene, std::string dir, const std::string& tolerances,
            const std::string& schemes, std::optional<double> step, bool no_plots,
            bool allow_failures, bool fail_above, CompareOptions options) {
  const std::string stem =
      scene.empty() ? "chapter_5_5_1" : std::filesystem::path(scene).stem().string();
  SceneSpec spec = scene.empty()
                       ? parse_scene_text(embedded_scene(stem).text, "<embedded:" + stem + ">")
                       : parse_scene_file(scene);
  if (step) {
    spec.solve.step = *step;
    check_settings(spec.file, spec.solve);
  }
  if (dir.empty()) dir = "condyn-out/compare-" + stem;
  apply_lists(options, tolerances, schemes);
  OutputPlan plan;  // the folder and its files, checked before the runs
  if (!scene.empty()) plan.add_input(scene);
  for (const auto& input : spec.input_files) plan.add_input(input);  // a table, a matrix
  plan_compare_files(plan, dir, options.schemes, options.baumgarte_study);
  plan.check();
  options.progress = [](const std::string& line) { std::cerr << line << std::endl; };
  const CompareResult result = run_compare(spec, options);
  for (const auto& w : result.warnings) std::cerr << "warning: " << spec.file << ": " << w << "\n";
  print_compare_table(std::cout, result);
  write_compare_files(plan, dir, result);
  std::cout << "\nwrote runs.csv, runs.json, drift_*.csv, history_*.csv, "
            << (options.baumgarte_study ? "baumgarte_study.csv " : "") << "and summary.txt to "
            << dir << (options.baumgarte_study ? "" : " (no Baumgarte study: --baumgarte-study)")
            << "\n";
  if (!no_plots) std::cout << draw_compare_plots(dir) << "\n";
  return verdict(result, options, dir, allow_failures, fail_above);
}

/// The sub-command and its options, read into `args`.
CLI::App* add_compare_options(CLI::App& app, CompareArgs& args) {
  auto* cmd = app.add_subcommand(
      "compare", "every scheme across a tolerance sweep: errors, drift, cost, plots");
  cmd->add_option("scene", args.scene, "scene file (default: the chapter truss, §5.5.1, built in)")
      ->check(CLI::Validator(
          [](std::string& text) {
            return is_blank(text) ? std::string(
                                        "is empty: name a scene file, or leave it out for the "
                                        "built-in truss")
                                  : std::string();
          },
          "FILE"));
  cmd->add_option("--out-dir", args.dir, "output folder (default: condyn-out/compare-SCENE-STEM)")
      ->check(non_empty_check());
  cmd->add_option("--tolerances", args.tolerances,
                  "comma-separated rtol values (default 1e-3,1e-4,...,1e-10)")
      ->check(non_empty_check());
  cmd->add_option("--schemes", args.schemes, "comma-separated schemes (default: all of them)")
      ->check(non_empty_check());
  add_step_option(cmd, args.step);
  cmd->add_option("--repeats", args.options.repeats, "runs per point for the wall time (default 3)")
      ->transform(whole_check(1, CompareOptions::kMaxRepeats));
  cmd->add_option("--drift-rtol", args.options.drift_rtol,
                  "tolerance of the drift, history and Baumgarte-study runs (default 1e-6)")
      ->check(decimal_range_check(CompareOptions::kMinDriftRtol, CompareOptions::kMaxDriftRtol));
  cmd->add_flag("--no-plots", args.no_plots, "do not call the plotting script");
  cmd->add_flag("--allow-failures", args.allow_failures,
                "exit 0 even when runs failed (they are reported either way)");
  cmd->add_option("--fail-above", args.options.mark_factor,
                  "exit 1 when a run's worst error exceeds FACTOR times its rtol (penalty: its "
                  "weight's target); such runs are marked OVER either way, above 1e4 by default")
      ->check(decimal_range_check(1.0, 1e15));
  cmd->add_flag("--baumgarte-study", args.options.baumgarte_study,
                "also run the Baumgarte gain study (16 runs at --drift-rtol)");
  cmd->add_option("--max-steps", args.options.max_steps,
                  "step budget of each run (not the reference); a run beyond it is a failed run")
      ->transform(whole_check(1, std::numeric_limits<int>::max()));
  cmd->add_option("--max-wall-time", args.options.max_wall_time,
                  "wall-time budget in seconds of each run (not the reference)")
      ->check(decimal_range_check(1e-9, 1e12));
  return cmd;
}

}  // namespace

Command add_compare_command(CLI::App& app) {
  auto args = std::make_shared<CompareArgs>();
  auto* cmd = add_compare_options(app, *args);
  return {cmd,
          [args, cmd] {
            return compare(args->scene, args->dir, args->tolerances, args->schemes, args->step,
                           args->no_plots, args->allow_failures, cmd->count("--fail-above") > 0,
                           args->options);
          },
          [args] { return args->scene; }};
}

}  // namespace condyn
