#pragma once
/// What to try after a failed run, in one line: chosen by the failure's kind, worded from the facts
/// it carries (time reached against t0 and t_end, last step, steps, wall time), with what the
/// scheme itself adds (its gains, its weight, its drift).

#include <string>

#include "dae/run/solve_result.hpp"
#include "models/core/scheme.hpp"

namespace condyn {

[[nodiscard]] std::string failure_suggestion(Scheme scheme, const RunFailure& e);

/// After a failure of the step size (collapsed, tiny for many steps, repeated error-test or
/// convergence failures, a failure before the first step): when the displacements' atol lies
/// within 100 ulps of the largest of 1, the model's `coordinates`
/// (MechanicalSystem::coordinate_scale, which the constraint rows compute with) and the largest
/// displacement the run reached (`max_displacement`), the advice to raise it; else nothing. Without
/// it, a conical pendulum failing under GGL at atol 1e-16 was advised about singular
/// configurations and a tight rtol alone.
[[nodiscard]] std::string roundoff_advice(const RunFailure& e, double atol, double max_displacement,
                                          double coordinates);

}  // namespace condyn
