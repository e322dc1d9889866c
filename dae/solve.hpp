#pragma once
/// Scheme choice and dispatch: the one entry point the CLI and the validation suite use.

#include <optional>
#include <string>

#include "dae/solve_summary.hpp"
#include "dae/trajectory.hpp"
#include "models/model.hpp"

namespace condyn {

struct SchemeChoice {
  Scheme scheme = Scheme::elimination;
  std::string reason;  ///< why this scheme (printed by `condyn info`)
};

/// Why `scheme` cannot treat this model (elimination and penalty on nonlinear models), or
/// nothing when it can.
[[nodiscard]] std::optional<std::string> scheme_refusal(const Model& model, Scheme scheme);

/// Resolves `requested` (auto picks the lightest formulation that serves the model).
[[nodiscard]] SchemeChoice choose_scheme(const Model& model, Scheme requested);

/// What a scheme makes the integrator solve for this model.
struct SystemSize {
  int unknowns = 0;
  long jacobian_nonzeros = 0;
};

/// Builds the scheme's DAE (without integrating) and sizes it. Throws like solve() would.
[[nodiscard]] SystemSize system_size(const Model& model, Scheme scheme);

/// Integrator options from the model's [solve] section, possibly overridden by the caller.
[[nodiscard]] IntegratorOptions integrator_options(const Model& model);

/// Solves the model under `scheme` (not `automatic`). Throws std::invalid_argument for a scheme
/// this build cannot run yet, IntegrationError on solver failure.
[[nodiscard]] Trajectory solve(const Model& model, Scheme scheme, const IntegratorOptions& options,
                               SolveSummary& summary);

}  // namespace condyn
