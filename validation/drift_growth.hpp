#pragma once
/// How the constraint drift grows over a run: the exponent p of drift ∝ t^p, fitted to the
/// running maximum of the position drift at every internal step, next to what theory predicts
/// (reference/external-benchmarks.md §4: index 1 like t², index 2 like t, GGL, index 3 and the
/// stabilized schemes bounded).

#include <optional>
#include <string>
#include <vector>

#include "dae/trajectory.hpp"
#include "models/scene_spec.hpp"

namespace condyn {

struct DriftGrowth {
  double exponent = 0.0;  ///< least-squares slope of log(running max drift) against log t
  int points = 0;         ///< steps used
  double t_from = 0.0, t_to = 0.0;
};

/// Fits over the steps with t >= t_from (default: the last 99% of the run on a log scale) where
/// the running maximum exceeds `floor` (drift at roundoff carries no growth law). Nothing when
/// fewer than 10 such steps exist.
[[nodiscard]] std::optional<DriftGrowth> fit_drift_growth(const std::vector<StepRecord>& steps,
                                                          double floor = 1e-15);

/// What theory predicts for the scheme's position drift, in words ("t^2", "bounded", ...).
[[nodiscard]] std::string predicted_drift_growth(Scheme scheme);

}  // namespace condyn
