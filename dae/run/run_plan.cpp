#include "dae/run/run_plan.hpp"

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <stdexcept>
#include <string>
#include <utility>

#include "dae/formulations/augmented_lagrangian_ode.hpp"
#include "dae/formulations/partitioned_ode.hpp"
#include "dae/formulations/rattle_stability.hpp"
#include "dae/formulations/scheme_run.hpp"
#include "dae/run/failure_advice.hpp"
#include "dae/run/observed_run.hpp"
#include "dae/run/singular_passages.hpp"
#include "models/core/number_cell.hpp"

namespace condyn {

namespace {

/// `scheme`: the one that runs (elimination starts from
/// AbsoluteTolerances::first_step_from_motion).
IntegratorSettings settings_from(const Model& model, const SolveSpec& settings,
                                 const AbsoluteTolerances& atol, Scheme scheme) {
  IntegratorSettings o;
  o.rtol = settings.rtol;
  o.atol = atol.displacement;
  o.atol_velocity = atol.velocity;
  o.atol_multiplier = atol.multiplier;
  o.atol_mu = atol.mu;
  o.multiplier_atol_per_row = !settings.atol_multiplier;
  o.multiplier_mass = atol.mass;
  o.mu_atol_per_row = !settings.atol_mu;
  o.time_scale = atol.time_scale;
  o.first_step = scheme == Scheme::elimination ? atol.first_step_from_motion : atol.first_step;
  o.first_kink = model.first_kink(0.0);
  o.dense_linear_solver = settings.dense_linear_solver;
  o.max_order = settings.max_order;
  o.bridge_singular = settings.bridge_singular;
  o.condensed_newton = settings.condensed_newton;
  o.output_times = settings.output_times();
  o.breakpoints = model.breakpoints(settings.t_end);
  o.max_steps = settings.max_steps;
  o.max_steps_per_output = settings.steps_per_output_budget();
  if (fixed_step(settings.scheme) && settings.step) {
    // A fixed step takes output_step / h steps between two outputs, and two more around a load
    // step: the budget, meant to stop a step size that collapses, must not refuse them.
    const double fixed = std::ceil(settings.output_step / *settings.step) + 2.0;
    o.max_steps_per_output = std::max(o.max_steps_per_output, static_cast<long>(fixed));
  }
  o.max_wall_seconds = settings.max_wall_time;
  return o;
}

/// The tolerances and the integrator's settings of `settings` (again after a fallback).
void plan_tolerances(RunPlan& p) {
  p.tolerances = absolute_tolerances(*p.model, p.settings);
  p.integrator = settings_from(*p.model, p.settings, p.tolerances, p.scheme);
}

/// Elimination's reduction and its ODE; when they are refused, auto falls back to GGL with a
/// multiplier for every row (which integrates such a model), and a named elimination is refused.
void plan_elimination(RunPlan& p, SchemeDecisions& decisions) {
  try {
    if (p.model->is_nonlinear()) {
      // Coordinate partitioning: its refusals (rows without a position form, dependent rows at
      // the start, a singular KKT matrix) found here, by setting it up once.
      (void)PartitionedOde(*p.model, p.integrator.output_times.front());
      return;
    }
    p.reduced_ode = decisions.reduced_ode(p.settings.slaves);
    p.reduced = decisions.reduced(p.settings.slaves);
    return;
  } catch (const SchemeNotApplicable& why) {
    if (p.settings.scheme != Scheme::automatic) {
      p.refusal = why.what();
      return;
    }
    p.fallback = std::string("auto: elimination refused (") + why.what() + "), GGL instead";
  }
  p.scheme = Scheme::ggl;
  p.reason = *p.fallback;
  p.settings.scheme = Scheme::ggl;
  p.settings.treatment = SolveSpec::Treatment::multipliers;
  plan_tolerances(p);
}

/// The Newmark family's parameters and step (fixed or error-controlled).
RunNote newmark_note(Scheme scheme, const SolveSpec& settings) {
  const AlphaParameters p = alpha_parameters(scheme, settings.newmark_family);
  std::string text = describe(scheme, p) +
                     (settings.step ? ", fixed step " + shortest_number(*settings.step)
                                    : ", error-controlled steps") +
                     (settings.newmark_family.constraints == NewmarkConstraints::stabilized
                          ? ", constraints stabilized (index 2: positions and velocities)"
                          : "");
  return {RunNote::Kind::scheme_setting, std::move(text)};
}

/// RATTLE's step (it has no parameters).
RunNote rattle_note(const SolveSpec& settings) {
  return {RunNote::Kind::scheme_setting,
          "rattle: symplectic, fixed step " + shortest_number(settings.step.value_or(0))};
}

/// The parameters of a multiplier scheme or penalty, and the mixed treatment's rows: computed
/// once here, noted in the summary before the run.
void plan_parameters(RunPlan& p, SchemeDecisions& decisions) {
  const Model& model = *p.model;
  if (p.scheme == Scheme::baumgarte) {
    p.gains = baumgarte_gains(model, p.settings);
    p.notes.push_back({RunNote::Kind::scheme_setting, p.gains.rule});
  }
  if (p.scheme == Scheme::penalty && model.is_nonlinear()) {
    // The augmented Lagrangian: its α from the model
    // (dae/formulations/augmented_lagrangian_ode.hpp).
    std::string rule = augmented_lagrangian_parameters(model).rule;
    if (p.settings.penalty_weight)
      rule += "; [solve] penalty's weight is for linear models, unused";
    p.notes.push_back({RunNote::Kind::scheme_setting, std::move(rule)});
  } else if (p.scheme == Scheme::penalty) {
    p.weights = penalty_weights(model, p.settings);
    p.notes.push_back({RunNote::Kind::scheme_setting, p.weights.rule});
  }
  if (newmark_family(p.scheme)) p.notes.push_back(newmark_note(p.scheme, p.settings));
  if (p.scheme == Scheme::rattle) {
    p.notes.push_back(rattle_note(p.settings));
    if (auto warning =
            rattle_stability_warning(p.tolerances.scales, p.settings.step.value_or(0.0))) {
      p.notes.push_back({RunNote::Kind::warning, std::move(*warning)});
    }
  }
  if (uses_mixed_treatment(model, p.scheme, p.settings)) {
    p.treatment = decisions.treatment();
    p.notes.push_back({RunNote::Kind::treatment,
                       "mixed treatment: " + std::to_string(p.treatment->eliminated.size()) +
                           " rows eliminated, " + std::to_string(p.treatment->kept.size()) +
                           " with multipliers"});
  }
}

/// The factorization of the Newton matrices: CHOLMOD, which condenses the Newton systems, where
/// they are symmetric positive definite and it is chosen; noted when it is, or when auto could
/// not load it.
void plan_factorization(RunPlan& p) {
  using LinearSolver = SolveSpec::LinearSolver;
  const SolveSpec& s = p.settings;
  // The condensed system is formed only when it may be factored by CHOLMOD.
  const bool asked = s.linear_solver == LinearSolver::cholmod ||
                     (s.linear_solver == LinearSolver::automatic && s.condensed_newton);
  const auto newton = asked ? symmetric_newton_system(p) : nullptr;
  p.factorization = choose_factorization(newton.get(), p.scheme, p.settings);
  if (p.factorization.cholmod || p.factorization.cholmod_unavailable) {
    p.notes.push_back({RunNote::Kind::scheme_setting, p.factorization.reason});
  }
  if (!p.factorization.cholmod) return;
  p.integrator.cholmod = true;
  p.integrator.cholmod_ordering = p.factorization.ordering;
  p.integrator.condensed_newton = true;
}

}  // namespace

std::unique_ptr<NewtonSystem> symmetric_newton_system(const RunPlan& p) {
  if (p.refusal || p.settings.dense_linear_solver) return nullptr;
  if (p.scheme == Scheme::elimination && p.reduced_ode) return p.reduced_ode->newton_system();
  if (p.scheme == Scheme::penalty && !p.model->is_nonlinear()) {
    return PenaltyOde(*p.model->system, p.weights).newton_system();
  }
  return nullptr;
}

IntegratorSettings integrator_settings(const Model& model, const SolveSpec& settings) {
  return settings_from(model, settings, absolute_tolerances(model, settings), settings.scheme);
}

RunPlan plan(const Model& model, const SolveSpec& settings) {
  SchemeDecisions decisions(model);
  return plan(model, settings, decisions);
}

RunPlan plan(const Model& model, const SolveSpec& settings, SchemeDecisions& decisions) {
  settings.validate();
  RunPlan p;
  p.model = &model;
  p.settings = settings;
  p.scheme = settings.scheme;
  p.reason = "requested";
  if (auto why = scheme_refusal(model, settings.scheme)) {
    p.refusal = std::move(why);
    plan_tolerances(p);
    return p;
  }
  if (settings.scheme == Scheme::automatic) {
    SchemeChoice choice = decisions.choose(settings);
    p.scheme = choice.scheme;
    p.reason = std::move(choice.reason);
  }
  plan_tolerances(p);
  if (p.scheme == Scheme::elimination) plan_elimination(p, decisions);
  if (!p.refusal) plan_parameters(p, decisions);
  if (!p.refusal) plan_factorization(p);
  return p;
}

RunHooks hooks_for(const std::vector<Quantity>& quantities) {
  const auto has = [&quantities](Quantity q) {
    return std::find(quantities.begin(), quantities.end(), q) != quantities.end();
  };
  RunHooks hooks;
  hooks.accelerations = has(Quantity::acceleration) || has(Quantity::absolute_acceleration);
  hooks.energy_balance = has(Quantity::energy);
  hooks.reactions = hooks.accelerations || has(Quantity::reaction) || has(Quantity::multiplier);
  return hooks;
}

namespace {

/// The plan's integrator settings with what the caller observes.
IntegratorOptions options_of(const RunPlan& plan, const RunHooks& hooks) {
  IntegratorOptions options;
  static_cast<IntegratorSettings&>(options) = plan.integrator;
  options.record_steps = hooks.record_steps;
  options.accelerations = hooks.accelerations;
  options.row_multipliers = hooks.reactions;
  options.energy_balance = hooks.energy_balance;
  options.on_progress = hooks.on_progress;
  options.on_row = hooks.on_row;
  return options;
}

/// Runs the plan's scheme through its runner (dae/formulations/scheme_run.hpp).
void run_scheme(const RunPlan& plan, const IntegratorOptions& options, const ObservedRun& run) {
  const Model& model = *plan.model;
  switch (plan.scheme) {
    case Scheme::elimination: {
      if (model.is_nonlinear()) return run_partitioned_elimination(model, run);
      ReducedOde ode = *plan.reduced_ode;  // this run's own copy
      return run_elimination(model, *plan.reduced, ode, run);
    }
    case Scheme::automatic:
      break;  // resolved by plan()
    case Scheme::index1:
    case Scheme::baumgarte:
    case Scheme::ggl:
    case Scheme::index2:
    case Scheme::index3:
      return run_multipliers(model, plan.scheme, plan.gains, plan.treatment.get(),
                             options.row_multipliers, run);
    case Scheme::penalty:
      return run_penalty(model, plan.weights, run);
    case Scheme::projection:
      return run_projection(model, run);
    case Scheme::newmark:
    case Scheme::hht:
    case Scheme::generalized_alpha:
      return run_newmark(model, alpha_parameters(plan.scheme, plan.settings.newmark_family),
                         plan.settings.newmark_family.constraints, plan.settings.step.value_or(0.0),
                         plan.treatment.get(), options.row_multipliers, run);
    case Scheme::rattle:
      return run_rattle(model, plan.settings.step.value_or(0.0), options.row_multipliers, run);
  }
  throw std::logic_error("unknown scheme");
}

/// What is noted after the run, in this order: the order cap, the warnings (of a run that
/// ended), the singular passages.
void note_after(const RunPlan& plan, SolveResult& result) {
  const SolveSpec& settings = plan.settings;
  SolveSummary& summary = result.summary;
  if (settings.max_order < 5) {
    summary.add_note(RunNote::Kind::order_cap,
                     "BDF order at most " + std::to_string(settings.max_order) +
                         " (highest used: " + std::to_string(summary.max_order_used) + ")");
  }
  for (const auto& note : {summary.error_test_warning(), summary.atol_warning(settings.atol),
                           summary.drift_warning(settings.rtol, settings.atol)}) {
    if (note && !result.failure) summary.add_note(RunNote::Kind::warning, *note);
  }
  if (std::string note = singular_passage_note(summary.singular_passages, result.trajectory.t);
      !note.empty()) {
    summary.add_note(RunNote::Kind::singular_passage, std::move(note));
  }
}

/// What to try instead, after a failure.
void advise(const RunPlan& plan, SolveResult& result) {
  RunFailure& failure = *result.failure;
  std::string causes =
      roundoff_advice(failure, plan.settings.atol, result.summary.max_abs_displacement,
                      plan.model->system->coordinate_scale());
  // Only a scene's atol_mu can lie below the rows' floor (the derived one never does).
  if (plan.scheme == Scheme::ggl && plan.settings.atol_mu) {
    causes += mu_roundoff_advice(failure, *plan.settings.atol_mu, plan.tolerances.mu_floor);
  }
  AdviceContext context;
  context.nonlinear_model = plan.model->is_nonlinear();
  context.fixed_step = fixed_step(plan.scheme) && plan.settings.step.has_value();
  context.undamped_index3 =
      newmark_family(plan.scheme) &&
      plan.settings.newmark_family.constraints == NewmarkConstraints::index3 &&
      !damps_high_frequencies(alpha_parameters(plan.scheme, plan.settings.newmark_family));
  failure.suggestion = failure_suggestion(plan.scheme, failure, causes, context);
  // RATTLE blown up by a step beyond its stability limit: the limit, not the loads, explains it.
  if (plan.scheme == Scheme::rattle && failure.kind != FailureKind::interrupted) {
    for (const RunNote& note : plan.notes) {
      if (note.kind == RunNote::Kind::warning) failure.suggestion += "; " + note.text;
    }
  }
  failure.suggestion += singular_failure_advice(result.summary.singular_passages);
}

}  // namespace

SolveResult execute(const RunPlan& plan, const RunHooks& hooks) {
  if (plan.refusal) throw SchemeNotApplicable(*plan.refusal, plan.settings.scheme_where);
  const Model& model = *plan.model;
  const IntegratorOptions options = options_of(plan, hooks);
  SolveResult result;
  result.scheme = plan.scheme;
  result.summary.scheme = to_string(plan.scheme);
  result.summary.notes = plan.notes;
  try {
    run_scheme(plan, options, [&](const Integrate& integrate, const Observation& observe) {
      result = run_observed(model, options, integrate, observe, result.summary);
      result.scheme = plan.scheme;
    });
    if (plan.fallback) {
      result.summary.notes.insert(result.summary.notes.begin(),
                                  {RunNote::Kind::fallback, *plan.fallback});
    }
  } catch (const SchemeNotApplicable& why) {
    throw SchemeNotApplicable(why.what(), plan.settings.scheme_where);
  } catch (const IntegrationError& e) {
    // Outside the loop (the loop's own failures come back as data): the integrator could not be
    // created or initialised.
    result.failure = failure_of(e);
  }
  note_after(plan, result);
  if (result.failure) advise(plan, result);
  return result;
}

}  // namespace condyn
