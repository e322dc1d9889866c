#include "validation/studies/compare.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "dae/formulations/baumgarte_gains.hpp"
#include "dae/formulations/penalty_ode.hpp"
#include "dae/run/mapped_rows.hpp"
#include "dae/run/solve.hpp"
#include "models/assembly/build_model.hpp"
#include "models/scene/toml_access.hpp"
#include "validation/references/accuracy.hpp"
#include "validation/references/scientific.hpp"
#include "validation/studies/compare_reference.hpp"
#include "validation/studies/user_checks.hpp"

namespace condyn {

void CompareOptions::validate() const {
  auto bad = [](const std::string& what) { throw std::invalid_argument(what); };
  const auto got = [](double v) { return " (got " + TomlAccess::fmt(v) + ")"; };
  if (tolerances.empty()) bad("tolerances: none given");
  for (std::size_t k = 0; k < tolerances.size(); ++k) {
    const double t = tolerances[k];
    if (!(t >= kMinRtol && t < 1.0)) {
      bad("tolerances: each lies in [" + TomlAccess::fmt(kMinRtol) + ", 1)" + got(t));
    }
    for (std::size_t j = 0; j < k; ++j) {
      if (tolerances[j] == t) bad("tolerances: " + TomlAccess::fmt(t) + " is listed twice");
    }
  }
  if (repeats < 1 || repeats > kMaxRepeats) {
    bad("repeats: lies in [1, " + std::to_string(kMaxRepeats) + "] (got " +
        std::to_string(repeats) + ")");
  }
  if (schemes.empty()) bad("schemes: none given");
  if (!(drift_rtol >= kMinDriftRtol && drift_rtol <= kMaxDriftRtol)) {
    bad("drift_rtol: lies in [" + TomlAccess::fmt(kMinDriftRtol) + ", " +
        TomlAccess::fmt(kMaxDriftRtol) + "]" + got(drift_rtol));
  }
  if (!(atol_ratio >= 0.0)) bad("atol ratio: must be >= 0" + got(atol_ratio));
  if (max_steps < 0 || max_steps > std::numeric_limits<int>::max()) {
    bad("max_steps: lies in [0, 2147483647], 0 for no budget (got " + std::to_string(max_steps) +
        ")");
  }
  if (!(mark_factor >= 1.0 && mark_factor <= 1e15)) {
    bad("mark factor: lies in [1, 1e15]" + got(mark_factor));
  }
  if (!(max_wall_time == 0.0 || (max_wall_time >= kMinWallTime && max_wall_time <= kMaxWallTime))) {
    bad("max_wall_time: 0 for no budget, else in [" + TomlAccess::fmt(kMinWallTime) + ", " +
        TomlAccess::fmt(kMaxWallTime) + "] seconds" + got(max_wall_time));
  }
}

namespace {

/// Run settings `s` within the per-run budget of the options (compare --max-steps,
/// --max-wall-time).
SolveSpec budgeted(SolveSpec s, const CompareOptions& options) {
  if (options.max_steps > 0) s.max_steps = options.max_steps;
  if (options.max_wall_time > 0.0) s.max_wall_time = options.max_wall_time;
  return s;
}

/// Penalty's error target without rtol: kPenaltyAccuracy at the default weight, shrinking like
/// 1/w under a weight of the scene's; 0 where penalty does not apply or has no constraints, and on
/// a nonlinear model, where penalty is the augmented Lagrangian (its multipliers iterated to
/// convergence: its error follows rtol, and it has no weight w).
double penalty_error_target(const Model& model, const SolveSpec& settings) {
  if (model.constraint_count() == 0 || model.is_nonlinear() ||
      scheme_refusal(model, Scheme::penalty)) {
    return 0.0;
  }
  SolveSpec defaults = settings;
  defaults.penalty_weight.reset();
  return kPenaltyAccuracy * penalty_weights(model, defaults).position /
         penalty_weights(model, settings).position;
}

/// Sets r.error_ratio and r.over_tolerance from its errors and error_target.
void mark_against_target(RunRecord& r, double factor) {
  double worst = std::max(r.error_u, r.error_v);
  if (std::isfinite(r.error_reaction)) worst = std::max(worst, r.error_reaction);
  r.error_ratio = worst / r.error_target;
  r.over_tolerance = r.error_ratio > factor;
}

/// The drift growth of every history that ran, under one rule: the motion's oscillations are
/// counted once for all of them, as the fewest of their runs count (half the sign changes of the
/// fastest-reversing velocity over the steps): the motion is one, and a scheme whose velocities
/// chatter about zero adds sign changes, never removes them (GGL counted 10 or more where the
/// others counted 3.5 and 8, and was fitted where they were not).
void assess_drift_growths(std::vector<SchemeHistory>& histories) {
  std::optional<double> oscillations;
  for (const auto& h : histories) {
    if (!h.ok || h.trajectory.steps.empty()) continue;
    const double count = static_cast<double>(h.trajectory.steps.back().velocity_reversals) / 2.0;
    oscillations = std::min(oscillations.value_or(count), count);
  }
  for (auto& h : histories) {
    if (!h.ok) continue;
    // Roundoff in the drift: a few dozen ulps of the largest displacement (1 when all are 0).
    const double u_scale = h.trajectory.u.size() > 0 ? h.trajectory.u.cwiseAbs().maxCoeff() : 0.0;
    const double roundoff =
        64.0 * std::numeric_limits<double>::epsilon() * (u_scale > 0.0 ? u_scale : 1.0);
    h.growth = assess_drift_growth(h.trajectory.steps, roundoff, oscillations);
  }
}

}  // namespace

WallStatistics wall_statistics(std::vector<double> walls) {
  if (walls.empty()) throw std::invalid_argument("wall_statistics: no timings");
  std::sort(walls.begin(), walls.end());
  const std::size_t n = walls.size();
  const double median = n % 2 ? walls[n / 2] : 0.5 * (walls[n / 2 - 1] + walls[n / 2]);
  return {median, walls.front(), walls.back()};
}

namespace {

/// The model's facts the output names (constrained DOFs, constraint names) and the requested
/// schemes that can treat it; the others go to out.skipped with the reason. Throws
/// SchemeNotApplicable when none can.
std::vector<Scheme> applicable_schemes(const Model& base, const CompareOptions& options,
                                       CompareResult& out) {
  if (base.outputs) {  // a mechanism's histories show its joints' reactions
    const auto& names = base.outputs->names(Quantity::reaction);
    for (std::size_t k = 0; k < names.size(); ++k) {
      out.reaction_columns.emplace_back(names[k], static_cast<int>(k));
    }
  }
  for (int d = 0; d < base.dofs() && !base.outputs; ++d) {  // A: nonlinear models' linearization
    if (base.A.col(d).nonZeros() > 0) {
      out.reaction_columns.emplace_back("reaction_" + base.dof_names[static_cast<std::size_t>(d)],
                                        d);
    }
  }
  for (const auto& c : base.constraints) out.constraint_names.push_back(c.name);
  std::vector<Scheme> schemes;
  std::string refusals;
  for (Scheme scheme : options.schemes) {
    if (auto why = scheme_refusal(base, scheme)) {
      out.skipped.emplace_back(scheme, *why);
      refusals += std::string("\n  ") + to_string(scheme) + ": " + *why;
    } else {
      schemes.push_back(scheme);
    }
  }
  if (schemes.empty()) {
    throw SchemeNotApplicable("no requested scheme applies to this scene:" + refusals);
  }
  return schemes;
}

/// What every run of the sweep is measured against.
struct Yardstick {
  const Model& model;
  const Trajectory& ref;  ///< at the output rows, or the published state
  bool published;
  const ErrorScales& scales;
};

/// Relative to the reference's largest entry, or, where the reference is zero (the period-2
/// pendulum is at rest at t = 2N), to the scale of the whole run; without one, to the run's own
/// largest entry over its rows.
double relative_to_published(const Eigen::VectorXd& a, const Eigen::MatrixXd& b, double whole,
                             const Eigen::MatrixXd& history) {
  double scale = std::max(b.cwiseAbs().maxCoeff(), whole);
  if (!(scale > 0.0)) scale = history.cwiseAbs().maxCoeff();
  const double diff = (a - b.col(0)).cwiseAbs().maxCoeff();
  return scale > 0.0 ? diff / scale : diff;
}

/// A run's errors against the reference in the columns its results show: a mechanism's output
/// map's (poses, velocities, joint reactions: the reference is mapped alike), else per DOF.
TrajectoryError shown_error(const Model& model, const Trajectory& run, const Trajectory& ref,
                            const ErrorScales& scales) {
  if (!model.outputs) return relative_error(run, ref, scales);
  return relative_error(mapped_trajectory(model, run, {}, true), ref, scales);
}

/// The errors, drift and cost of one successful run of the sweep, into `r`.
void score_run(RunRecord& r, const Trajectory& run, const SolveSummary& summary,
               const Yardstick& against) {
  if (against.published) {
    const Eigen::Index last = run.u.cols() - 1;
    r.error_u =
        relative_to_published(run.u.col(last), against.ref.u, against.scales.displacement, run.u);
    r.error_v =
        relative_to_published(run.v.col(last), against.ref.v, against.scales.velocity, run.v);
    r.error_reaction = std::numeric_limits<double>::quiet_NaN();  // λ: not scored
    const auto score = score_against_reference(against.model, run, r.rtol, r.atol);
    r.mescd_u = score->digits_u;
    if (score->digits_v) r.mescd_v = *score->digits_v;
  } else {
    const TrajectoryError err = shown_error(against.model, run, against.ref, against.scales);
    r.error_u = err.displacement;
    r.error_v = err.velocity;
    r.error_reaction = err.reaction;
  }
  if (const double e = relative_energy_error(run, against.scales.energy); e >= 0.0) {
    r.energy_error = e;
  }
  r.max_drift_position = summary.max_drift_position;
  r.max_drift_velocity = summary.max_drift_velocity;
  r.final_drift_position = run.drift_position[run.drift_position.size() - 1];
  r.final_drift_velocity = run.drift_velocity[run.drift_velocity.size() - 1];
  r.steps = summary.steps;
  r.residual_evals = summary.residual_evals;
  r.jacobian_evals = summary.jacobian_evals;
  r.newton_failures = summary.newton_failures;
  r.error_test_failures = summary.error_test_failures;
}

/// One point of the sweep, `r` (its scheme, rtol and atol set): run options.repeats times for the
/// wall time, scored at its first run and marked against its target (`penalty_target` under
/// penalty). A failure is recorded in `r`, not thrown.
void run_point(RunRecord& r, const SolveSpec& scene, const CompareOptions& options,
               const RunHooks& hooks, const Yardstick& against, double penalty_target) {
  const SolveSpec settings = budgeted(settings_of(scene, r.scheme, r.rtol, r.atol), options);
  std::vector<double> walls;
  try {
    for (int k = 0; k < options.repeats; ++k) {
      const SolveResult result = solve(against.model, settings, hooks);
      const Trajectory& run = succeeded(result).trajectory;
      walls.push_back(result.summary.wall_seconds);
      if (k > 0) continue;  // repeats only time the run: the numbers are deterministic
      score_run(r, run, result.summary, against);
    }
    r.repeats = static_cast<int>(walls.size());
    const WallStatistics stats = wall_statistics(walls);
    r.wall_median = stats.median;
    r.wall_min = stats.min;
    r.wall_max = stats.max;
    r.ok = std::isfinite(r.error_u) && std::isfinite(r.error_v) &&
           (against.published || std::isfinite(r.error_reaction));
    if (!r.ok) r.message = "non-finite error against the reference";
    r.error_target = r.scheme == Scheme::penalty ? std::max(r.rtol, penalty_target) : r.rtol;
    // Under a fixed step the Newmark family's error is the step's, O(h²), and rtol only its
    // Newton tolerance: no target to mark it against.
    if (fixed_step(r.scheme) && settings.step) r.error_target = std::nan("");
    if (r.ok) mark_against_target(r, options.mark_factor);
  } catch (const std::exception& e) {
    r.ok = false;
    r.message = e.what();
  }
}

/// The tolerance sweep: every scheme at every tolerance (atol = rtol · `ratio`), into out.runs.
void run_sweep(const SolveSpec& scene, const std::vector<Scheme>& schemes, double ratio,
               const CompareOptions& options, const Yardstick& against, CompareResult& out) {
  const double penalty_target = penalty_error_target(against.model, scene);
  const std::size_t total = schemes.size() * options.tolerances.size();
  std::size_t done = 0;
  for (Scheme scheme : schemes) {
    for (double rtol : options.tolerances) {
      RunRecord r;
      r.scheme = scheme;
      r.rtol = rtol;
      r.atol = rtol * ratio;
      const RunHooks hooks =
          progress_hooks(options, "[" + std::to_string(done + 1) + "/" + std::to_string(total) +
                                      "] " + to_string(scheme) + " rtol " + scientific(rtol, 1));
      run_point(r, scene, options, hooks, against, penalty_target);
      ++done;
      if (options.progress) {
        std::ostringstream s;
        s << "[" << done << "/" << total << "] " << to_string(scheme) << " rtol "
          << scientific(rtol, 1) << ": "
          << (r.ok ? "error " + scientific(std::max({r.error_u, r.error_v, r.error_reaction}), 1) +
                         ", " + std::to_string(r.steps) + " steps"
                   : "FAILED: " + r.message);
        options.progress(s.str());
      }
      out.runs.push_back(std::move(r));
    }
  }
}

/// Drift logs and histories of every scheme at one tolerance (`drift_settings`), into
/// out.histories; a failed run keeps its rows and steps.
void run_histories(const Model& base, const std::vector<Scheme>& schemes,
                   const SolveSpec& drift_settings, CompareResult& out) {
  for (Scheme scheme : schemes) {
    SchemeHistory h;
    h.scheme = scheme;
    try {
      RunHooks hooks;
      hooks.record_steps = true;
      SolveSpec settings = drift_settings;
      settings.scheme = scheme;
      const SolveResult run = solve(base, settings, hooks);
      h.trajectory = run.trajectory;  // a failed run's rows and steps too (the drift figure)
      if (!run.ok()) {
        h.message = describe_failure(run, settings.t_end);
        h.t_reached = run.failure->t_reached;
        out.histories.push_back(std::move(h));
        continue;
      }
      h.t_reached = settings.t_end;
      h.ok = true;
    } catch (const std::exception& e) {
      h.message = e.what();
    }
    out.histories.push_back(std::move(h));
  }
  assess_drift_growths(out.histories);  // in the coordinates integrated (their roundoff)
  // A mechanism's histories in its output map's columns (the reactions written per joint).
  for (auto& h : out.histories)
    h.trajectory = mapped_trajectory(base, std::move(h.trajectory), {}, true);
}

/// Baumgarte study: the default gains scaled over a grid, at `drift_settings`, into
/// out.baumgarte_study. Asked for, it runs whatever --schemes lists (it wrote a header-only file
/// when baumgarte was not among them).
void run_baumgarte_study(const Model& base, const SolveSpec& drift_settings,
                         const CompareOptions& options, const Trajectory& ref, CompareResult& out) {
  if (options.baumgarte_study && base.constraint_count() == 0 && options.progress) {
    options.progress("Baumgarte study: not run (the scene has no constraints to stabilise)");
  }
  if (!options.baumgarte_study || base.constraint_count() == 0) return;
  const BaumgarteGains defaults = baumgarte_gains(base, drift_settings);
  for (double fa : options.baumgarte_factors) {
    for (double fb : options.baumgarte_factors) {
      BaumgarteStudyPoint p;
      p.alpha = defaults.alpha * fa;
      p.beta = defaults.beta * fb;
      p.is_default = fa == 1.0 && fb == 1.0;
      SolveSpec s = drift_settings;
      s.scheme = Scheme::baumgarte;
      s.baumgarte_alpha = p.alpha;
      s.baumgarte_beta = p.beta;
      try {
        const SolveResult result = solve(base, s);
        const SolveSummary& summary = succeeded(result).summary;
        if (out.reference_kind != "published") {
          p.error_u = shown_error(base, result.trajectory, ref, out.error_scales).displacement;
        }
        p.ok = true;
        p.max_drift_position = summary.max_drift_position;
        p.max_drift_velocity = summary.max_drift_velocity;
        p.steps = summary.steps;
        p.wall = summary.wall_seconds;
      } catch (const std::exception& e) {
        p.message = e.what();
      }
      out.baumgarte_study.push_back(std::move(p));
    }
  }
  if (options.progress) {
    options.progress("Baumgarte study: " + std::to_string(out.baumgarte_study.size()) +
                     " runs at rtol " + scientific(options.drift_rtol, 1));
  }
}

}  // namespace

CompareResult run_compare(const SceneSpec& spec, const CompareOptions& options) {
  options.validate();
  CompareResult out;
  out.options = options;
  out.scene_name = spec.name.empty() ? spec.file : spec.name;
  BuildReport report;
  const Model base = build_model(spec, report);  // once: the runs differ only in their settings
  // The scene's rtol is not compare's (its tolerances are): a warning of a loose one is not
  // about this comparison.
  for (auto& w : report.warnings) {
    if (w.rfind("rtol ", 0) != 0) out.warnings.push_back(std::move(w));
  }
  // A bad [[check]] is bad input here as in run and check.
  if (!spec.checks.empty()) (void)CheckEvaluator(base, spec.checks, spec.file);
  const std::vector<Scheme> schemes = applicable_schemes(base, options, out);
  const double ratio =
      options.atol_ratio > 0.0 ? options.atol_ratio : spec.solve.atol / spec.solve.rtol;
  // The runs are scored at the output rows.
  const Trajectory ref = reference_at_rows(base, spec.solve, options, out);
  const Yardstick against{base, ref, out.reference_kind == "published", out.error_scales};
  run_sweep(spec.solve, schemes, ratio, options, against, out);
  const SolveSpec drift_settings = budgeted(
      settings_of(spec.solve, Scheme::automatic, options.drift_rtol, options.drift_rtol * ratio),
      options);
  run_histories(base, schemes, drift_settings, out);
  run_baumgarte_study(base, drift_settings, options, ref, out);
  return out;
}

int CompareResult::over_tolerance_runs() const {
  return static_cast<int>(
      std::count_if(runs.begin(), runs.end(), [](const auto& r) { return r.over_tolerance; }));
}

int CompareResult::failed_runs() const {
  int n = 0;
  for (const auto& r : runs) n += r.ok ? 0 : 1;
  for (const auto& h : histories) n += h.ok ? 0 : 1;
  return n;
}

}  // namespace condyn
