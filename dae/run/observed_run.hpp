#pragma once
/// One observed integration for every scheme: the constraint drift at every internal step (where
/// the scheme's equations hold exactly) and at the outputs (interpolated), a per-step drift log
/// when asked for, the trajectory assembled in full DOF space with its multipliers, and, when the
/// integrator fails, the failure as data with the rows computed before it.

#include "dae/formulations/scheme_run.hpp"
#include "dae/run/solve_result.hpp"
#include "models/core/model.hpp"

namespace condyn {

/// Runs `integrate` with a per-step observer added to `options` and returns the result: the
/// trajectory assembled in full DOF space, and `summary` (the scheme and the notes set before the
/// run) with the integrator's counters and the drifts, whose maxima cover the steps observed and
/// the outputs. When the integrator fails (IntegrationError), the result's failure holds its facts
/// and its trajectory the rows before it (when there is more than the initial one).
[[nodiscard]] SolveResult run_observed(const Model& model, const IntegratorOptions& options,
                                       const Integrate& integrate, const Observation& observe,
                                       SolveSummary summary);

}  // namespace condyn
