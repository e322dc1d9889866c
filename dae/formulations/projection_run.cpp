#include "dae/formulations/projected_ode.hpp"
#include "dae/formulations/scheme_run.hpp"
#include "dae/integrators/cvode_integrator.hpp"

namespace condyn {

void run_projection(const Model& model, const ObservedRun& run) {
  ProjectedOde ode(*model.system, model.u0, !model.nonlinear, &model);
  run_first_order(
      model, [&](double t, const Eigen::VectorXd& y) { return ode.multipliers(t, y); },
      [&](const Eigen::VectorXd& y0, const IntegratorOptions& o, SolveSummary& s) {
        return integrate_ode(ode, y0, o, s);
      },
      run);
}

}  // namespace condyn
