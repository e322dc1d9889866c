#include "dae/formulations/scheme_run.hpp"

namespace condyn {

Observation::FullState full_state_prefix(int n) {
  return [n](double, const Eigen::VectorXd& y) {
    return std::make_pair(Eigen::VectorXd(y.head(n)), Eigen::VectorXd(y.segment(n, n)));
  };
}

void run_first_order(const Model& model, const StateMultipliers& multipliers,
                     const IntegrateFrom& integrate_from, const ObservedRun& run) {
  Observation observe;
  observe.full_state = full_state_prefix(model.dofs());
  observe.multipliers = [&](double t, const Eigen::VectorXd& y, const Eigen::VectorXd&,
                            const Eigen::VectorXd&,
                            const Eigen::VectorXd&) { return multipliers(t, y); };
  Eigen::VectorXd y0(2 * model.dofs());
  y0 << model.u0, model.v0;
  run([&](const IntegratorOptions& o, SolveSummary& s) { return integrate_from(y0, o, s); },
      observe);
}

}  // namespace condyn
