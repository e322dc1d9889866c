// The Newmark family's runner: the stepper of dae/integrators/newmark_stepper.hpp on the model's
// own system, or under the mixed treatment on the system with its cheap linear rows eliminated
// (dae/formulations/eliminated_system.hpp), as the multiplier schemes run it; its state [u; v; λ]
// ([u; v; λ; μ] stabilized) observed as the other schemes' (λ at a step is the step's own
// multiplier, f_con = −Aᵀλ under both forms, an unknown held with the positions; at the output
// rows, when reactions are asked for, λ from acceleration level at the row's u and v, as the
// multiplier schemes report: the step's own carries the constraint modes' step-to-step
// oscillation, undamped under average acceleration, and an O(h) start-up transient where a
// constraint moves (docs/schemes.md)). μ, the stabilized form's correction, is reported as GGL's:
// its largest |μ| in the summary.

#include <algorithm>
#include <memory>

#include "dae/formulations/row_multipliers.hpp"
#include "dae/formulations/scheme_run.hpp"
#include "dae/formulations/treated_system.hpp"
#include "dae/integrators/newmark_error_control.hpp"
#include "dae/integrators/newmark_stepper.hpp"

namespace condyn {

void run_newmark(const Model& model, const AlphaParameters& parameters,
                 NewmarkConstraints constraints, double step, const ConstraintTreatment* mixed,
                 bool row_multipliers, const ObservedRun& run) {
  TreatedSystem treated(model, mixed);
  const MechanicalSystem& system = treated.system();
  const int n = system.dofs(), m = system.constraints();
  const Eigen::Index lambda_at = 2 * Eigen::Index{n};  // y = [u; v; λ (; μ)], y' = [u'; u''; 0]
  Observation observe;
  treated.observe(
      [lambda_at, m](const Eigen::VectorXd& y) { return Eigen::VectorXd(y.segment(lambda_at, m)); },
      row_multipliers, observe);
  const bool linear = !model.nonlinear;
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
        auto consistent = std::make_shared<AccelerationLevelMultipliers>(system, linear);
        // step 0: error-controlled, with the displacements' tolerances of the BDF schemes.
        NewmarkSettings settings{parameters, step, o.rtol, o.atol_of(UnknownKind::displacement)};
        settings.constraints = constraints;
        settings.first_kink = o.first_kink;
        if (step == 0.0) settings.newton_fraction = newmark_newton_fraction(o.rtol);
        NewmarkStepper stepper(
            system, linear, settings,
            [consistent](double t, const Eigen::VectorXd& u, const Eigen::VectorXd& v) {
              return (*consistent)(t, u, v);
            },
            o.output_times.front(), treated.initial(model.u0), treated.initial(model.v0));
        s.unknowns = stepper.size();
        RawTrajectory out = drive(stepper, stepper.y(), stepper.yp(), o, s);
        s.jacobian_nonzeros = stepper.jacobian_nonzeros();
        s.set_reached(o.output_times.back());
        return out;
      },
      observe);
}

}  // namespace condyn
