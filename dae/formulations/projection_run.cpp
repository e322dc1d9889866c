#include "dae/formulations/projected_ode.hpp"
#include "dae/formulations/scheme_run.hpp"
#include "dae/integrators/cvode_integrator.hpp"

namespace condyn {

void run_projection(const Model& model, const ObservedRun& run) {
  ProjectedOde ode(*model.system, model.u0, !model.nonlinear, &model);
  Observation observe;
  observe.full_state = full_state_prefix(model.dofs());
  observe.multipliers = [&](double t, const Eigen::VectorXd& y, const Eigen::VectorXd&,
                            const Eigen::VectorXd&,
                            const Eigen::VectorXd&) { return ode.multipliers(t, y); };
  Eigen::VectorXd y0(2 * model.dofs());
  y0 << model.u0, model.v0;
  run([&](const IntegratorOptions& o, SolveSummary& s) { return integrate_ode(ode, y0, o, s); },
      observe);
}

}  // namespace condyn
