#include <algorithm>

#include "dae/formulations/generalized_alpha_bridge.hpp"
#include "dae/formulations/multiplier_dae.hpp"
#include "dae/formulations/row_multipliers.hpp"
#include "dae/formulations/scheme_run.hpp"
#include "dae/formulations/treated_system.hpp"
#include "dae/integrators/ida_integrator.hpp"

namespace condyn {

void observe_row_multipliers(AccelerationLevelMultipliers& at_rows, EliminatedSystem* observer,
                             int n, Observation& observe) {
  observe.row_multipliers = [&at_rows, observer, n, own = observe.multipliers](
                                double t, const Eigen::VectorXd& y, const Eigen::VectorXd& yp,
                                const Eigen::VectorXd& u, const Eigen::VectorXd& v) {
    const Eigen::VectorXd q = y.head(n), w = y.segment(n, n);
    const auto solved = at_rows(t, q, w);
    if (!solved) return own(t, y, yp, u, v);
    if (observer) return observer->multipliers(t, q, w, solved->first, solved->second);
    return solved->second;
  };
}

void run_multipliers(const Model& model, Scheme scheme, const BaumgarteGains& gains,
                     const ConstraintTreatment* mixed, bool row_multipliers,
                     const ObservedRun& run) {
  TreatedSystem treated(model, mixed);
  const MechanicalSystem& system = treated.system();
  MultiplierDae dae(system, scheme, gains.alpha, gains.beta, !model.nonlinear);
  Observation observe;
  treated.observe([&dae](const Eigen::VectorXd& y) { return Eigen::VectorXd(dae.lambda(y)); },
                  row_multipliers, observe);
  double max_mu = 0.0;
  observe.on_state = [&](const Eigen::VectorXd& y) {
    if (dae.mu(y).size() > 0) max_mu = std::max(max_mu, dae.mu(y).cwiseAbs().maxCoeff());
  };
  if (scheme == Scheme::ggl) observe.on_finish = [&](SolveSummary& s) { s.max_abs_mu = max_mu; };
  const Eigen::VectorXd y0 = dae.pack(treated.initial(model.u0), treated.initial(model.v0));
  run(
      [&](const IntegratorOptions& o, SolveSummary& s) {
        if (!model.nonlinear || !o.bridge_singular) return integrate(dae, y0, o, s);
        // A's rank can change along the motion: singular configurations are bridged.
        const PassageBridge bridge = generalized_alpha_bridge(system, false, o);
        return integrate(dae, y0, o, s, &bridge);
      },
      observe);
}

}  // namespace condyn
