// condyn: constrained dynamic systems with constraints as algebraic equations.
// Commands: run, info, validate, compare, check, stress. See README.md and docs/cli.md.

#include <malloc.h>
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <limits>
#include <new>
#include <optional>
#include <sstream>

#include "dae/integrators/ida_integrator.hpp"
#include "dae/run/scheme_memory.hpp"
#include "dae/run/singular_passages.hpp"
#include "dae/run/solve.hpp"
#include "models/assembly/build_model.hpp"
#include "models/scene/scene_parser.hpp"
#include "src/cli/cli_flags.hpp"
#include "src/cli/plot_command.hpp"
#include "src/output/csv_output.hpp"
#include "src/output/escaped_streams.hpp"
#include "src/output/output_files.hpp"
#include "src/output/output_format.hpp"
#include "src/output/temp_registry.hpp"
#include "src/reports/check_report.hpp"
#include "src/reports/compare_output.hpp"
#include "src/reports/info_report.hpp"
#include "src/reports/report_format.hpp"
#include "src/reports/stress_output.hpp"
#include "validation/references/accuracy.hpp"
#include "validation/references/embedded_scenes.hpp"
#include "validation/references/suite.hpp"
#include "validation/studies/compare.hpp"
#include "validation/studies/stress.hpp"
#include "validation/studies/user_checks.hpp"

namespace {

using namespace condyn;

/// The message for a failed run (dae/run/solve_result.hpp) and where the rows computed before the
/// failure went (`partial_note`, from RunOutputs::write_partial).
std::string describe_failure(const SolveResult& result, double t_end,
                             const std::string& partial_note) {
  return condyn::describe_failure(result, t_end) +
         (partial_note.empty() ? std::string() : "\n  " + partial_note);
}

struct RunArgs {
  std::string scene, scheme, constraints, out, steps_out;
  std::optional<double> rtol, atol;
  std::optional<long> max_steps;
  std::optional<double> max_wall_time;
};

/// One progress line on standard error for a long run (the loop calls this only after the first
/// couple of seconds, so short runs print nothing).
void print_progress(const Progress& p) {
  const double span = p.t_end - p.t0;
  const double percent = span > 0.0 ? 100.0 * (p.t - p.t0) / span : 100.0;
  std::ostringstream s;
  s.precision(4);
  s << "progress: t = " << p.t << " of " << p.t_end << " (";
  s.precision(3);
  s << percent << "%), " << p.steps << " steps, " << p.elapsed_seconds << " s";
  std::cerr << s.str() << std::endl;
}

/// info builds a formulation per scheme and drops it. glibc serves each large block by mmap and
/// unmaps it at free, so the next build would fault it in again, zeroed page by page: on large
/// models most of info's time. Served from the heap and kept for reuse instead (figures in
/// docs/benchmarks.md). Runs gain nothing from it: their large blocks live to the end.
void keep_freed_memory() {
  mallopt(M_MMAP_MAX, 0);
  mallopt(M_TRIM_THRESHOLD, std::numeric_limits<int>::max());
}

int run(const RunArgs& args) {
  SceneSpec spec = parse_scene_file(args.scene);
  std::string set_aside;  // SolveSpec::override_scheme's note, if any
  if (!args.scheme.empty())
    set_aside =
        spec.solve.override_scheme(parse_scheme_flag("--scheme", args.scheme), {"--scheme", 0});
  if (!args.constraints.empty())
    spec.solve.treatment = parse_treatment_flag(args.constraints, spec.solve.scheme);
  if (args.rtol) spec.solve.rtol = *args.rtol;  // a loose one is warned of (BuildReport)
  if (args.atol) spec.solve.atol = *args.atol;
  if (args.max_steps) spec.solve.max_steps = *args.max_steps;
  if (args.max_wall_time) spec.solve.max_wall_time = *args.max_wall_time;
  // Every output is checked before the work; with data on standard output, the rest goes to
  // standard error.
  RunOutputs outputs(args.scene, args.out, spec.output, args.steps_out, spec.input_files);
  std::ostream& msg = outputs.messages();
  BuildReport report;
  const Model model = build_model(spec, report);
  if (!set_aside.empty()) report.warnings.insert(report.warnings.begin(), set_aside);
  // [[check]] tables are checked as `condyn check` checks them (their reference files already
  // are, when read), though run does not evaluate them: a bad one is bad input here too.
  if (!spec.checks.empty()) (void)CheckEvaluator(model, spec.checks, args.scene);
  // The chosen scheme's memory against the machine's: refused when even its lower bound cannot
  // fit, warned about now (before a run that may be killed) when its estimate cannot.
  if (const auto warning = check_run_memory(model, spec.solve))
    std::cerr << "warning: " << args.scene << ": " << *warning << "\n";
  release_model_input(spec);
  // The scene's parse tree and its copy of the model are freed in the middle of the heap, where
  // glibc would keep their pages resident to the end: return them (docs/benchmarks.md).
  malloc_trim(0);

  RunHooks hooks = hooks_for(spec.output.quantities);
  hooks.record_steps = !args.steps_out.empty();
  hooks.on_progress = print_progress;
  // Rows go to the result file as they are computed when it is a regular file (nothing of size
  // DOFs x output times is held); a stream gets the whole result at the end. The last row is
  // kept for the published reference of a benchmark (scored at t_end).
  const bool streamed = outputs.can_stream();
  std::optional<TrajectoryRow> last;
  if (streamed) {
    auto sink = outputs.stream_rows(model);
    const bool keep_last = static_cast<bool>(model.reference);
    hooks.on_row = [sink, keep_last, &last](const TrajectoryRow& row) {
      sink(row);
      if (keep_last) last = row;
    };
  }
  // From here a first SIGINT, SIGTERM or SIGHUP stops the run as a failure that keeps its rows
  // (or, had it finished, its whole result); main then ends the process by the signal.
  keep_rows_on_signal(true);
  const SolveResult result = solve(model, spec.solve, hooks);
  const Trajectory& traj = result.trajectory;
  const SolveSummary& summary = result.summary;
  const char* treatment = treatment_name(model, result.scheme, spec.solve);
  const RunAttributes attributes{to_string(result.scheme), spec.solve.rtol, spec.solve.atol,
                                 treatment != nullptr ? treatment : ""};
  if (!result.ok()) {
    // Nothing computed is lost: the rows before the failure go to FILE.partial.csv.
    const std::string partial =
        streamed ? outputs.finish_stream_partial(attributes, traj)
                 : (traj.t.empty() ? "" : outputs.write_partial(model, attributes, traj));
    const bool stopped = result.failure->kind == FailureKind::interrupted;
    std::cerr << "error: " << args.scene << (stopped ? ": run stopped: " : ": integration failed: ")
              << describe_failure(result, spec.solve.t_end, partial) << "\n";
    return 1;
  }
  if (streamed) {
    outputs.finish_stream(attributes, traj);
  } else {
    outputs.write(model, attributes, traj);
  }
  if (!report.initial_projection.empty())
    msg << "initial state: " << report.initial_projection << "\n";
  if (!report.damping.empty()) msg << "damping: " << report.damping << "\n";
  if (!report.massless_dofs.empty()) msg << "massless DOFs: " << report.massless_dofs << "\n";
  for (const auto& r : report.ground_records) msg << "ground motion record: " << r << "\n";
  for (const auto& w : report.warnings) std::cerr << "warning: " << args.scene << ": " << w << "\n";
  for (const auto& w : singular_passage_warnings(summary.singular_passages))
    std::cerr << "warning: " << args.scene << ": " << w << "\n";
  for (const auto& d : report.dropped_constraints)
    msg << "dropped redundant constraint " << d << "\n";
  msg << summary.brief() << "\n";
  if (const double e = relative_energy_error(traj); std::isnan(e)) {
    msg << "energy: not evaluated: an energy leaves the double range (loads or motions too large "
           "for double precision)\n";
  } else if (e >= 0.0) {
    msg << "energy: max |E(t) - E(0)| = " << e << " relative to max(|E(0)|, max kinetic energy)\n";
  }
  const SolveSpec& settings = spec.solve;
  // A streamed run kept its last row (for a model with a published reference): scored alone.
  const std::optional<Trajectory> last_row =
      last ? std::optional<Trajectory>(trajectory_of(*last)) : std::nullopt;
  const Trajectory& scored = last_row ? *last_row : traj;
  if (const auto score = score_against_reference(model, scored, settings.rtol, settings.atol)) {
    msg << "published reference at t = " << score->t << " (" << score->source
        << "): " << score->describe() << " (mescd with rtol " << settings.rtol << ", atol "
        << settings.atol << ")\n";
  }
  msg << "wrote " << traj.t.size() << " rows to " << outputs.csv_name() << "\n";
  if (outputs.has_steps()) {
    msg << "wrote the drift at " << traj.steps.size() << " internal steps to "
        << outputs.steps_name() << "\n";
  }
  for (const auto& stale : outputs.removed_partials()) {
    msg << "removed " << stale << ", the partial result of an earlier failed run\n";
  }
  return 0;
}

int compare(const std::string& scene, std::string dir, const std::string& tolerances,
            const std::string& schemes, bool no_plots, bool allow_failures, bool fail_above,
            CompareOptions options) {
  const std::string stem =
      scene.empty() ? "chapter_5_5_1" : std::filesystem::path(scene).stem().string();
  const SceneSpec spec =
      scene.empty() ? parse_scene_text(embedded_scene(stem).text, "<embedded:" + stem + ">")
                    : parse_scene_file(scene);
  if (dir.empty()) dir = "condyn-out/compare-" + stem;
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
  if (!schemes.empty()) {
    options.schemes.clear();
    for (const auto& s : split_list("--schemes", schemes)) {
      const Scheme scheme = parse_scheme_flag("--schemes", s);
      if (scheme == Scheme::automatic) {
        throw CLI::ValidationError("--schemes", "name schemes, not 'auto'");
      }
      options.schemes.push_back(scheme);
    }
  }
  try {
    options.validate();
  } catch (const std::invalid_argument& e) {
    throw CLI::ValidationError("compare", e.what());
  }
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

/// condyn check: every scene run and its [[check]] tables evaluated; the exit code is the worst
/// of the scenes' (0 all hold, 1 a check or a run failed, 2 bad input).
int check(const std::vector<std::string>& scenes, const std::string& scheme,
          const std::string& junit) {
  SceneCheckOptions options;
  if (!scheme.empty()) {
    options.scheme = parse_scheme_flag("--scheme", scheme);
    options.scheme_where = {"--scheme", 0};
  }
  OutputPlan plan;  // the JUnit report, checked before the runs
  for (const auto& s : scenes) plan.add_input(s);
  std::optional<OutputPlan::Id> report;
  if (!junit.empty()) {
    // Nor may it be a file a scene reads (a matrix, a table, a check's reference): each scene is
    // parsed for their names first (a scene that does not parse is reported by its run below).
    for (const auto& s : scenes) {
      try {
        for (const auto& input : parse_scene_file(s).input_files) plan.add_input(input);
      } catch (const std::exception&) {  // the run below reports it
      }
    }
    report = plan.add_output(junit, "--junit");
  }
  plan.check();
  if (report) (void)output_format(junit, "--junit", {FileFormat::xml});  // its name says XML
  // A report on standard output (`--junit -`) keeps it a well-formed XML stream: the lines go to
  // stderr, as run's do with `--out -`.
  std::ostream& msg = report && plan.to_stdout(*report) ? std::cerr : std::cout;
  std::vector<CheckedScene> checked;
  int code = 0;
  for (const auto& path : scenes) {
    CheckedScene c;
    c.scene = path;
    const auto start = std::chrono::steady_clock::now();
    try {
      c.result = run_scene_checks(path, options);
      c.exit_code = exit_code_of(*c.result);
    } catch (const SceneError& e) {
      c.error = e.what();
      c.exit_code = 2;
    } catch (const SchemeNotApplicable& e) {
      c.error = scene_message(path, e.where(), e.what());
      c.exit_code = 2;
    } catch (const std::exception& e) {
      c.error = path + ": " + e.what();
      c.exit_code = 1;
    }
    c.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    print_checked_scene(msg, c);
    // On disk before the next scene runs: a CI job killed by its time limit keeps the verdicts
    // already reached (stdout to a file or pipe is fully buffered, and a signal discards it).
    msg.flush();
    code = std::max(code, c.exit_code);
    checked.push_back(std::move(c));
  }
  print_check_summary(msg, checked);
  if (report) {
    plan.write(*report, [&checked](std::ostream& out) { out << junit_xml(checked); });
    plan.commit_all();
    msg << "wrote the JUnit report to " << plan.display_name(*report) << "\n";
  }
  return code;
}

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

namespace {

int run_command(int argc, char** argv) {
  CLI::App app{"condyn: constrained dynamic systems, constraints as algebraic equations"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("condyn ") + CONDYN_VERSION);

  RunArgs run_args;
  auto* run_cmd = app.add_subcommand("run", "solve a scene and write its CSV");
  run_cmd->add_option("scene", run_args.scene, "scene file (TOML)")->required();
  run_cmd
      ->add_option("--scheme", run_args.scheme,
                   "scheme (overrides [solve] scheme): " + scheme_names())
      ->check(non_empty_check());
  run_cmd
      ->add_option("--constraints", run_args.constraints,
                   "mixed or multipliers (overrides [solve] constraints): eliminate the "
                   "cheap linear rows under a multiplier scheme, or keep every multiplier")
      ->check(non_empty_check());
  run_cmd->add_option("--rtol", run_args.rtol, "relative tolerance (overrides [solve] rtol)")
      ->check(rtol_check());
  run_cmd->add_option("--atol", run_args.atol, "absolute tolerance (overrides [solve] atol)")
      ->check(atol_check());
  run_cmd
      ->add_option("--max-steps", run_args.max_steps,
                   "step budget of the run (overrides [solve] max_steps); more is a failure")
      ->transform(whole_check(1, std::numeric_limits<int>::max()));
  run_cmd
      ->add_option("--max-wall-time", run_args.max_wall_time,
                   "wall-time budget in seconds (overrides [solve] max_wall_time); more is a "
                   "failure")
      ->check(decimal_range_check(1e-9, 1e12));
  run_cmd
      ->add_option("--out", run_args.out,
                   "result file: .csv or no extension for CSV, .h5, .hdf5 or .hdf for HDF5, - "
                   "for standard output (default: [output] file, else SCENE-STEM.csv here)")
      ->check(file_name_check());
  run_cmd
      ->add_option("--steps-out", run_args.steps_out,
                   "also write the constraint drift at every internal step to this CSV (.csv or "
                   "no extension)")
      ->check(file_name_check());

  std::string info_scene, info_scheme, info_constraints;
  bool info_all_constraints = false;
  auto* info_cmd = app.add_subcommand("info", "classify the constraints and size the model");
  info_cmd->add_option("scene", info_scene, "scene file (TOML)")->required();
  info_cmd->add_option("--scheme", info_scheme, "scheme to report on (default: the scene's)")
      ->check(non_empty_check());
  info_cmd
      ->add_option("--constraints", info_constraints,
                   "mixed or multipliers (default: the scene's [solve] constraints)")
      ->check(non_empty_check());
  info_cmd->add_flag("--all-constraints", info_all_constraints,
                     "list every constraint (default: above 60, the first 40 and a count per "
                     "class)");

  std::string compare_scene, compare_dir, compare_tolerances, compare_schemes;
  bool compare_no_plots = false;
  CompareOptions compare_options;
  auto* compare_cmd = app.add_subcommand(
      "compare", "every scheme across a tolerance sweep: errors, drift, cost, plots");
  compare_cmd
      ->add_option("scene", compare_scene,
                   "scene file (default: the chapter truss, §5.5.1, built in)")
      ->check(CLI::Validator(
          [](std::string& text) {
            return is_blank(text) ? std::string(
                                        "is empty: name a scene file, or leave it out for the "
                                        "built-in truss")
                                  : std::string();
          },
          "FILE"));
  compare_cmd
      ->add_option("--out-dir", compare_dir,
                   "output folder (default: condyn-out/compare-SCENE-STEM)")
      ->check(non_empty_check());
  compare_cmd
      ->add_option("--tolerances", compare_tolerances,
                   "comma-separated rtol values (default 1e-3,1e-4,...,1e-10)")
      ->check(non_empty_check());
  compare_cmd
      ->add_option("--schemes", compare_schemes, "comma-separated schemes (default: all of them)")
      ->check(non_empty_check());
  compare_cmd
      ->add_option("--repeats", compare_options.repeats,
                   "runs per point for the wall time (default 3)")
      ->transform(whole_check(1, CompareOptions::kMaxRepeats));
  compare_cmd
      ->add_option("--drift-rtol", compare_options.drift_rtol,
                   "tolerance of the drift, history and Baumgarte-study runs (default 1e-6)")
      ->check(decimal_range_check(CompareOptions::kMinDriftRtol, CompareOptions::kMaxDriftRtol));
  compare_cmd->add_flag("--no-plots", compare_no_plots, "do not call the plotting script");
  bool compare_allow_failures = false;
  compare_cmd->add_flag("--allow-failures", compare_allow_failures,
                        "exit 0 even when runs failed (they are reported either way)");
  compare_cmd
      ->add_option("--fail-above", compare_options.mark_factor,
                   "exit 1 when a run's worst error exceeds FACTOR times its rtol (penalty: its "
                   "weight's target); such runs are marked OVER either way, above 1e4 by default")
      ->check(decimal_range_check(1.0, 1e15));
  compare_cmd->add_flag("--baumgarte-study", compare_options.baumgarte_study,
                        "also run the Baumgarte gain study (16 runs at --drift-rtol)");
  compare_cmd
      ->add_option("--max-steps", compare_options.max_steps,
                   "step budget of each run (not the reference); a run beyond it is a failed run")
      ->transform(whole_check(1, std::numeric_limits<int>::max()));
  compare_cmd
      ->add_option("--max-wall-time", compare_options.max_wall_time,
                   "wall-time budget in seconds of each run (not the reference)")
      ->check(decimal_range_check(1e-9, 1e12));

  std::vector<std::string> check_scenes;
  std::string check_scheme, check_junit;
  auto* check_cmd = app.add_subcommand(
      "check", "run scenes and evaluate their [[check]] tables: exit 0 only if every check holds");
  check_cmd->add_option("scenes", check_scenes, "scene files (TOML) with [[check]] tables")
      ->required();
  check_cmd
      ->add_option("--scheme", check_scheme,
                   "scheme for every scene (overrides [solve] scheme): " + scheme_names())
      ->check(non_empty_check());
  check_cmd
      ->add_option("--junit", check_junit,
                   "also write a JUnit XML report to this file (.xml or no extension)")
      ->check(non_empty_check());

  PlotArgs plot_args;
  auto* plot_cmd = app.add_subcommand(
      "plot", "figures of one run's CSV or HDF5: displacements, drift, energy (docs/plots.md)");
  plot_cmd->add_option("result", plot_args.result, "the CSV or HDF5 file that condyn run wrote")
      ->required();
  plot_cmd
      ->add_option("--dofs", plot_args.dofs,
                   "DOFs to draw, names or globs, comma-separated (default: the four with the "
                   "largest peaks)")
      ->check(non_empty_check());
  plot_cmd
      ->add_option("--out-dir", plot_args.out_dir,
                   "folder for the figures (default: beside RESULT)")
      ->check(non_empty_check());
  plot_cmd
      ->add_option("--format", plot_args.formats,
                   "comma-separated: png, pdf, svg (default: png,pdf)")
      ->check(non_empty_check());

  std::string stress_dir, stress_families_list;
  bool stress_no_plots = false;
  auto* stress_cmd = app.add_subcommand(
      "stress", "stiff and extreme generated scenes under every scheme: where each holds, breaks");
  stress_cmd->add_option("--out-dir", stress_dir, "output folder (default: condyn-out/stress)")
      ->check(non_empty_check());
  stress_cmd
      ->add_option("--families", stress_families_list,
                   "comma-separated families (default: all): stiffness, mass_ratio, "
                   "penalty_weight, baumgarte_gains, long_horizon, redundancy, dead_point, "
                   "high_frequency")
      ->check(non_empty_check());
  stress_cmd->add_flag("--no-plots", stress_no_plots, "do not call the plotting script");

  ValidationOptions validate_options;
  auto* validate_cmd = app.add_subcommand("validate", "run the built-in validation suite");
  validate_cmd->add_flag("--quiet", validate_options.quiet, "print only the summary tables");

  // An option before the command that condyn does not have (-x, --versio): CLI11 would say
  // only "A subcommand is required".
  if (argc > 1 && argv[1][0] == '-') {
    const std::string first = argv[1];
    if (first != "-h" && first != "--help" && first != "--version") {
      std::cerr << "error: unknown option '" << first
                << "' (condyn takes --help and --version before a command; condyn --help lists "
                   "the commands)\n";
      return 2;
    }
  }
  // A first word that names no command: CLI11 would say only "A subcommand is required".
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

  // The scene being processed, to name it in errors that arise after parsing.
  const std::string scene = *run_cmd ? run_args.scene : *info_cmd ? info_scene : compare_scene;
  try {
    if (*run_cmd) return run(run_args);
    if (*info_cmd) {
      keep_freed_memory();
      SceneSpec spec = parse_scene_file(info_scene);
      std::string set_aside;
      if (!info_scheme.empty())
        set_aside =
            spec.solve.override_scheme(parse_scheme_flag("--scheme", info_scheme), {"--scheme", 0});
      if (!info_constraints.empty()) {  // info sizes every scheme unless --scheme names one
        spec.solve.treatment = parse_treatment_flag(
            info_constraints, info_scheme.empty() ? Scheme::automatic : spec.solve.scheme);
      }
      BuildReport report;
      const Model model = build_model(spec, report);
      if (!set_aside.empty()) report.warnings.insert(report.warnings.begin(), set_aside);
      // A bad [[check]] is bad input here as in run and check.
      if (!spec.checks.empty()) (void)CheckEvaluator(model, spec.checks, info_scene);
      release_model_input(spec);
      print_info(std::cout, model, report, spec.solve, info_all_constraints);
      return 0;
    }
    if (*validate_cmd) return run_validation(std::cout, validate_options) ? 0 : 1;
    if (*stress_cmd) return stress(stress_dir, stress_families_list, stress_no_plots);
    if (*compare_cmd) {
      return compare(compare_scene, compare_dir, compare_tolerances, compare_schemes,
                     compare_no_plots, compare_allow_failures,
                     compare_cmd->count("--fail-above") > 0, compare_options);
    }
    if (*check_cmd) return check(check_scenes, check_scheme, check_junit);
    if (*plot_cmd) return plot_result(plot_args);
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
