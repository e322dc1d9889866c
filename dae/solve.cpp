#include "dae/solve.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "dae/baumgarte_gains.hpp"
#include "dae/cvode_integrator.hpp"
#include "dae/elimination.hpp"
#include "dae/ida_integrator.hpp"
#include "dae/model_scales.hpp"
#include "dae/multiplier_dae.hpp"
#include "dae/observed_run.hpp"
#include "dae/penalty_ode.hpp"
#include "dae/projected_ode.hpp"
#include "dae/reduced_ode.hpp"
#include "models/linear_system.hpp"

namespace condyn {

std::optional<std::string> scheme_refusal(const Model& model, Scheme scheme) {
  if (!model.is_nonlinear()) return std::nullopt;
  const bool nonholonomic = std::any_of(model.constraints.begin(), model.constraints.end(),
                                        [](const Constraint& c) { return c.nonholonomic; });
  if (scheme == Scheme::elimination) {
    if (nonholonomic) {
      return "elimination cannot treat a nonholonomic constraint: master-slave elimination "
             "solves constraints for slave displacements, and a nonintegrable velocity "
             "constraint has no displacement form to solve. The chapter says so: nonholonomic "
             "MFCs \"are non treatable by master-slave methods unless they integrate to "
             "holonomic constraints\" (§5.6), and for them \"only the Lagrange multiplier "
             "method, used with extreme care, offers hope\" (§5.3.1). Use index1, baumgarte, "
             "ggl, index2, index3 or projection";
    }
    return "elimination is the chapter's linear path (constant coefficients, linear forces); "
           "this model is nonlinear (state-dependent constraints or forces). Use index1, "
           "baumgarte, ggl, index2, index3 or projection";
  }
  if (scheme == Scheme::penalty) {
    return "penalty is implemented for linear constraints only; use index1, baumgarte, ggl, "
           "index2, index3 or projection";
  }
  return std::nullopt;
}

SchemeChoice choose_scheme(const Model& model, Scheme requested) {
  if (requested != Scheme::automatic) return {requested, "requested"};
  if (model.is_nonlinear()) {
    return {Scheme::ggl,
            "nonlinear model: GGL (stabilized index 2) holds position and velocity constraints "
            "to the Newton tolerance at every step, and treats nonholonomic rows too"};
  }
  // Every constraint condyn reads today is linear with constant coefficients, hence holonomic or
  // integrable: elimination solves the smallest system (n − m DOFs, no multipliers).
  if (model.constraint_count() == 0) {
    return {Scheme::elimination, "no constraints: the model is integrated as it is"};
  }
  return {Scheme::elimination,
          "every constraint is linear and integrable: elimination solves the smallest system"};
}

IntegratorOptions integrator_options(const Model& model) {
  IntegratorOptions o;
  o.rtol = model.solve.rtol;
  const AbsoluteTolerances atol = absolute_tolerances(model);
  o.atol = atol.displacement;
  o.atol_velocity = atol.velocity;
  o.atol_multiplier = atol.multiplier;
  o.atol_mu = atol.mu;
  o.time_scale = atol.time_scale;
  o.first_step = atol.first_step;
  o.dense_linear_solver = model.solve.dense_linear_solver;
  o.output_times = model.output_times();
  o.breakpoints = model.breakpoints();
  o.max_steps = model.solve.max_steps;
  o.max_wall_seconds = model.solve.max_wall_time;
  return o;
}

namespace {

/// The MechanicalSystem a model is integrated as: its own for nonlinear models, else a view of
/// the linear model.
class SystemOf {
 public:
  explicit SystemOf(const Model& model) {
    if (!model.is_nonlinear()) linear_.emplace(model);
    system_ = model.is_nonlinear() ? model.nonlinear.get() : &*linear_;
  }
  const MechanicalSystem& operator*() const { return *system_; }

 private:
  std::optional<LinearSystem> linear_;
  const MechanicalSystem* system_ = nullptr;
};

void refuse_inapplicable(const Model& model, Scheme scheme) {
  if (auto why = scheme_refusal(model, scheme)) throw SchemeNotApplicable(*why);
}

MultiplierScheme multiplier_scheme(Scheme s) {
  switch (s) {
    case Scheme::index1:
      return MultiplierScheme::index1;
    case Scheme::baumgarte:
      return MultiplierScheme::baumgarte;
    case Scheme::index2:
      return MultiplierScheme::index2;
    case Scheme::index3:
      return MultiplierScheme::index3;
    default:
      return MultiplierScheme::ggl;
  }
}

Eigen::VectorXd initial_state(const Model& model) {
  Eigen::VectorXd y0(2 * model.dofs());
  y0 << model.u0, model.v0;
  return y0;
}

Trajectory solve_multipliers(const Model& model, Scheme scheme, const IntegratorOptions& options,
                             SolveSummary& summary) {
  const SystemOf system_of(model);
  const MechanicalSystem& system = *system_of;
  BaumgarteGains gains;
  if (scheme == Scheme::baumgarte) {
    gains = baumgarte_gains(model);
    summary.notes = gains.rule;
  }
  const MultiplierDae dae(system, multiplier_scheme(scheme), gains.alpha, gains.beta);
  summary.scheme = to_string(scheme);
  double max_mu = 0.0;
  Observation observe;
  observe.full_state = full_state_prefix(model.dofs());
  observe.multipliers = [&](double, const Eigen::VectorXd& y, const Eigen::VectorXd&,
                            const Eigen::VectorXd&) { return Eigen::VectorXd(dae.lambda(y)); };
  observe.on_state = [&](const Eigen::VectorXd& y) {
    if (dae.mu(y).size() > 0) max_mu = std::max(max_mu, dae.mu(y).cwiseAbs().maxCoeff());
  };
  Trajectory traj = run_observed(
      model, options, summary,
      [&](const IntegratorOptions& o) {
        return integrate(dae, dae.pack(model.u0, model.v0), o, summary);
      },
      observe);
  if (scheme == Scheme::ggl) summary.max_abs_mu = max_mu;
  return traj;
}

Trajectory solve_penalty(const Model& model, const IntegratorOptions& options,
                         SolveSummary& summary) {
  const LinearSystem system(model);  // linear models only (scheme_refusal)
  const PenaltyWeights weights = penalty_weights(model);
  summary.notes = weights.rule;
  summary.scheme = to_string(Scheme::penalty);
  const PenaltyOde ode(system, weights);
  Observation observe;
  observe.full_state = full_state_prefix(model.dofs());
  observe.multipliers = [&](double t, const Eigen::VectorXd& y, const Eigen::VectorXd&,
                            const Eigen::VectorXd&) { return ode.multipliers(t, y); };
  return run_observed(
      model, options, summary,
      [&](const IntegratorOptions& o) { return integrate(ode, initial_state(model), o, summary); },
      observe);
}

Trajectory solve_projection(const Model& model, const IntegratorOptions& options,
                            SolveSummary& summary) {
  const SystemOf system(model);
  summary.scheme = to_string(Scheme::projection);
  const ProjectedOde ode(*system, model.u0);
  Observation observe;
  observe.full_state = full_state_prefix(model.dofs());
  observe.multipliers = [&](double t, const Eigen::VectorXd& y, const Eigen::VectorXd&,
                            const Eigen::VectorXd&) { return ode.multipliers(t, y); };
  return run_observed(
      model, options, summary,
      [&](const IntegratorOptions& o) {
        return integrate_ode(ode, initial_state(model), o, summary);
      },
      observe);
}

}  // namespace

SystemSize system_size(const Model& model, Scheme scheme) {
  if (scheme == Scheme::automatic) scheme = choose_scheme(model, scheme).scheme;
  refuse_inapplicable(model, scheme);
  if (scheme == Scheme::elimination) {
    const ReducedSystem reduced = reduce(model);
    const ReducedOde ode(model, reduced);
    return {ode.size(), ode.jacobian_pattern().nonZeros()};
  }
  if (scheme == Scheme::penalty) {
    const LinearSystem system(model);
    const PenaltyOde ode(system, penalty_weights(model));
    return {ode.size(), ode.jacobian_pattern().nonZeros()};
  }
  const SystemOf system_of(model);
  const MechanicalSystem& system = *system_of;
  if (scheme == Scheme::projection) {
    const ProjectedOde ode(system, model.u0);
    return {ode.size(), static_cast<long>(ode.size()) * ode.size()};  // dense
  }
  const BaumgarteGains gains =
      scheme == Scheme::baumgarte ? baumgarte_gains(model) : BaumgarteGains{};
  const MultiplierDae dae(system, multiplier_scheme(scheme), gains.alpha, gains.beta);
  return {dae.size(), dae.jacobian_pattern().nonZeros()};
}

namespace {

Trajectory solve_resolved(const Model& model, Scheme scheme, const IntegratorOptions& options,
                          SolveSummary& summary) {
  switch (scheme) {
    case Scheme::elimination:
      return solve_elimination(model, options, summary);
    case Scheme::automatic:
      break;  // resolved by solve()
    case Scheme::index1:
    case Scheme::baumgarte:
    case Scheme::ggl:
    case Scheme::index2:
    case Scheme::index3:
      return solve_multipliers(model, scheme, options, summary);
    case Scheme::penalty:
      return solve_penalty(model, options, summary);
    case Scheme::projection:
      return solve_projection(model, options, summary);
  }
  throw std::logic_error("unknown scheme");
}

}  // namespace

namespace {

/// "about 140", "about 4e+304": two significant digits, an order of magnitude for the advice.
std::string about(double x) {
  std::ostringstream s;
  if (x >= 1.0 && x < 1e6) {
    const double unit = std::pow(10.0, std::floor(std::log10(x)) - 1.0);
    s << "about " << static_cast<long>(std::round(x / unit) * unit);
  } else {
    s.precision(2);
    s << "about " << x;
  }
  return s.str();
}

/// What the scheme itself adds to the advice after a solver failure.
std::string scheme_advice(Scheme scheme) {
  switch (scheme) {
    case Scheme::baumgarte:
      return "; large Baumgarte gains make the system stiff: try smaller [solve] baumgarte gains "
             "or ggl";
    case Scheme::penalty:
      return "; a large penalty weight makes the system stiff: try a smaller [solve] penalty "
             "weight or ggl";
    case Scheme::index1:
    case Scheme::index2:
      return "; this scheme lets the drift grow: ggl or projection hold the constraints";
    case Scheme::index3:
      return "; index3 is the least robust formulation: try ggl";
    default:
      return "";
  }
}

}  // namespace

std::string failure_suggestion(Scheme scheme, const IntegrationError& e) {
  // What is left of the run, in steps of the last size and in wall time at the pace so far.
  const double left = e.t_end - e.t_reached;
  const bool progressed = e.in_loop && e.t_reached > e.t0;
  const double steps_left = e.last_step != 0.0 ? left / std::abs(e.last_step) : 0.0;
  const double seconds_left = progressed ? e.elapsed_seconds * left / (e.t_reached - e.t0) : 0.0;
  switch (e.kind) {
    case FailureKind::non_finite:
    case FailureKind::residual_non_finite:
      return "the solution blew up: check loads and time functions for runaway growth, and masses "
             "and stiffnesses for absurd magnitudes";
    case FailureKind::step_budget: {
      std::string s = "the run used up its step budget ([solve] max_steps or --max-steps)";
      if (steps_left > 0.0) {
        s += "; at the last step size the rest of the run needs " + about(steps_left) +
             " more steps";
      }
      return s + ": shorten t_end, raise the budget, or loosen rtol (larger steps)";
    }
    case FailureKind::wall_time_budget: {
      std::string s =
          "the run used up its wall-time budget ([solve] max_wall_time or "
          "--max-wall-time)";
      if (seconds_left > 0.0) {
        s += "; at the pace so far the rest of the run needs " + about(seconds_left) + " s";
      }
      return s + ": shorten t_end, raise the budget, or loosen rtol (larger steps)";
    }
    case FailureKind::steps_per_output:
      return "the step size stayed tiny for many steps: the model is very stiff or oscillates far "
             "faster than the output step; a smaller output_step lets the run go on, a looser "
             "rtol takes larger steps" +
             scheme_advice(scheme);
    case FailureKind::step_size_collapsed:
      return "the step size collapsed to roundoff of the time reached: the motion reaches a "
             "singular configuration (constraints that become dependent, a mechanism at a dead "
             "point, a prescribed motion it cannot follow) or a jump; check the scene at the time "
             "reached" +
             scheme_advice(scheme);
    case FailureKind::tolerance_too_tight:
      return "the tolerances ask for more than double precision holds at these magnitudes: "
             "loosen rtol, or raise atol to the size of the smallest quantity that matters";
    case FailureKind::linear_solver:
      return "the iteration matrix could not be factored (singular): a DOF that nothing holds "
             "(no mass, stiffness or constraint), or constraints that became dependent near the "
             "time reached; `condyn info` shows the classification, another scheme may pass" +
             scheme_advice(scheme);
    case FailureKind::first_step:
      return "the integrator failed before its first step, so no motion was computed: check the "
             "initial state (displacements and velocities consistent with the constraints; "
             "[initial] project = true), the tolerances (atol on the scale of the smallest "
             "unknown that matters, rtol not tighter than needed), and the time scale (t_end and "
             "output_step against the model's periods); another scheme may start";
    case FailureKind::bad_input:
      return "the integrator refused an input (a time, tolerance or size it cannot use): check "
             "t_end, output_step, the load step times and the tolerances";
    case FailureKind::convergence:
    case FailureKind::error_test:
    case FailureKind::unknown:
      break;
  }
  std::string s = progressed ? "repeated convergence or error-test failures near the time "
                               "reached: the motion may pass a singular configuration or jump "
                               "there; a looser rtol or another scheme may pass"
                             : "repeated convergence or error-test failures right after the "
                               "start or a load step: check the state there and the tolerances; "
                               "a looser rtol or another scheme may pass";
  return s + scheme_advice(scheme);
}

Trajectory solve(const Model& model, Scheme scheme, const IntegratorOptions& options,
                 SolveSummary& summary) {
  refuse_inapplicable(model, scheme);
  if (scheme == Scheme::automatic) scheme = choose_scheme(model, scheme).scheme;
  try {
    return solve_resolved(model, scheme, options, summary);
  } catch (IntegrationError& e) {
    e.scheme = to_string(scheme);
    e.suggestion = failure_suggestion(scheme, e);
    throw;
  }
}

}  // namespace condyn
