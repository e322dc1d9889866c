#include "validation/studies/compare.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "dae/formulations/baumgarte_gains.hpp"
#include "dae/formulations/penalty_ode.hpp"
#include "dae/run/solve.hpp"
#include "models/assembly/build_model.hpp"
#include "models/scene/toml_access.hpp"
#include "validation/references/accuracy.hpp"
#include "validation/references/exact_solution.hpp"
#include "validation/references/scientific.hpp"
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

/// The scene's run settings with the scheme and tolerances of one run of the sweep.
SolveSpec settings_of(const SolveSpec& scene, Scheme scheme, double rtol, double atol) {
  SolveSpec s = scene;
  s.scheme = scheme;
  s.rtol = rtol;
  s.atol = atol;
  return s;
}

/// Hooks that report a long run's progress through options.progress, each line led by `what`
/// ("[3/8] projection rtol 1.0e-06"): a sweep whose run takes minutes says which one it is.
RunHooks progress_hooks(const CompareOptions& options, const std::string& what) {
  RunHooks hooks;
  if (!options.progress) return hooks;
  hooks.on_progress = [&options, what](const Progress& p) {
    std::ostringstream s;
    s.precision(4);
    s << what << ": running, t = " << p.t << " of " << p.t_end << ", " << p.steps << " steps, ";
    s.precision(3);
    s << p.elapsed_seconds << " s";
    options.progress(s.str());
  };
  return hooks;
}

/// The same within the per-run budget of the options (compare --max-steps, --max-wall-time).
SolveSpec budgeted(SolveSpec s, const CompareOptions& options) {
  if (options.max_steps > 0) s.max_steps = options.max_steps;
  if (options.max_wall_time > 0.0) s.max_wall_time = options.max_wall_time;
  return s;
}

/// The first of elimination, GGL, projection and index1 that applies and reaches t_end at `rtol`
/// (atol rtol/100), without the scene's budget ([solve] max_steps, max_wall_time) as without
/// compare's: a reference at rtol/100 takes more steps than the runs it scores (the scene's 450
/// steps failed all three fallbacks of a nonlinear scene). Each in turn,
/// the next when one fails or does not apply: GGL at tight tolerances can ask its derived μ and λ
/// tolerances for roundoff (the pendulum at rtol 1e-13 failed, where projection and index1 run
/// it). Nothing when all fail; `failures` then says why, scheme by scheme.
std::optional<std::pair<Scheme, Trajectory>> first_run(const Model& model,
                                                       const SolveSpec& settings,
                                                       const CompareOptions& options, double rtol,
                                                       const std::string& what,
                                                       std::string& failures) {
  for (Scheme scheme : {Scheme::elimination, Scheme::ggl, Scheme::projection, Scheme::index1}) {
    if (scheme_refusal(model, scheme)) continue;
    SolveSpec unbounded = settings_of(settings, scheme, rtol, rtol * 1e-2);
    unbounded.max_steps = 0;
    unbounded.max_wall_time = 0.0;
    try {
      const SolveResult run = solve(
          model, unbounded,
          progress_hooks(options, what + " " + to_string(scheme) + " rtol " + scientific(rtol, 1)));
      return std::make_pair(scheme, succeeded(run).trajectory);
    } catch (const std::exception& why) {
      failures +=
          (failures.empty() ? "" : "; ") + std::string(to_string(scheme)) + ": " + why.what();
    }
  }
  return std::nullopt;
}

/// The best reference available: a built-in benchmark's published state at t_end, else the exact
/// modal solution, else a tight run (first_run at 1/100 of the smallest tolerance). Trajectories
/// are at settings.output_times().
Trajectory reference(const Model& model, const SolveSpec& settings, const CompareOptions& options,
                     CompareResult& out) {
  if (model.reference) {
    if (const auto published = model.reference(settings.t_end)) {
      out.reference_kind = "published";
      out.reference_description = published->source;
      out.trusted_digits_u = published->digits_u;
      out.trusted_digits_v = published->digits_v;
      Trajectory ref;
      ref.t = {published->t};
      ref.u = published->u;
      ref.v = published->v;
      return ref;
    }
  }
  try {
    Trajectory exact = exact_trajectory(model, settings.output_times());
    out.reference_kind = "exact";
    out.reference_description = "exact modal solution (closed form)";
    return exact;
  } catch (const ExactSolutionUnavailable& e) {
    const double tight = std::max(
        1e-13, *std::min_element(options.tolerances.begin(), options.tolerances.end()) / 100.0);
    std::string failures;
    if (auto run = first_run(model, settings, options, tight, "reference", failures)) {
      out.reference_kind = to_string(run->first);
      out.reference_description = std::string(to_string(run->first)) + " at rtol " +
                                  scientific(tight, 1) + " (no exact solution: " + e.what() +
                                  (failures.empty() ? "" : "; failed: " + failures) + ")";
      return std::move(run->second);
    }
    // Without a reference no run can be scored: say which runs failed and what to change.
    throw NoReferenceError(
        "no reference solution: there is no exact one (" + std::string(e.what()) +
        "), and the tight reference runs failed at rtol " + scientific(tight, 1) +
        " (1/100 of the smallest --tolerances value): " + failures +
        "; a looser smallest tolerance, or a t_end the scene reaches, gives compare a "
        "reference (`condyn run` with --scheme ggl --rtol " +
        scientific(tight, 1) + " --atol " + scientific(tight * 1e-2, 1) + " shows the same)");
  }
}

/// Penalty's error target without rtol: kPenaltyAccuracy at the default weight, shrinking like
/// 1/w under a weight of the scene's; 0 where penalty does not apply or has no constraints.
double penalty_error_target(const Model& model, const SolveSpec& settings) {
  if (model.constraint_count() == 0 || scheme_refusal(model, Scheme::penalty)) return 0.0;
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

/// The rows of `dense` at `times`, each of them among its times (the output grid refined by
/// kScaleSamples, whose every kScaleSamples-th time is an output time bit for bit).
Trajectory rows_at(const Trajectory& dense, const std::vector<double>& times) {
  std::vector<Eigen::Index> cols;
  std::size_t j = 0;
  for (double t : times) {
    while (j < dense.t.size() && dense.t[j] < t) ++j;
    if (j == dense.t.size() || dense.t[j] != t) {
      throw std::logic_error("compare: output time " + scientific(t, 16) +
                             " is not among the reference's times");
    }
    cols.push_back(static_cast<Eigen::Index>(j));
  }
  const auto pick = [&cols](const Eigen::MatrixXd& x) {
    return x.cols() == 0 ? x : Eigen::MatrixXd(x(Eigen::all, cols));
  };
  const auto pick_vector = [&cols](const Eigen::VectorXd& x) {
    return x.size() == 0 ? x : Eigen::VectorXd(x(cols));
  };
  Trajectory out;
  out.t = times;
  out.u = pick(dense.u);
  out.v = pick(dense.v);
  out.reaction = pick(dense.reaction);
  out.acceleration = pick(dense.acceleration);
  out.multiplier = pick(dense.multiplier);
  out.drift_position = pick_vector(dense.drift_position);
  out.drift_velocity = pick_vector(dense.drift_velocity);
  out.energy = pick_vector(dense.energy);
  out.kinetic = pick_vector(dense.kinetic);
  return out;
}

/// The scene's settings with kScaleSamples output rows per output interval.
SolveSpec refined(SolveSpec settings) {
  settings.output_step /= kScaleSamples;  // a power of two: the output times stay among its own
  return settings;
}

/// The error scales (accuracy.hpp) of a run against a published state, which has no trajectory:
/// from a run of first_run at drift_rtol on the refined grid (two digits of a scale need no
/// tight run), or, when all fail, nothing (each run's own rows then give its scales).
std::optional<ErrorScales> published_scales(const Model& model, const SolveSpec& settings,
                                            const CompareOptions& options, std::string& source) {
  std::string failures;
  if (auto run =
          first_run(model, refined(settings), options, options.drift_rtol, "scales", failures)) {
    source = std::string("a ") + to_string(run->first) + " run at rtol " +
             scientific(options.drift_rtol, 1);
    return error_scales(run->second);
  }
  source = "each run's own output rows (the scale runs failed: " + failures + ")";
  return std::nullopt;
}

}  // namespace

WallStatistics wall_statistics(std::vector<double> walls) {
  if (walls.empty()) throw std::invalid_argument("wall_statistics: no timings");
  std::sort(walls.begin(), walls.end());
  const std::size_t n = walls.size();
  const double median = n % 2 ? walls[n / 2] : 0.5 * (walls[n / 2 - 1] + walls[n / 2]);
  return {median, walls.front(), walls.back()};
}

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
  for (int d = 0; d < base.dofs(); ++d) {  // A holds the linearization of nonlinear models
    if (base.A.col(d).nonZeros() > 0) {
      out.constrained_dofs.emplace_back(base.dof_names[static_cast<std::size_t>(d)], d);
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
  const double ratio =
      options.atol_ratio > 0.0 ? options.atol_ratio : spec.solve.atol / spec.solve.rtol;
  // The reference on a grid kScaleSamples times finer than the output rows, for scales of the
  // whole run; the runs are scored at the output rows.
  const Trajectory dense = reference(base, refined(spec.solve), options, out);
  const bool published = out.reference_kind == "published";
  std::optional<ErrorScales> scales;
  if (published) {
    scales = published_scales(base, spec.solve, options, out.scale_source);
  } else {
    scales = error_scales(dense);
    out.scale_source = "the reference";
  }
  if (scales) out.error_scales = *scales;
  const Trajectory ref = published ? dense : rows_at(dense, spec.solve.output_times());
  if (!published) {
    out.reference_t = ref.t;
    out.reference_multiplier = ref.multiplier;
  }
  const double penalty_target = penalty_error_target(base, spec.solve);

  const std::size_t total = schemes.size() * options.tolerances.size();
  std::size_t done = 0;
  for (Scheme scheme : schemes) {
    for (double rtol : options.tolerances) {
      RunRecord r;
      r.scheme = scheme;
      r.rtol = rtol;
      r.atol = rtol * ratio;
      const SolveSpec settings = budgeted(settings_of(spec.solve, scheme, r.rtol, r.atol), options);
      std::vector<double> walls;
      const RunHooks hooks =
          progress_hooks(options, "[" + std::to_string(done + 1) + "/" + std::to_string(total) +
                                      "] " + to_string(scheme) + " rtol " + scientific(rtol, 1));
      try {
        for (int k = 0; k < options.repeats; ++k) {
          const SolveResult result = solve(base, settings, hooks);
          const Trajectory& run = succeeded(result).trajectory;
          const SolveSummary& summary = result.summary;
          walls.push_back(summary.wall_seconds);
          if (k > 0) continue;  // repeats only time the run: the numbers are deterministic
          if (published) {
            const Eigen::Index last = run.u.cols() - 1;
            // Relative to the reference's largest entry, or, where the reference is zero (the
            // period-2 pendulum is at rest at t = 2N), to the scale of the whole run; without
            // one, to the run's own largest entry over its rows.
            const auto rel = [](const Eigen::VectorXd& a, const Eigen::MatrixXd& b, double whole,
                                const Eigen::MatrixXd& history) {
              double scale = std::max(b.cwiseAbs().maxCoeff(), whole);
              if (!(scale > 0.0)) scale = history.cwiseAbs().maxCoeff();
              const double diff = (a - b.col(0)).cwiseAbs().maxCoeff();
              return scale > 0.0 ? diff / scale : diff;
            };
            r.error_u = rel(run.u.col(last), ref.u, out.error_scales.displacement, run.u);
            r.error_v = rel(run.v.col(last), ref.v, out.error_scales.velocity, run.v);
            r.error_reaction = std::numeric_limits<double>::quiet_NaN();  // λ: not scored
            const auto score = score_against_reference(base, run, r.rtol, r.atol);
            r.mescd_u = score->digits_u;
            if (score->digits_v) r.mescd_v = *score->digits_v;
          } else {
            const TrajectoryError err = relative_error(run, ref, out.error_scales);
            r.error_u = err.displacement;
            r.error_v = err.velocity;
            r.error_reaction = err.reaction;
          }
          if (const double e = relative_energy_error(run, out.error_scales.energy); e >= 0.0) {
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
        r.repeats = static_cast<int>(walls.size());
        const WallStatistics stats = wall_statistics(walls);
        r.wall_median = stats.median;
        r.wall_min = stats.min;
        r.wall_max = stats.max;
        r.ok = std::isfinite(r.error_u) && std::isfinite(r.error_v) &&
               (published || std::isfinite(r.error_reaction));
        if (!r.ok) r.message = "non-finite error against the reference";
        r.error_target = scheme == Scheme::penalty ? std::max(rtol, penalty_target) : rtol;
        if (r.ok) mark_against_target(r, options.mark_factor);
      } catch (const std::exception& e) {
        r.ok = false;
        r.message = e.what();
      }
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

  // Drift logs and histories at one tolerance.
  const SolveSpec drift_settings = budgeted(
      settings_of(spec.solve, Scheme::automatic, options.drift_rtol, options.drift_rtol * ratio),
      options);
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
  assess_drift_growths(out.histories);

  // Baumgarte study: the default gains scaled over a grid. Asked for, it runs whatever
  // --schemes lists (it wrote a header-only file when baumgarte was not among them).
  if (options.baumgarte_study && base.constraint_count() == 0 && options.progress) {
    options.progress("Baumgarte study: not run (the scene has no constraints to stabilise)");
  }
  if (options.baumgarte_study && base.constraint_count() > 0) {
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
            p.error_u = relative_error(result.trajectory, ref, out.error_scales).displacement;
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
