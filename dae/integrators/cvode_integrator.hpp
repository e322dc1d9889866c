#pragma once
/// The only place that talks to SUNDIALS CVODE: BDF with Newton on the problem's own Newton
/// systems (OdeProblem::newton_system; a dense difference-quotient Jacobian for a problem without
/// one), and CVODE's projection after every step (CVodeSetProjFn,
/// with the error estimate projected too); a non-stiff problem (OdeProblem::non_stiff) by Adams
/// with functional iteration. Same loop as IDA (dae/integrators/step_driver.hpp).

#include "dae/integrators/passage_bridge.hpp"
#include "dae/integrators/step_driver.hpp"
#include "dae/interface/ode_problem.hpp"

namespace condyn {

/// Integrates y' = F(t, y) from y0 at options.output_times.front(). Fills the summary (the number
/// of projections goes into notes). Throws IntegrationError on solver failure. With a `bridge`
/// (its restart_at set here), singular configurations are crossed by its steps
/// (dae/integrators/passage_bridge.hpp).
[[nodiscard]] RawTrajectory integrate_ode(OdeProblem& problem, const Eigen::VectorXd& y0,
                                          const IntegratorOptions& options, SolveSummary& summary,
                                          const PassageBridge* bridge = nullptr);

}  // namespace condyn
