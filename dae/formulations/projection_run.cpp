#include "dae/formulations/generalized_alpha_bridge.hpp"
#include "dae/formulations/projected_ode.hpp"
#include "dae/formulations/scheme_run.hpp"
#include "dae/integrators/cvode_integrator.hpp"

namespace condyn {

namespace {
/// The conditioning, as a fraction of the run's best, at which CVODE takes over from a bridge
/// (PassageBridge::exit_fraction): a restart at the passage threshold, 0.05, crawls.
constexpr double kProjectionBridgeExit = 0.25;
}  // namespace

void run_projection(const Model& model, const ObservedRun& run) {
  ProjectedOde ode(*model.system, model.u0, !model.nonlinear, &model);
  run_first_order(
      model, [&](double t, const Eigen::VectorXd& y) { return ode.multipliers(t, y); },
      [&](const Eigen::VectorXd& y0, const IntegratorOptions& o, SolveSummary& s) {
        if (!model.nonlinear || !o.bridge_singular) return integrate_ode(ode, y0, o, s);
        // A's rank can change along the motion: singular configurations are bridged.
        PassageBridge bridge = generalized_alpha_bridge(*model.system, false, o);
        bridge.exit_fraction = kProjectionBridgeExit;
        return integrate_ode(ode, y0, o, s, &bridge);
      },
      run);
}

}  // namespace condyn
