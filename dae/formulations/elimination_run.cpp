#include "dae/formulations/multiplier_recovery.hpp"
#include "dae/formulations/scheme_run.hpp"
#include "dae/integrators/ida_integrator.hpp"

namespace condyn {

void run_elimination(const Model& model, const ReducedSystem& reduced, ReducedOde& ode,
                     const ObservedRun& run) {
  const auto& masters = reduced.transform.masters;
  const int nm = static_cast<int>(masters.size());
  Eigen::VectorXd y0(2 * nm);
  for (int k = 0; k < nm; ++k) {
    y0[k] = model.u0[masters[static_cast<std::size_t>(k)]];
    y0[nm + k] = model.v0[masters[static_cast<std::size_t>(k)]];
  }
  const auto& T = reduced.transform.T;
  const auto& G = reduced.transform.G;
  const MultiplierRecovery recover(model);
  Observation observe;
  observe.full_state = [&](double t, const Eigen::VectorXd& y) {
    Eigen::VectorXd u = T * y.head(nm), v = T * y.tail(nm);
    if (reduced.rheonomic) {
      u += G * model.position_rhs(0, t);
      v += G * model.position_rhs(1, t);
    }
    return std::make_pair(u, v);
  };
  observe.multipliers = [&](double t, const Eigen::VectorXd& y, const Eigen::VectorXd&,
                            const Eigen::VectorXd& u, const Eigen::VectorXd& v) {
    Eigen::VectorXd a = T * ode.acceleration(t, y.head(nm), y.tail(nm));
    if (reduced.rheonomic) a += G * model.position_rhs(2, t);
    return recover(t, u, v, a);
  };
  observe.drift_at_every_step = false;
  run([&](const IntegratorOptions& o, SolveSummary& s) { return integrate(ode, y0, o, s); },
      observe);
}

}  // namespace condyn
