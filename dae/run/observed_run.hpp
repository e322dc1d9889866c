#pragma once
/// One observed integration for every scheme: the constraint drift at every internal step (where
/// the scheme's equations hold exactly) and at the outputs (interpolated), a per-step drift log
/// when asked for, the trajectory assembled in full DOF space with its multipliers, and, when the
/// integrator fails, the failure as data with the rows computed before it.

#include <Eigen/Dense>
#include <functional>
#include <utility>

#include "dae/run/solve_result.hpp"
#include "models/core/model.hpp"

namespace condyn {

/// How a scheme's state y maps to what the model observes.
struct Observation {
  using FullState = std::function<std::pair<Eigen::VectorXd, Eigen::VectorXd>(
      double t, const Eigen::VectorXd& y)>;
  /// u and u' in full DOF space at (t, y).
  FullState full_state;
  /// λ at an output (t, y, y'), whose full-space u and u' are given.
  std::function<Eigen::VectorXd(double t, const Eigen::VectorXd& y, const Eigen::VectorXd& yp,
                                const Eigen::VectorXd& u, const Eigen::VectorXd& v)>
      multipliers;
  /// λ at an output row, when it differs from `multipliers` (which the energy balance's
  /// integrand keeps at every quadrature point); optional.
  std::function<Eigen::VectorXd(double t, const Eigen::VectorXd& y, const Eigen::VectorXd& yp,
                                const Eigen::VectorXd& u, const Eigen::VectorXd& v)>
      row_multipliers;
  /// Further per-step observation of y (GGL's μ); optional.
  std::function<void(const Eigen::VectorXd& y)> on_state;
  /// Measure the drift at every internal step even without a drift log (the multiplier schemes,
  /// whose drift between outputs is what they are judged by). Elimination satisfies the
  /// constraints by construction and pays for the per-step map only when a log is asked for.
  bool drift_at_every_step = true;
};

/// Runs `run` with a per-step observer added to `options` and assembles the trajectory into
/// result.trajectory; the summary's max drifts cover the steps observed and the outputs. When the
/// integrator fails (IntegrationError), result.failure holds its facts and result.trajectory the
/// rows before it (when there is more than the initial one). `run` fills result.summary's counters.
void run_observed(const Model& model, const IntegratorOptions& options,
                  const std::function<RawTrajectory(const IntegratorOptions&)>& run,
                  const Observation& observe, SolveResult& result);

/// The full-state map of a scheme whose state starts with [u; v] (every scheme but elimination).
[[nodiscard]] Observation::FullState full_state_prefix(int n);

}  // namespace condyn
