// The Newmark family's runner: the stepper of dae/integrators/newmark_stepper.hpp on the model's
// own system, its state [u; v; λ] ([u; v; λ; μ] stabilized) observed as the other schemes' (λ at
// a step is the step's own multiplier, f_con = −Aᵀλ under both forms, an unknown held with the
// positions; at the output rows, when reactions are asked for, λ from acceleration level at the
// row's u and v, as the multiplier schemes report: the step's own carries the constraint modes'
// step-to-step oscillation, undamped under average acceleration, and an O(h) start-up transient
// where a constraint moves (docs/schemes.md)). μ, the stabilized form's correction, is reported
// as GGL's: its largest |μ| in the summary.

#include <algorithm>
#include <memory>

#include "dae/formulations/row_multipliers.hpp"
#include "dae/formulations/scheme_run.hpp"
#include "dae/integrators/newmark_error_control.hpp"
#include "dae/integrators/newmark_stepper.hpp"

namespace condyn {

void run_newmark(const Model& model, const AlphaParameters& parameters,
                 NewmarkConstraints constraints, double step, bool row_multipliers,
                 const ObservedRun& run) {
  const int n = model.dofs(), m = model.constraint_count();
  const Eigen::Index lambda_at = 2 * Eigen::Index{n};  // y = [u; v; λ (; μ)]
  Observation observe;
  observe.full_state = full_state_prefix(n);
  observe.multipliers = [lambda_at, m](double, const Eigen::VectorXd& y, const Eigen::VectorXd&,
                                       const Eigen::VectorXd&, const Eigen::VectorXd&) {
    return Eigen::VectorXd(y.segment(lambda_at, m));
  };
  const bool linear = !model.nonlinear;
  std::shared_ptr<AccelerationLevelMultipliers> at_rows;
  if (row_multipliers && m > 0) {
    at_rows = std::make_shared<AccelerationLevelMultipliers>(*model.system, linear);
    observe.row_multipliers = [at_rows, n, own = observe.multipliers](
                                  double t, const Eigen::VectorXd& y, const Eigen::VectorXd& yp,
                                  const Eigen::VectorXd& u, const Eigen::VectorXd& v) {
      const auto solved = (*at_rows)(t, y.head(n), y.segment(n, n));
      return solved ? solved->second : own(t, y, yp, u, v);
    };
  }
  double max_mu = 0.0;
  if (constraints == NewmarkConstraints::stabilized) {
    observe.on_state = [&max_mu, mu_at = lambda_at + m](const Eigen::VectorXd& y) {
      const auto mu = y.tail(y.size() - mu_at);
      if (mu.size() > 0) max_mu = std::max(max_mu, mu.cwiseAbs().maxCoeff());
    };
    observe.on_finish = [&max_mu](SolveSummary& s) { s.max_abs_mu = max_mu; };
  }
  run(
      [&](const IntegratorOptions& o, SolveSummary& s) {
        const WallTimer timer(s);
        auto consistent = std::make_shared<AccelerationLevelMultipliers>(*model.system, linear);
        // step 0: error-controlled, with the displacements' tolerances of the BDF schemes.
        NewmarkSettings settings{parameters, step, o.rtol, o.atol_of(UnknownKind::displacement)};
        settings.constraints = constraints;
        settings.first_kink = o.first_kink;
        if (step == 0.0) settings.newton_fraction = newmark_newton_fraction(o.rtol);
        NewmarkStepper stepper(
            *model.system, linear, settings,
            [consistent](double t, const Eigen::VectorXd& u, const Eigen::VectorXd& v) {
              return (*consistent)(t, u, v);
            },
            o.output_times.front(), model.u0, model.v0);
        s.unknowns = stepper.size();
        RawTrajectory out = drive(stepper, stepper.y(), stepper.yp(), o, s);
        s.jacobian_nonzeros = stepper.jacobian_nonzeros();
        s.set_reached(o.output_times.back());
        return out;
      },
      observe);
}

}  // namespace condyn
