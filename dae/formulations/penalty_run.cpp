#include "dae/formulations/augmented_lagrangian_ode.hpp"
#include "dae/formulations/scheme_run.hpp"
#include "dae/integrators/cvode_integrator.hpp"
#include "dae/integrators/ida_integrator.hpp"

namespace condyn {

void run_penalty(const Model& model, const PenaltyWeights& weights, const ObservedRun& run) {
  if (model.is_nonlinear()) {
    AugmentedLagrangianOde ode(*model.system, model.u0, augmented_lagrangian_parameters(model));
    run_first_order(
        model, [&](double t, const Eigen::VectorXd& y) { return ode.multipliers(t, y); },
        [&](const Eigen::VectorXd& y0, const IntegratorOptions& o, SolveSummary& s) {
          return integrate_ode(ode, y0, o, s);
        },
        run);
    return;
  }
  PenaltyOde ode(*model.system, weights);
  run_first_order(
      model, [&](double t, const Eigen::VectorXd& y) { return ode.multipliers(t, y); },
      [&](const Eigen::VectorXd& y0, const IntegratorOptions& o, SolveSummary& s) {
        return integrate(ode, y0, o, s);
      },
      run);
}

}  // namespace condyn
