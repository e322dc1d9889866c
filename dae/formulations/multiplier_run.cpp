#include <algorithm>
#include <optional>

#include "dae/formulations/eliminated_system.hpp"
#include "dae/formulations/multiplier_dae.hpp"
#include "dae/formulations/row_multipliers.hpp"
#include "dae/formulations/scheme_run.hpp"
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
  std::optional<EliminatedSystem> reduced, observer;
  if (mixed && !mixed->eliminated.empty()) {
    reduced.emplace(model, *mixed);
    observer.emplace(*reduced);  // its own evaluator, for the outputs
  }
  const bool is_mixed = reduced.has_value();
  const MechanicalSystem& system =
      is_mixed ? static_cast<const MechanicalSystem&>(*reduced) : *model.system;
  MultiplierDae dae(system, scheme, gains.alpha, gains.beta, !model.nonlinear);
  const int n = system.dofs();
  Observation observe;
  if (is_mixed) {
    observe.full_state = [&](double t, const Eigen::VectorXd& y) {
      return observer->expand(t, y.head(n), y.segment(n, n));
    };
    observe.multipliers = [&](double t, const Eigen::VectorXd& y, const Eigen::VectorXd& yp,
                              const Eigen::VectorXd&, const Eigen::VectorXd&) {
      return observer->multipliers(t, y.head(n), y.segment(n, n), yp.segment(n, n), dae.lambda(y));
    };
  } else {
    observe.full_state = full_state_prefix(n);
    observe.multipliers = [&](double, const Eigen::VectorXd& y, const Eigen::VectorXd&,
                              const Eigen::VectorXd&,
                              const Eigen::VectorXd&) { return Eigen::VectorXd(dae.lambda(y)); };
  }
  std::optional<AccelerationLevelMultipliers> at_rows;
  // Under the mixed treatment even without kept rows: the eliminated rows' λ follow from the
  // reduced u'', which the integrator only interpolates between steps.
  if (row_multipliers && (is_mixed || system.constraints() > 0))
    at_rows.emplace(system, !model.nonlinear);
  if (at_rows) observe_row_multipliers(*at_rows, observer ? &*observer : nullptr, n, observe);
  double max_mu = 0.0;
  observe.on_state = [&](const Eigen::VectorXd& y) {
    if (dae.mu(y).size() > 0) max_mu = std::max(max_mu, dae.mu(y).cwiseAbs().maxCoeff());
  };
  if (scheme == Scheme::ggl) observe.on_finish = [&](SolveSummary& s) { s.max_abs_mu = max_mu; };
  const Eigen::VectorXd y0 =
      is_mixed ? dae.pack(reduced->restrict(model.u0), reduced->restrict(model.v0))
               : dae.pack(model.u0, model.v0);
  run([&](const IntegratorOptions& o, SolveSummary& s) { return integrate(dae, y0, o, s); },
      observe);
}

}  // namespace condyn
