// RATTLE's runner: the stepper of dae/integrators/rattle_stepper.hpp on the model's own system,
// its state [u; v; μ] observed as the other schemes' (reactions from acceleration level at the
// output rows when asked for, as under the multiplier schemes).

#include <optional>

#include "dae/formulations/row_multipliers.hpp"
#include "dae/formulations/scheme_run.hpp"
#include "dae/integrators/rattle_stepper.hpp"

namespace condyn {

void run_rattle(const Model& model, double step, bool row_multipliers, const ObservedRun& run) {
  const int n = model.dofs(), m = model.constraint_count();
  Observation observe;
  observe.full_state = full_state_prefix(n);
  observe.multipliers = [m](double, const Eigen::VectorXd& y, const Eigen::VectorXd&,
                            const Eigen::VectorXd&, const Eigen::VectorXd&) {
    return Eigen::VectorXd(y.tail(m));  // y = [u; v; μ]
  };
  std::optional<AccelerationLevelMultipliers> at_rows;
  if (row_multipliers && m > 0) {
    at_rows.emplace(*model.system, !model.nonlinear);
    observe_row_multipliers(*at_rows, nullptr, n, observe);
  }
  run(
      [&](const IntegratorOptions& o, SolveSummary& s) {
        const WallTimer timer(s);
        RattleStepper stepper(*model.system, RattleSettings{o.rtol, o.atol}, step,
                              o.output_times.front(), model.u0, model.v0);
        s.unknowns = stepper.size();
        RawTrajectory out = drive(stepper, stepper.y(), stepper.yp(), o, s);
        s.jacobian_nonzeros = stepper.jacobian_nonzeros();
        s.set_reached(o.output_times.back());
        return out;
      },
      observe);
}

}  // namespace condyn
