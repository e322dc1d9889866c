#include "dae/run/observed_run.hpp"

#include <algorithm>
#include <exception>
#include <iomanip>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "dae/run/energy_balance.hpp"
#include "dae/run/singular_passages.hpp"
#include "models/core/constraint_drift.hpp"
#include "models/core/mechanism.hpp"

namespace condyn {

namespace {

/// The summary's drifts: the largest over the internal steps and the output rows, after a
/// failure as after a whole run (`max_relative`: ConstraintDrift::relative_position's); and the
/// largest displacement of the rows (`streamed_max_u` for a streamed run, whose trajectory holds
/// no u).
void summarize_drift(SolveResult& result, double max_dp, double max_dv, double max_relative,
                     double streamed_max_u) {
  const auto max_of = [](const Eigen::VectorXd& x) { return x.size() ? x.maxCoeff() : 0.0; };
  result.summary.max_relative_drift_position = max_relative;
  result.summary.max_drift_position = std::max(max_dp, max_of(result.trajectory.drift_position));
  result.summary.max_drift_velocity = std::max(max_dv, max_of(result.trajectory.drift_velocity));
  const Eigen::MatrixXd& u = result.trajectory.u;
  result.summary.max_abs_displacement =
      std::max(streamed_max_u, u.size() > 0 ? u.cwiseAbs().maxCoeff() : 0.0);
}

/// Where a mechanism drifted most (constraint row `row`): the body whose rigid-body row it is
/// (rigid_row_body), or else its joint (rows are named "<joint>.<what>": the name up to its last
/// '.'); neither for another model's row or no row.
void name_worst_drift(const Model& model, int row, SolveSummary& summary) {
  if (!model.outputs || row < 0 || row >= model.constraint_count()) return;
  const std::string& name = model.constraints[static_cast<std::size_t>(row)].name;
  if (std::string body = rigid_row_body(name); !body.empty()) {
    summary.worst_drift_body = std::move(body);
    return;
  }
  const std::size_t dot = name.rfind('.');
  if (dot != std::string::npos && dot != 0) summary.worst_drift_joint = name.substr(0, dot);
}

/// The energy balance's integrals over every internal step (EnergyTerms::powers at the
/// quadrature points of the loop), added to `observed`.
void add_energy_integrals(const Observation& observe, EnergyTerms& energy,
                          IntegratorOptions& observed) {
  observed.integrand_size = EnergyTerms::kIntegrals;
  observed.integrand = [&](double t, const Eigen::VectorXd& y, const Eigen::VectorXd& yp) {
    const auto [u, v] = observe.full_state(t, y);
    return energy.powers(t, u, v, observe.multipliers(t, y, yp, u, v));
  };
  // At a load step a massless DOF held by stiffness jumps to its new equilibrium: the load,
  // at its new value, does f_ext(t+)ᵀΔu over the jump (the work the quadrature cannot see).
  observed.integrand_jump = [&](double t, const Eigen::VectorXd& before,
                                const Eigen::VectorXd& after) {
    const Eigen::VectorXd u_after = observe.full_state(t, after).first;
    return energy.jump_work(t, u_after, u_after - observe.full_state(t, before).first);
  };
}

/// The facts of an integrator's failure in the result, and where the loop stopped.
void record_failure(const IntegrationError& e, SolveResult& result) {
  result.failure = failure_of(e);
  if (e.in_loop) {
    std::ostringstream s;
    s << "stopped at t = " << std::fixed << std::setprecision(6) << e.t_reached;
    result.summary.termination = s.str();
  }
}

/// Runs `integrate` into `raw`; true when it reached its end. A failure is recorded in `result`
/// with the partial rows `assemble` makes of what was computed (none for a streamed run, whose
/// rows are already out).
template <class Assemble>
bool integrate_or_record(const Integrate& integrate, const IntegratorOptions& observed,
                         bool streamed, const Assemble& assemble, RawTrajectory& raw,
                         SolveResult& result) {
  try {
    raw = integrate(observed, result.summary);
    return true;
  } catch (const IntegrationError& e) {
    record_failure(e, result);
    if (!streamed && e.raw_partial && !e.raw_partial->t.empty()) {
      try {
        result.trajectory = assemble(*e.raw_partial);
      } catch (const std::exception&) {
        // Best effort: a partial result that cannot be assembled (a singular KKT matrix at the
        // last row, say) is dropped; the failure reported is the integrator's, not this one.
      }
    }
    return false;
  }
}

}  // namespace

SolveResult run_observed(const Model& model, const IntegratorOptions& options,
                         const Integrate& integrate, const Observation& observe,
                         SolveSummary summary) {
  SolveResult result;
  result.summary = std::move(summary);
  double max_dp = 0.0, max_dv = 0.0, max_relative = 0.0;
  std::vector<StepRecord> steps;
  VelocityReversals reversals;
  ConstraintDrift drift(model);
  // The drift relative to each row's scale, at every step seen and every output row (elimination
  // and runs without a step log are judged at their rows).
  int worst_row = -1;  // where max_relative was reached
  const auto note_relative = [&] {
    if (drift.relative_position() > max_relative) {
      max_relative = drift.relative_position();
      worst_row = drift.worst_row();
    }
  };
  const auto track_relative = [&](double t, const Eigen::VectorXd& u, const Eigen::VectorXd& v) {
    (void)drift(t, u, v);
    note_relative();
  };
  IntegratorOptions observed = options;
  // The energy balance's integrals, over every internal step.
  std::optional<EnergyTerms> energy;
  if (options.energy_balance) add_energy_integrals(observe, energy.emplace(model), observed);
  // Passages near a singular configuration, at every step, for models whose A depends on the
  // state (a linear model's rank is checked once, when it is built).
  std::optional<SingularPassageMonitor> passages;
  if (model.nonlinear && model.constraint_count() > 0) {
    passages.emplace(*model.system);
    observed.conditioning = [&](double t, const Eigen::VectorXd& y) {
      return passages->conditioning(t, observe.full_state(t, y).first);
    };
  }
  if (observe.drift_at_every_step || options.record_steps || observe.on_state || passages) {
    observed.on_step = [&](double t, const Eigen::VectorXd& y) {
      if (observe.on_state) observe.on_state(y);
      if (!observe.drift_at_every_step && !options.record_steps && !passages) return;
      const auto [u, v] = observe.full_state(t, y);
      if (passages) passages->step(t, u, v);
      if (!observe.drift_at_every_step && !options.record_steps) return;
      const auto [dp, dv] = drift(t, u, v);
      max_dp = std::max(max_dp, dp);
      max_dv = std::max(max_dv, dv);
      note_relative();
      if (options.record_steps) steps.push_back({t, dp, dv, reversals(v)});
    };
  }
  const auto& row_lambda = observe.row_multipliers ? observe.row_multipliers : observe.multipliers;
  const auto assemble = [&](const RawTrajectory& raw) {
    std::vector<Eigen::VectorXd> u, v, lambda;
    for (std::size_t k = 0; k < raw.t.size(); ++k) {
      auto [uk, vk] = observe.full_state(raw.t[k], raw.y[k]);
      track_relative(raw.t[k], uk, vk);
      lambda.push_back(row_lambda(raw.t[k], raw.y[k], raw.yp[k], uk, vk));
      u.push_back(std::move(uk));
      v.push_back(std::move(vk));
    }
    Trajectory traj =
        assemble_trajectory(model, raw.t, u, v, lambda, options.accelerations, raw.integrals);
    traj.steps = steps;
    return traj;
  };
  // Streamed: each output row is assembled as the loop reaches it and handed to the sink; the
  // trajectory keeps its times, drifts and energies only.
  const bool streamed = static_cast<bool>(options.on_row);
  std::optional<RowAssembler> rows;
  RowLog log;
  if (streamed) {
    rows.emplace(model, options.accelerations, options.energy_balance);
    observed.on_output = [&](double t, const Eigen::VectorXd& y, const Eigen::VectorXd& yp,
                             const Eigen::VectorXd& integrals) {
      auto [u, v] = observe.full_state(t, y);
      track_relative(t, u, v);
      Eigen::VectorXd lambda = row_lambda(t, y, yp, u, v);
      TrajectoryRow row = (*rows)(t, std::move(u), std::move(v), std::move(lambda), integrals);
      // The monitor has seen the step that reached t: the flag is the one the whole run gives.
      if (passages) row.near_singular = passages->covers(t);
      options.on_row(row);
      log.add(row);
    };
  }
  RawTrajectory raw;
  const bool failed = !integrate_or_record(integrate, observed, streamed, assemble, raw, result);
  if (streamed) {
    result.trajectory = log.trajectory();
    result.trajectory.steps = steps;
  } else if (!failed) {
    result.trajectory = assemble(raw);
  }
  summarize_drift(result, max_dp, max_dv, max_relative, log.max_abs_displacement());
  name_worst_drift(model, worst_row, result.summary);
  if (passages) {
    result.summary.singular_passages = passages->passages();
    if (!streamed) {
      result.trajectory.near_singular =
          near_singular_rows(result.summary.singular_passages, result.trajectory.t);
    }
  }
  if (observe.on_finish) observe.on_finish(result.summary);
  return result;
}

}  // namespace condyn
