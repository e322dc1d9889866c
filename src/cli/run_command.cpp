// condyn run: solve a scene and write its result (docs/cli.md).

#include <malloc.h>
#include <cmath>
#include <iostream>
#include <limits>
#include <memory>
#include <optional>
#include <sstream>

#include "dae/run/scheme_memory.hpp"
#include "dae/run/singular_passages.hpp"
#include "dae/run/solve.hpp"
#include "models/assembly/build_model.hpp"
#include "models/scene/scene_parser.hpp"
#include "src/cli/cli_flags.hpp"
#include "src/cli/commands.hpp"
#include "src/output/csv_output.hpp"
#include "src/output/temp_registry.hpp"
#include "validation/references/accuracy.hpp"
#include "validation/studies/user_checks.hpp"

namespace condyn {

namespace {

struct RunArgs {
  std::string scene, scheme, constraints, out, steps_out;
  std::optional<double> rtol, atol;
  std::optional<double> step;  ///< --step: the fixed-step schemes' step
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

/// The scene with the flags' overrides of its [solve] table; `set_aside` gets
/// SolveSpec::override_scheme's note, if any.
SceneSpec scene_with_flags(const RunArgs& args, std::string& set_aside) {
  SceneSpec spec = parse_scene_file(args.scene);
  if (!args.scheme.empty())
    set_aside =
        spec.solve.override_scheme(parse_scheme_flag("--scheme", args.scheme), {"--scheme", 0});
  if (!args.constraints.empty())
    spec.solve.treatment = parse_treatment_flag(args.constraints, spec.solve.scheme);
  if (args.rtol) spec.solve.rtol = *args.rtol;  // a loose one is warned of (BuildReport)
  if (args.atol) spec.solve.atol = *args.atol;
  if (args.max_steps) spec.solve.max_steps = *args.max_steps;
  if (args.max_wall_time) spec.solve.max_wall_time = *args.max_wall_time;
  if (args.step) spec.solve.step = *args.step;
  check_settings(args.scene, spec.solve);
  return spec;
}

/// What a finished run prints after writing its result: the build's notes and warnings, the
/// run's summary and energy balance, its score against a published reference (`last`: the last
/// row a streamed run kept for it) and the files written. `said_before`: the plan's warnings,
/// printed before the run, left out of the summary line.
void print_run_report(std::ostream& msg, const RunArgs& args, const RunOutputs& outputs,
                      const Model& model, const BuildReport& report, const SolveSpec& settings,
                      const SolveResult& result, const std::optional<TrajectoryRow>& last,
                      const std::vector<RunNote>& said_before) {
  const Trajectory& traj = result.trajectory;
  const SolveSummary& summary = result.summary;
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
  msg << summary.brief(said_before) << "\n";
  if (const double e = relative_energy_error(traj); std::isnan(e)) {
    msg << "energy: not evaluated: an energy leaves the double range (loads or motions too large "
           "for double precision)\n";
  } else if (e >= 0.0) {
    msg << "energy: max |E(t) - E(0)| = " << e
        << " relative to max(|E(0)|, max kinetic energy, |f(0)| times the model's size)\n";
  }
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
}

int run(const RunArgs& args) {
  std::string set_aside;  // SolveSpec::override_scheme's note, if any
  SceneSpec spec = scene_with_flags(args, set_aside);
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
  // The run's plan: every decision made once (dae/run/run_plan.hpp). Its scheme's memory against
  // the machine's: refused when even its lower bound cannot fit, warned about now (before a run
  // that may be killed) when its estimate cannot. The sizes are freed with `decisions`.
  RunPlan run_plan;
  {
    SchemeDecisions decisions(model);
    run_plan = plan(model, spec.solve, decisions);
    if (const auto warning = check_run_memory(run_plan, decisions))
      std::cerr << "warning: " << args.scene << ": " << *warning << "\n";
  }
  // What the plan warns of before the run (rattle's step beyond its stability limit).
  std::vector<RunNote> said_before;
  for (const RunNote& note : run_plan.notes) {
    if (note.kind != RunNote::Kind::warning) continue;
    std::cerr << "warning: " << args.scene << ": " << note.text << "\n";
    said_before.push_back(note);
  }
  release_model_input(spec);
  // The scene's parse tree and its copy of the model are freed in the middle of the heap, where
  // glibc would keep their pages resident to the end: return them (docs/benchmarks.md).
  malloc_trim(0);

  // What the rows must carry: the [output] quantities and what the [[derived]] columns read.
  RunHooks hooks = hooks_for(with_derived_quantities(spec.output.quantities, model.derived));
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
  const SolveResult result = execute(run_plan, hooks);
  // Nothing computed is lost: a failed run's rows go to the partial file (NAME.partial.EXT).
  const std::string partial = outputs.keep(model, run_attributes(model, spec.solve, result.scheme),
                                           result.trajectory, result.ok());
  if (!result.ok()) {
    const bool stopped = result.failure->kind == FailureKind::interrupted;
    std::cerr << "error: " << args.scene << (stopped ? ": run stopped: " : ": integration failed: ")
              << failure_message(result, spec.solve.t_end, partial) << "\n";
    return 1;
  }
  print_run_report(msg, args, outputs, model, report, spec.solve, result, last, said_before);
  return 0;
}

}  // namespace

Command add_run_command(CLI::App& app) {
  auto args = std::make_shared<RunArgs>();
  auto* cmd = app.add_subcommand("run", "solve a scene and write its CSV");
  cmd->add_option("scene", args->scene, "scene file (TOML)")->required();
  cmd->add_option("--scheme", args->scheme, "scheme (overrides [solve] scheme): " + scheme_names())
      ->check(non_empty_check());
  cmd->add_option("--constraints", args->constraints,
                  "mixed or multipliers (overrides [solve] constraints): eliminate the "
                  "cheap linear rows under a multiplier scheme, or keep every multiplier")
      ->check(non_empty_check());
  cmd->add_option("--rtol", args->rtol, "relative tolerance (overrides [solve] rtol)")
      ->check(rtol_check());
  cmd->add_option("--atol", args->atol, "absolute tolerance (overrides [solve] atol)")
      ->check(atol_check());
  add_step_option(cmd, args->step);
  cmd->add_option("--max-steps", args->max_steps,
                  "step budget of the run (overrides [solve] max_steps); more is a failure")
      ->transform(whole_check(1, std::numeric_limits<int>::max()));
  cmd->add_option("--max-wall-time", args->max_wall_time,
                  "wall-time budget in seconds (overrides [solve] max_wall_time); more is a "
                  "failure")
      ->check(decimal_range_check(1e-9, 1e12));
  cmd->add_option("--out", args->out,
                  "result file: .csv or no extension for CSV, .h5, .hdf5 or .hdf for HDF5, - "
                  "for standard output (default: [output] file, else SCENE-STEM.csv here)")
      ->check(file_name_check());
  cmd->add_option("--steps-out", args->steps_out,
                  "also write the constraint drift at every internal step to this CSV (.csv or "
                  "no extension)")
      ->check(file_name_check());
  return {cmd, [args] { return run(*args); }, [args] { return args->scene; }};
}

}  // namespace condyn
