#include "dae/formulations/scheme_run.hpp"
#include "dae/integrators/ida_integrator.hpp"

namespace condyn {

void run_penalty(const Model& model, const PenaltyWeights& weights, const ObservedRun& run) {
  PenaltyOde ode(*model.system, weights);  // linear models only (scheme_refusal)
  run_first_order(
      model, [&](double t, const Eigen::VectorXd& y) { return ode.multipliers(t, y); },
      [&](const Eigen::VectorXd& y0, const IntegratorOptions& o, SolveSummary& s) {
        return integrate(ode, y0, o, s);
      },
      run);
}

}  // namespace condyn
