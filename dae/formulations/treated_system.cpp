#include "dae/formulations/treated_system.hpp"

namespace condyn {

TreatedSystem::TreatedSystem(const Model& model, const ConstraintTreatment* mixed) : model_(model) {
  if (mixed && !mixed->eliminated.empty()) {
    reduced_.emplace(model, *mixed);
    observer_.emplace(*reduced_);
  }
}

const MechanicalSystem& TreatedSystem::system() const {
  return reduced_ ? static_cast<const MechanicalSystem&>(*reduced_) : *model_.system;
}

Eigen::VectorXd TreatedSystem::initial(const Eigen::VectorXd& x) const {
  return reduced_ ? reduced_->restrict(x) : x;
}

void TreatedSystem::observe(const KeptMultipliers& lambda, bool row_multipliers,
                            Observation& observe) {
  const int n = system().dofs();
  if (observer_) {
    EliminatedSystem& observer = *observer_;
    observe.full_state = [&observer, n](double t, const Eigen::VectorXd& y) {
      return observer.expand(t, y.head(n), y.segment(n, n));
    };
    observe.multipliers = [&observer, n, lambda](double t, const Eigen::VectorXd& y,
                                                 const Eigen::VectorXd& yp, const Eigen::VectorXd&,
                                                 const Eigen::VectorXd&) {
      return observer.multipliers(t, y.head(n), y.segment(n, n), yp.segment(n, n), lambda(y));
    };
  } else {
    observe.full_state = full_state_prefix(n);
    observe.multipliers = [lambda](double, const Eigen::VectorXd& y, const Eigen::VectorXd&,
                                   const Eigen::VectorXd&,
                                   const Eigen::VectorXd&) { return lambda(y); };
  }
  // Under the mixed treatment even without kept rows: the eliminated rows' λ follow from the
  // reduced u'', which the integrators only interpolate between steps.
  if (row_multipliers && (mixed() || system().constraints() > 0)) {
    at_rows_.emplace(system(), !model_.nonlinear);
    observe_row_multipliers(*at_rows_, observer_ ? &*observer_ : nullptr, n, observe);
  }
}

}  // namespace condyn
