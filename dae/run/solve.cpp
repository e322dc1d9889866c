#include "dae/run/solve.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <initializer_list>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "dae/formulations/baumgarte_gains.hpp"
#include "dae/formulations/constraint_treatment.hpp"
#include "dae/formulations/eliminated_system.hpp"
#include "dae/formulations/master_slave.hpp"
#include "dae/formulations/model_scales.hpp"
#include "dae/formulations/multiplier_dae.hpp"
#include "dae/formulations/penalty_ode.hpp"
#include "dae/formulations/projected_ode.hpp"
#include "dae/formulations/reduced_ode.hpp"
#include "dae/formulations/row_multipliers.hpp"
#include "dae/integrators/cvode_integrator.hpp"
#include "dae/integrators/ida_integrator.hpp"
#include "dae/run/elimination.hpp"
#include "dae/run/failure_advice.hpp"
#include "dae/run/observed_run.hpp"
#include "dae/run/singular_passages.hpp"

namespace condyn {

namespace {

/// Why a scheme cannot run a model, if it cannot (scheme_refusal() words it).
enum class Refusal {
  none,
  penalty_static_start,
  elimination_nonholonomic,
  elimination_nonlinear,
  penalty_nonlinear,
  penalty_dense_row
};

/// The constraint row with the most entries, and their count (m = 0: row −1).
std::pair<int, long> longest_row(const Eigen::SparseMatrix<double>& A) {
  std::vector<long> entries(static_cast<std::size_t>(A.rows()), 0);
  for (int k = 0; k < A.outerSize(); ++k) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, k); it; ++it) {
      ++entries[static_cast<std::size_t>(it.row())];
    }
  }
  const auto at = std::max_element(entries.begin(), entries.end());
  if (at == entries.end()) return {-1, 0};
  return {static_cast<int>(at - entries.begin()), *at};
}

/// Penalty's springs add w aᵢᵀaᵢ for each row aᵢ to K (and C): a row over L DOFs couples them
/// all, L² entries of the stiffness, as master-slave elimination's dense block would
/// (kMaxDenseGroupEntries): a row over 50,000 DOFs (a floor's average drift) is 2.5·10⁹.
bool penalty_too_dense(const Model& model) {
  const double entries = static_cast<double>(longest_row(model.A).second);
  return entries * entries > kMaxDenseGroupEntries;
}

Refusal refusal_of(const Model& model, Scheme scheme) {
  if (scheme == Scheme::penalty && model.static_start && model.constraint_count() > 0) {
    return Refusal::penalty_static_start;
  }
  if (!model.is_nonlinear()) {
    return scheme == Scheme::penalty && penalty_too_dense(model) ? Refusal::penalty_dense_row
                                                                 : Refusal::none;
  }
  if (scheme == Scheme::elimination) {
    const bool nonholonomic = std::any_of(model.constraints.begin(), model.constraints.end(),
                                          [](const Constraint& c) { return c.nonholonomic; });
    return nonholonomic ? Refusal::elimination_nonholonomic : Refusal::elimination_nonlinear;
  }
  if (scheme == Scheme::penalty) return Refusal::penalty_nonlinear;
  return Refusal::none;
}

/// "a, b or c": the candidates this model is not refused under, so that a refusal never points
/// to a scheme that refuses the same scene (projection's once named penalty on a static start).
std::string usable(const Model& model, std::initializer_list<Scheme> candidates) {
  std::vector<std::string> names;
  for (Scheme s : candidates) {
    if (refusal_of(model, s) == Refusal::none) names.emplace_back(to_string(s));
  }
  std::string out;
  for (std::size_t k = 0; k < names.size(); ++k) {
    out += (k == 0 ? "" : k + 1 == names.size() ? " or " : ", ") + names[k];
  }
  return out;
}

}  // namespace

std::optional<std::string> scheme_refusal(const Model& model, Scheme scheme) {
  using S = Scheme;
  const auto dae_schemes = {S::index1, S::baumgarte, S::ggl, S::index2, S::index3, S::projection};
  switch (refusal_of(model, scheme)) {
    case Refusal::none:
      return std::nullopt;
    case Refusal::penalty_static_start:
      return "[initial] static = true gives the equilibrium under exact constraints, where "
             "penalty's springs carry no force: under penalty the structure would not start at "
             "rest (its supports unloaded). Use another scheme, or give the displacements";
    case Refusal::elimination_nonholonomic:
      return "elimination cannot treat a nonholonomic constraint: master-slave elimination "
             "solves constraints for slave displacements, and a nonintegrable velocity "
             "constraint has no displacement form to solve. The chapter says so: nonholonomic "
             "MFCs \"are non treatable by master-slave methods unless they integrate to "
             "holonomic constraints\" (§5.6), and for them \"only the Lagrange multiplier "
             "method, used with extreme care, offers hope\" (§5.3.1). Use " +
             usable(model, dae_schemes);
    case Refusal::elimination_nonlinear:
      return "elimination is the chapter's linear path (constant coefficients, linear forces); "
             "this model is nonlinear (state-dependent constraints or forces). Use " +
             usable(model, dae_schemes);
    case Refusal::penalty_nonlinear:
      return "penalty is implemented for linear models only (constant constraints, linear "
             "forces); this model is nonlinear (state-dependent constraints or forces). Use " +
             usable(model, dae_schemes);
    case Refusal::penalty_dense_row: {
      const auto [row, entries] = longest_row(model.A);
      std::ostringstream s;
      s << "penalty: constraint '" << model.constraints[static_cast<std::size_t>(row)].name
        << "' has " << entries << " terms; its spring couples them all, a dense block of "
        << static_cast<double>(entries) * static_cast<double>(entries)
        << " entries in the stiffness and damping (beyond " << kMaxDenseGroupEntries << "); use "
        << usable(model, {S::index1, S::ggl, S::automatic}) << ", which keep it as one multiplier";
      return s.str();
    }
  }
  return std::nullopt;
}

bool uses_mixed_treatment(const Model& model, Scheme resolved, const SolveSpec& settings) {
  if (resolved == Scheme::automatic || !mixes(resolved) || model.constraint_count() == 0)
    return false;
  return settings.treatment == SolveSpec::Treatment::mixed ||
         (settings.treatment == SolveSpec::Treatment::automatic &&
          settings.scheme == Scheme::automatic);
}

const char* treatment_name(const Model& model, Scheme resolved, const SolveSpec& settings) {
  if (resolved == Scheme::automatic || !mixes(resolved) || model.constraint_count() == 0)
    return nullptr;
  return uses_mixed_treatment(model, resolved, settings) ? "mixed" : "multipliers";
}

namespace {

/// auto on a linear model with every row kept as a multiplier ([solve] constraints =
/// "multipliers"): elimination or GGL, whichever factors the smaller Newton matrix.
SchemeChoice cheaper_of_elimination_and_ggl(const Model& model, const SolveSpec& settings) {
  SolveSpec as_ggl = settings, as_elimination = settings;
  as_ggl.scheme = Scheme::ggl;
  as_elimination.scheme = Scheme::elimination;
  const SystemSize ggl = system_size(model, as_ggl);
  SystemSize elimination;
  try {
    elimination = system_size(model, as_elimination);
  } catch (const std::invalid_argument& why) {
    return {Scheme::ggl, std::string("elimination cannot treat this model (") + why.what() +
                             "): GGL, which holds the constraints to the Newton tolerance"};
  }
  std::ostringstream figures;
  figures << "elimination " << elimination.unknowns << " unknowns, "
          << elimination.jacobian_nonzeros << " Jacobian nonzeros; GGL " << ggl.unknowns << ", "
          << ggl.jacobian_nonzeros;
  if (elimination.jacobian_nonzeros <= ggl.jacobian_nonzeros) {
    return {Scheme::elimination,
            "every constraint is linear and integrable, and elimination "
            "solves the smaller system (" +
                figures.str() + ")"};
  }
  return {Scheme::ggl, "the master-slave transform fills in: GGL solves the smaller system (" +
                           figures.str() + ")"};
}

}  // namespace

SchemeChoice choose_scheme(const Model& model, const SolveSpec& settings) {
  if (settings.scheme != Scheme::automatic) return {settings.scheme, "requested"};
  const bool pure = settings.treatment == SolveSpec::Treatment::multipliers;
  if (model.is_nonlinear()) {
    std::string why =
        "nonlinear model: GGL (stabilized index 2) holds position and velocity constraints to "
        "the Newton tolerance at every step, and treats nonholonomic rows too";
    // Said only where it happens: a sleigh or Andrews' mechanism has no such row.
    if (!pure && !treat_constraints(model).eliminated.empty()) {
      why += "; its constant linear rows eliminated where that stays sparse";
    }
    return {Scheme::ggl, why};
  }
  if (model.constraint_count() == 0) {
    return {Scheme::elimination, "no constraints: the model is integrated as it is"};
  }
  if (pure) return cheaper_of_elimination_and_ggl(model, settings);
  // Every row of a linear model is linear with constant coefficients, hence holonomic or
  // integrable: each group is eliminated unless its master-slave transform fills in.
  ConstraintTreatment treatment;
  try {
    treatment = treat_constraints(model);
  } catch (const std::invalid_argument& why) {
    return {Scheme::ggl, std::string("master-slave elimination cannot treat this model (") +
                             why.what() + "): GGL with a multiplier for every row"};
  }
  if (treatment.kept.empty()) {
    return {Scheme::elimination,
            "every constraint is linear and integrable, and its elimination stays sparse"};
  }
  return {Scheme::ggl, "GGL with mixed treatment: " + std::to_string(treatment.eliminated.size()) +
                           " rows eliminated, " + std::to_string(treatment.kept.size()) +
                           " kept as multipliers (their master-slave transform would fill in)"};
}

IntegratorOptions integrator_options(const Model& model, const SolveSpec& settings) {
  IntegratorOptions o;
  o.rtol = settings.rtol;
  const AbsoluteTolerances atol = absolute_tolerances(model, settings);
  o.atol = atol.displacement;
  o.atol_velocity = atol.velocity;
  o.atol_multiplier = atol.multiplier;
  o.atol_mu = atol.mu;
  o.multiplier_atol_per_row = !settings.atol_multiplier;
  o.multiplier_mass = atol.mass;
  o.mu_atol_per_row = !settings.atol_mu;
  o.time_scale = atol.time_scale;
  o.first_step = atol.first_step;
  o.first_kink = model.first_kink(0.0);
  o.dense_linear_solver = settings.dense_linear_solver;
  o.max_order = settings.max_order;
  o.condensed_newton = settings.condensed_newton;
  o.output_times = settings.output_times();
  o.breakpoints = model.breakpoints(settings.t_end);
  o.max_steps = settings.max_steps;
  o.max_steps_per_output = settings.steps_per_output_budget();
  o.max_wall_seconds = settings.max_wall_time;
  return o;
}

namespace {

void refuse_inapplicable(const Model& model, Scheme scheme, const SourcePoint& chosen_at) {
  if (auto why = scheme_refusal(model, scheme)) throw SchemeNotApplicable(*why, chosen_at);
}

Eigen::VectorXd initial_state(const Model& model) {
  Eigen::VectorXd y0(2 * model.dofs());
  y0 << model.u0, model.v0;
  return y0;
}

void solve_multipliers(const Model& model, Scheme scheme, const SolveSpec& settings,
                       const IntegratorOptions& options, SolveResult& result) {
  SolveSummary& summary = result.summary;
  BaumgarteGains gains;
  if (scheme == Scheme::baumgarte) {
    gains = baumgarte_gains(model, settings);
    summary.notes = gains.rule;
  }
  summary.scheme = to_string(scheme);
  std::optional<EliminatedSystem> reduced, observer;
  if (uses_mixed_treatment(model, scheme, settings)) {
    const ConstraintTreatment treatment = treat_constraints(model);
    if (!treatment.eliminated.empty()) {
      reduced.emplace(model, treatment);
      observer.emplace(*reduced);  // its own evaluator, for the outputs
    }
    const std::string note = "mixed treatment: " + std::to_string(treatment.eliminated.size()) +
                             " rows eliminated, " + std::to_string(treatment.kept.size()) +
                             " with multipliers";
    summary.notes = summary.notes.empty() ? note : summary.notes + "; " + note;
  }
  const bool mixed = reduced.has_value();
  const MechanicalSystem& system =
      mixed ? static_cast<const MechanicalSystem&>(*reduced) : *model.system;
  MultiplierDae dae(system, scheme, gains.alpha, gains.beta, !model.nonlinear);
  const int n = system.dofs();
  double max_mu = 0.0;
  Observation observe;
  if (mixed) {
    observe.full_state = [&](double t, const Eigen::VectorXd& y) {
      return observer->expand(t, y.head(n), y.segment(n, n));
    };
    observe.multipliers = [&](double t, const Eigen::VectorXd& y, const Eigen::VectorXd& yp,
                              const Eigen::VectorXd&, const Eigen::VectorXd&) {
      return observer->multipliers(t, y.head(n), y.segment(n, n), yp.segment(n, n), dae.lambda(y));
    };
  } else {
    observe.full_state = full_state_prefix(n);
    observe.multipliers = [&](double, const Eigen::VectorXd& y, const Eigen::VectorXd&,
                              const Eigen::VectorXd&,
                              const Eigen::VectorXd&) { return Eigen::VectorXd(dae.lambda(y)); };
  }
  // Output rows take λ from acceleration level (dae/formulations/row_multipliers.hpp), on the
  // system the scheme integrates (the reduced one under the mixed treatment, whose eliminated rows'
  // λ follow).
  std::optional<AccelerationLevelMultipliers> at_rows;
  // Under the mixed treatment even without kept rows: the eliminated rows' λ follow from the
  // reduced u'', which the integrator only interpolates between steps.
  if (options.row_multipliers && (mixed || system.constraints() > 0))
    at_rows.emplace(system, !model.nonlinear);
  if (at_rows) {
    observe.row_multipliers = [&](double t, const Eigen::VectorXd& y, const Eigen::VectorXd& yp,
                                  const Eigen::VectorXd& u, const Eigen::VectorXd& v) {
      const Eigen::VectorXd q = y.head(n), w = y.segment(n, n);
      const auto solved = (*at_rows)(t, q, w);
      if (!solved) return observe.multipliers(t, y, yp, u, v);
      if (mixed) return observer->multipliers(t, q, w, solved->first, solved->second);
      return solved->second;
    };
  }
  observe.on_state = [&](const Eigen::VectorXd& y) {
    if (dae.mu(y).size() > 0) max_mu = std::max(max_mu, dae.mu(y).cwiseAbs().maxCoeff());
  };
  const Eigen::VectorXd y0 =
      mixed ? dae.pack(reduced->restrict(model.u0), reduced->restrict(model.v0))
            : dae.pack(model.u0, model.v0);
  run_observed(
      model, options, [&](const IntegratorOptions& o) { return integrate(dae, y0, o, summary); },
      observe, result);
  if (scheme == Scheme::ggl) summary.max_abs_mu = max_mu;
}

void solve_penalty(const Model& model, const SolveSpec& settings, const IntegratorOptions& options,
                   SolveResult& result) {
  SolveSummary& summary = result.summary;
  const PenaltyWeights weights = penalty_weights(model, settings);
  summary.notes = weights.rule;
  summary.scheme = to_string(Scheme::penalty);
  PenaltyOde ode(*model.system, weights);  // linear models only (scheme_refusal)
  Observation observe;
  observe.full_state = full_state_prefix(model.dofs());
  observe.multipliers = [&](double t, const Eigen::VectorXd& y, const Eigen::VectorXd&,
                            const Eigen::VectorXd&,
                            const Eigen::VectorXd&) { return ode.multipliers(t, y); };
  run_observed(
      model, options,
      [&](const IntegratorOptions& o) { return integrate(ode, initial_state(model), o, summary); },
      observe, result);
}

void solve_projection(const Model& model, const IntegratorOptions& options, SolveResult& result) {
  SolveSummary& summary = result.summary;
  summary.scheme = to_string(Scheme::projection);
  ProjectedOde ode(*model.system, model.u0, !model.nonlinear, &model);
  Observation observe;
  observe.full_state = full_state_prefix(model.dofs());
  observe.multipliers = [&](double t, const Eigen::VectorXd& y, const Eigen::VectorXd&,
                            const Eigen::VectorXd&,
                            const Eigen::VectorXd&) { return ode.multipliers(t, y); };
  run_observed(
      model, options,
      [&](const IntegratorOptions& o) {
        return integrate_ode(ode, initial_state(model), o, summary);
      },
      observe, result);
}

}  // namespace

SystemSize system_size(const Model& model, const SolveSpec& settings) {
  try {
    return SystemSizer(model)(settings);
  } catch (const SchemeNotApplicable& why) {
    throw SchemeNotApplicable(why.what(), settings.scheme_where);
  }
}

const ReducedSystem& SystemSizer::reduced(const std::vector<std::string>& slaves) {
  if (!reduced_) reduced_ = std::make_shared<const ReducedSystem>(reduce(model_, slaves));
  return *reduced_;
}

SystemSize SystemSizer::operator()(const SolveSpec& settings) {
  const Model& model = model_;
  Scheme scheme = settings.scheme;
  if (scheme == Scheme::automatic) scheme = choose_scheme(model, settings).scheme;
  refuse_inapplicable(model, scheme, settings.scheme_where);
  // The matrix IDA's Newton iterations factor: the condensed one when asked for.
  const bool condensed = settings.condensed_newton && !settings.dense_linear_solver;
  SystemSize size;
  size.dense = settings.dense_linear_solver;
  if (scheme == Scheme::elimination) {
    const ReducedOde ode(model, reduced(settings.slaves));
    size.unknowns = ode.size();
    size.condensed = condensed;
    size.reduced = true;
    size.jacobian_nonzeros =
        condensed ? ode.newton_system()->nonzeros() : ode.jacobian_pattern().nonZeros();
    return size;
  }
  if (scheme == Scheme::penalty) {
    const PenaltyOde ode(*model.system, penalty_weights(model, settings));
    size.unknowns = ode.size();
    size.jacobian_nonzeros = ode.jacobian_pattern().nonZeros();
    return size;
  }
  const MechanicalSystem* system = model.system.get();
  if (uses_mixed_treatment(model, scheme, settings)) {
    if (!mixed_) {
      const ConstraintTreatment treatment = treat_constraints(model);
      mixed_ = treatment.eliminated.empty()
                   ? nullptr
                   : std::make_shared<const EliminatedSystem>(model, treatment);
    }
    if (*mixed_) system = mixed_->get();
    size.reduced = *mixed_ != nullptr;
  }
  if (scheme == Scheme::projection) {
    const ProjectedOde ode(*system, model.u0, !model.nonlinear, &model);
    // The matrix the Newton iterations factor: the sparse saddle point, else CVODE's dense one.
    size.unknowns = ode.size();
    const auto newton = ode.newton_system();
    size.condensed = newton != nullptr;
    size.dense = !size.condensed;
    size.jacobian_nonzeros =
        newton ? newton->nonzeros() : static_cast<long>(ode.size()) * ode.size();
    return size;
  }
  // The Jacobian's pattern does not depend on the values of Baumgarte's gains, only on their
  // being nonzero: unit gains size it without the model's frequencies (a Lanczos run at scale).
  const double gain = scheme == Scheme::baumgarte ? 1.0 : 0.0;
  const MultiplierDae dae(*system, scheme, gain, gain, !model.nonlinear);
  size.unknowns = dae.size();
  const auto newton = condensed ? dae.newton_system() : nullptr;
  size.condensed = newton != nullptr;
  size.jacobian_nonzeros = newton ? newton->nonzeros() : dae.jacobian_pattern().nonZeros();
  return size;
}

namespace {

void solve_resolved(const Model& model, Scheme scheme, const SolveSpec& settings,
                    const IntegratorOptions& options, SolveResult& result) {
  switch (scheme) {
    case Scheme::elimination:
      return solve_elimination(model, settings.slaves, options, result);
    case Scheme::automatic:
      break;  // resolved by solve()
    case Scheme::index1:
    case Scheme::baumgarte:
    case Scheme::ggl:
    case Scheme::index2:
    case Scheme::index3:
      return solve_multipliers(model, scheme, settings, options, result);
    case Scheme::penalty:
      return solve_penalty(model, settings, options, result);
    case Scheme::projection:
      return solve_projection(model, options, result);
  }
  throw std::logic_error("unknown scheme");
}

}  // namespace

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

SolveResult solve(const Model& model, const SolveSpec& settings, const RunHooks& hooks) {
  settings.validate();
  Scheme scheme = settings.scheme;
  refuse_inapplicable(model, scheme, settings.scheme_where);
  if (scheme == Scheme::automatic) scheme = choose_scheme(model, settings).scheme;
  SolveResult result;
  result.scheme = scheme;
  const auto options_for = [&](const SolveSpec& s) {
    IntegratorOptions options = integrator_options(model, s);
    options.record_steps = hooks.record_steps;
    options.accelerations = hooks.accelerations;
    options.row_multipliers = hooks.reactions;
    options.energy_balance = hooks.energy_balance;
    options.on_progress = hooks.on_progress;
    options.on_row = hooks.on_row;
    return options;
  };
  try {
    try {
      solve_resolved(model, scheme, settings, options_for(settings), result);
    } catch (const SchemeNotApplicable& why) {
      // auto chose elimination for its cost. A model its reduction cannot integrate (a reduced
      // mass matrix singular to roundoff: a mass of 1e-20 beside 2) goes to GGL with a multiplier
      // for every row, which integrates it; the reason is in the summary. Nothing was integrated
      // or written yet: ReducedOde refuses when it is built, before the first step.
      if (settings.scheme != Scheme::automatic || scheme != Scheme::elimination)
        throw SchemeNotApplicable(why.what(), settings.scheme_where);
      SolveSpec ggl = settings;
      ggl.scheme = Scheme::ggl;
      ggl.treatment = SolveSpec::Treatment::multipliers;
      scheme = Scheme::ggl;
      result = SolveResult{};
      result.scheme = scheme;
      solve_resolved(model, scheme, ggl, options_for(ggl), result);
      const std::string note =
          std::string("auto: elimination refused (") + why.what() + "), GGL instead";
      auto& notes = result.summary.notes;
      notes = notes.empty() ? note : note + "; " + notes;
    }
  } catch (const IntegrationError& e) {
    // Outside the loop (the loop's own failures come back as data): the integrator could not be
    // created or initialised.
    result.failure = failure_of(e);
  }
  if (settings.max_order < 5) {
    const std::string note = "BDF order at most " + std::to_string(settings.max_order) +
                             " (highest used: " + std::to_string(result.summary.max_order_used) +
                             ")";
    auto& notes = result.summary.notes;
    notes = notes.empty() ? note : notes + "; " + note;
  }
  for (const auto& note :
       {result.summary.error_test_warning(), result.summary.atol_warning(settings.atol),
        result.summary.drift_warning(settings.rtol, settings.atol)}) {
    if (!note || result.failure) continue;
    auto& notes = result.summary.notes;
    notes = notes.empty() ? *note : notes + "; " + *note;
  }
  if (const std::string note =
          singular_passage_note(result.summary.singular_passages, result.trajectory.t);
      !note.empty()) {
    auto& notes = result.summary.notes;
    notes = notes.empty() ? note : notes + "; " + note;
  }
  if (result.failure) {
    RunFailure& failure = *result.failure;
    std::string causes =
        roundoff_advice(failure, settings.atol, result.summary.max_abs_displacement,
                        model.system->coordinate_scale());
    // Only a scene's atol_mu can lie below the rows' floor (the derived one never does): the
    // model's scales are computed again for it, on this failure's path alone.
    if (scheme == Scheme::ggl && settings.atol_mu) {
      causes += mu_roundoff_advice(failure, *settings.atol_mu,
                                   absolute_tolerances(model, settings).mu_floor);
    }
    failure.suggestion = failure_suggestion(scheme, failure, causes);
    failure.suggestion += singular_failure_advice(result.summary.singular_passages);
  }
  return result;
}

}  // namespace condyn
