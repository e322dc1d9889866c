// The Newmark family's runner: the stepper of dae/integrators/newmark_stepper.hpp on the model's
// own system, its state [u; v; λ] observed as the other schemes' (λ at a step is the step's own
// multiplier, an index-3 unknown held with the positions; at the output rows, when reactions are
// asked for, λ from acceleration level at the row's u and v, as the multiplier schemes report:
// the step's own carries the constraint modes' step-to-step oscillation, undamped under average
// acceleration, and an O(h) start-up transient where a constraint moves (docs/schemes.md)).

#include <memory>

#include "dae/formulations/row_multipliers.hpp"
#include "dae/formulations/scheme_run.hpp"
#include "dae/integrators/newmark_stepper.hpp"

namespace condyn {

void run_newmark(const Model& model, const AlphaParameters& parameters, double step,
                 bool row_multipliers, const ObservedRun& run) {
  const int n = model.dofs(), m = model.constraint_count();
  Observation observe;
  observe.full_state = full_state_prefix(n);
  observe.multipliers = [m](double, const Eigen::VectorXd& y, const Eigen::VectorXd&,
                            const Eigen::VectorXd&, const Eigen::VectorXd&) {
    return Eigen::VectorXd(y.tail(m));  // y = [u; v; λ]
  };
  const bool linear = !model.nonlinear;
  std::shared_ptr<AccelerationLevelMultipliers> at_rows;
  if (row_multipliers && m > 0) {
    at_rows = std::make_shared<AccelerationLevelMultipliers>(*model.system, linear);
    observe.row_multipliers = [at_rows, n, own = observe.multipliers](
                                  double t, const Eigen::VectorXd& y, const Eigen::VectorXd& yp,
                                  const Eigen::VectorXd& u, const Eigen::VectorXd& v) {
      const auto solved = (*at_rows)(t, y.head(n), y.segment(n, n));
      return solved ? solved->second : own(t, y, yp, u, v);
    };
  }
  run(
      [&](const IntegratorOptions& o, SolveSummary& s) {
        const WallTimer timer(s);
        auto consistent = std::make_shared<AccelerationLevelMultipliers>(*model.system, linear);
        NewmarkSettings settings{parameters, step, o.rtol, o.atol};
        NewmarkStepper stepper(
            *model.system, linear, settings,
            [consistent](double t, const Eigen::VectorXd& u, const Eigen::VectorXd& v) {
              return (*consistent)(t, u, v);
            },
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
