#include "dae/formulations/scheme_run.hpp"
#include "dae/integrators/ida_integrator.hpp"

namespace condyn {

void run_penalty(const Model& model, const PenaltyWeights& weights, const ObservedRun& run) {
  PenaltyOde ode(*model.system, weights);  // linear models only (scheme_refusal)
  Observation observe;
  observe.full_state = full_state_prefix(model.dofs());
  observe.multipliers = [&](double t, const Eigen::VectorXd& y, const Eigen::VectorXd&,
                            const Eigen::VectorXd&,
                            const Eigen::VectorXd&) { return ode.multipliers(t, y); };
  Eigen::VectorXd y0(2 * model.dofs());
  y0 << model.u0, model.v0;
  run([&](const IntegratorOptions& o, SolveSummary& s) { return integrate(ode, y0, o, s); },
      observe);
}

}  // namespace condyn
