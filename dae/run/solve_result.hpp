#pragma once
/// What a run returns, as data: the trajectory, the integrator's summary and, when the run failed,
/// the failure with the facts the caller needs to report it (the CLI decides what to write).

#include <optional>
#include <string>

#include "dae/integrators/step_driver.hpp"
#include "dae/interface/solve_summary.hpp"
#include "dae/run/trajectory.hpp"
#include "models/core/scheme.hpp"

namespace condyn {

/// A run that stopped before t_end (or never started).
struct RunFailure {
  FailureKind kind = FailureKind::unknown;
  std::string message;   ///< what failed, in the integrator's words (call, flag, time, reason)
  bool in_loop = false;  ///< the failure arose inside the integration loop: the fields below hold
  double t0 = 0.0, t_end = 0.0;  ///< the run's start and end
  double t_reached = 0.0;        ///< the last time the integrator reached successfully
  double last_step = 0.0;        ///< the last step size it took (0: none)
  long steps = 0;                ///< internal steps before the failure
  double elapsed_seconds = 0.0;  ///< wall time of the loop before the failure
  std::string suggestion;        ///< what to try instead (failure_suggestion)
};

/// The facts an IntegrationError carries, as a RunFailure (without a suggestion).
[[nodiscard]] RunFailure failure_of(const IntegrationError& e);

struct SolveResult {
  Scheme scheme = Scheme::automatic;  ///< the scheme that ran (automatic resolved)
  /// Every output row; after a failure, the rows before it when the loop had gone past the
  /// initial one (empty otherwise, or when they could not be assembled).
  Trajectory trajectory;
  SolveSummary summary;
  std::optional<RunFailure> failure;  ///< set when the run did not reach t_end
  [[nodiscard]] bool ok() const { return !failure; }
};

/// For callers to whom a failed run is an error (the validation suite, tests): `result` itself, or
/// std::runtime_error with the failure's message. Keep the result in a variable: the reference
/// returned is the argument.
const SolveResult& succeeded(const SolveResult& result);

/// A failed run's message: "under SCHEME (KIND): what failed", then, indented on their own lines,
/// where the loop stopped and what to try. For the CLI's error line and the Python module.
[[nodiscard]] std::string describe_failure(const SolveResult& result, double t_end);

}  // namespace condyn
