#pragma once
/// Baumgarte stabilization replaces A u'' = γ by
///   A u'' = γ − 2α ψ − β² φ,
/// so a constraint error e obeys e'' + 2α e' + β² e = 0. The default rule, when the scene gives
/// no gains: critical damping (α = β, the error decays fastest without oscillating) on the time
/// scale of the constrained system's highest natural frequency (β = ω_max of the linearization
/// at t = 0 on the constraint manifold, the geometric stiffness of the constraint forces included:
/// dae/formulations/model_scales.hpp; a pendulum gets √(g/L)): the drift is removed as fast as the
/// physics itself moves, and no faster, so stabilization adds no stiffness beyond the model's own.
/// The gains are the model's: they never depend on output_step. When ω_max is 0 (no stiffness, no
/// force, no motion), β = 2π / t_end.

#include <optional>
#include <string>

#include "models/core/model.hpp"
#include "models/core/solve_spec.hpp"

namespace condyn {

struct BaumgarteGains {
  double alpha = 0.0, beta = 0.0;
  std::string rule;  ///< how they were chosen, printed in the summary
};

/// Gains from the run's [solve] baumgarte (either may be omitted) and the default rule above.
[[nodiscard]] BaumgarteGains baumgarte_gains(const Model& model, const SolveSpec& settings);

}  // namespace condyn
