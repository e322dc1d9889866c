#pragma once
/// Scheme choice and dispatch: the one entry point the CLI and the validation suite use.

#include <optional>
#include <stdexcept>
#include <string>

#include "dae/solve_summary.hpp"
#include "dae/trajectory.hpp"
#include "models/model.hpp"

namespace condyn {

struct SchemeChoice {
  Scheme scheme = Scheme::elimination;
  std::string reason;  ///< why this scheme (printed by `condyn info`)
};

/// Thrown when a scheme cannot treat a model (the reason is scheme_refusal's): the request, not the
/// solver, is at fault, so the CLI answers it as bad input (exit 2).
class SchemeNotApplicable : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
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

/// What to try after `scheme` failed with `e`, in one line: chosen by e.kind, worded from the
/// facts it carries (time reached against t0 and t_end, last step, steps, wall time).
[[nodiscard]] std::string failure_suggestion(Scheme scheme, const IntegrationError& e);

/// Integrator options from the model's [solve] section, possibly overridden by the caller.
[[nodiscard]] IntegratorOptions integrator_options(const Model& model);

/// Solves the model under `scheme` (`automatic` resolves through choose_scheme). Throws
/// SchemeNotApplicable for a scheme that cannot treat the model, IntegrationError on solver
/// failure: with the scheme, the time reached, the last step, a suggestion and, when the loop
/// had produced output rows, the partial trajectory up to the failure.
[[nodiscard]] Trajectory solve(const Model& model, Scheme scheme, const IntegratorOptions& options,
                               SolveSummary& summary);

}  // namespace condyn
