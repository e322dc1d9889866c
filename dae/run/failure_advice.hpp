#pragma once
/// What to try after a failed run, in one line: chosen by the failure's kind, worded from the facts
/// it carries (time reached against t0 and t_end, last step, steps, wall time), with what the
/// scheme itself adds (its gains, its weight, its drift).

#include <string>

#include "dae/run/solve_result.hpp"
#include "models/core/scheme.hpp"

namespace condyn {

/// What the advice needs to know of the run beyond its scheme.
struct AdviceContext {
  /// The model's constraints or forces are nonlinear (under penalty, the augmented Lagrangian
  /// ran, its weight set from the model).
  bool nonlinear_model = false;
  /// The Newmark family or rattle ran with a fixed [solve] step (else the Newmark family's steps
  /// were controlled by its error estimate).
  bool fixed_step = false;
  /// The Newmark family ran at index 3 with parameters that damp no high frequency (ρ∞ = 1:
  /// average acceleration, hht with α = 0, generalized_alpha with ρ∞ = 1): on a mechanism the
  /// multipliers' oscillation grows and the steps shrink without end.
  bool undamped_index3 = false;
};

[[nodiscard]] std::string failure_suggestion(Scheme scheme, const RunFailure& e,
                                             const AdviceContext& context = {});

/// The same, for a failure that `causes` (what roundoff_advice and mu_roundoff_advice return,
/// joined) may explain: when they are not empty, a collapse or repeated convergence or error-test
/// failures are put down to the tolerance they name, with no guess at singular configurations
/// (a hanging chain of 30,000 links under GGL got that guess while its atol_mu asked for less than
/// roundoff); the other kinds keep their own advice with the causes after it.
[[nodiscard]] std::string failure_suggestion(Scheme scheme, const RunFailure& e,
                                             const std::string& causes,
                                             const AdviceContext& context = {});

/// After a failure of the step size (collapsed, tiny for many steps, repeated error-test or
/// convergence failures, a failure before the first step): when the displacements' atol lies
/// within 100 ulps of the largest of 1, the model's `coordinates`
/// (MechanicalSystem::coordinate_scale, which the constraint rows compute with) and the largest
/// displacement the run reached (`max_displacement`), the advice to raise it; else nothing. Without
/// it, a conical pendulum failing under GGL at atol 1e-16 was advised about singular
/// configurations and a tight rtol alone.
[[nodiscard]] std::string roundoff_advice(const RunFailure& e, double atol, double max_displacement,
                                          double coordinates);

/// After a failure of the kinds roundoff_advice takes, under GGL: when atol_mu (a scene's: the
/// derived one is never below it) lies below `mu_floor`, the smallest the constraint rows'
/// roundoff allows (AbsoluteTolerances::mu_floor), the advice to raise `[solve] atol_mu` to it;
/// else nothing.
[[nodiscard]] std::string mu_roundoff_advice(const RunFailure& e, double atol_mu, double mu_floor);

}  // namespace condyn
