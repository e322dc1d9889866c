#pragma once
/// The only place that talks to SUNDIALS IDA. Integrates a DaeProblem from consistent initial
/// values to every output time, stopping and re-initialising at load steps.

#include <stdexcept>

#include "dae/integrators/passage_bridge.hpp"
#include "dae/integrators/step_driver.hpp"
#include "dae/interface/dae_problem.hpp"
#include "dae/interface/solve_summary.hpp"

namespace condyn {

/// Integrates F(t, y, y') = 0 from (options.output_times.front(), y0) to the last output time.
/// The differential part of y0 must be consistent; algebraic components and y'(0) come from
/// problem.make_consistent. Fills the counters and the wall
/// time of `summary`. Throws IntegrationError on solver failure, std::invalid_argument on bad
/// options. With a `bridge` (its restart_at set here), singular configurations are crossed by
/// its steps (dae/integrators/passage_bridge.hpp).
[[nodiscard]] RawTrajectory integrate(DaeProblem& problem, const Eigen::VectorXd& y0,
                                      const IntegratorOptions& options, SolveSummary& summary,
                                      const PassageBridge* bridge = nullptr);

}  // namespace condyn
