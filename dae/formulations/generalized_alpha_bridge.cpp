#include "dae/formulations/generalized_alpha_bridge.hpp"

#include <memory>

#include "dae/formulations/row_multipliers.hpp"
#include "dae/integrators/newmark_stepper.hpp"
#include "dae/linsolve/constraint_conditioning.hpp"
#include "models/core/newmark_parameters.hpp"

namespace condyn {

PassageBridge generalized_alpha_bridge(const MechanicalSystem& system, bool linear,
                                       const IntegratorOptions& options) {
  const Eigen::Index n = system.dofs();
  auto consistent = std::make_shared<AccelerationLevelMultipliers>(system, linear);
  PassageBridge bridge;
  if (options.conditioning) {  // the run's monitor's: each state's computed once
    bridge.conditioning = options.conditioning;
  } else {
    auto conditioning = std::make_shared<ConstraintConditioning>(system);
    bridge.conditioning = [conditioning, n](double t, const Eigen::VectorXd& y) {
      return (*conditioning)(t, y.head(n));
    };
  }
  const NewmarkSettings settings{generalized_alpha_parameters(kDefaultRhoInf), 0.0, options.rtol,
                                 options.atol_of(UnknownKind::displacement)};
  bridge.start = [&system, linear, settings, consistent, n](double t, const Eigen::VectorXd& y,
                                                            double h) -> std::unique_ptr<Stepper> {
    NewmarkSettings fixed = settings;
    fixed.step = h;
    fixed.step_advice.clear();
    return std::make_unique<NewmarkStepper>(
        system, linear, fixed,
        [consistent](double s, const Eigen::VectorXd& u, const Eigen::VectorXd& v) {
          return (*consistent)(s, u, v);
        },
        t, y.head(n), y.segment(n, n));
  };
  return bridge;
}

}  // namespace condyn
