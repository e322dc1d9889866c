#pragma once
/// How the constraint drift grows over a run: the exponent p of drift ∝ t^p, fitted to the
/// running maximum of the position drift at every internal step, next to what theory predicts
/// (reference/external-benchmarks.md §4: index 1 like t², index 2 like t, GGL, index 3 and the
/// stabilized schemes bounded).

#include <optional>
#include <string>
#include <vector>

#include "dae/run/trajectory.hpp"
#include "models/core/scheme.hpp"

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

/// Whether a growth law can be read off a run, and which. A fit is shown only where it means
/// something: the running maximum of the drift must exceed roundoff (`floor`) over at least one
/// decade of time with enough steps, and follow a steady power law there, i.e. the exponent
/// fitted over each quarter (log time) of that window lies within `kSteadyExponentSpread` of the
/// whole window's; and the run must span at least `kMinOscillations` oscillations of the motion
/// (half the sign changes of the fastest-reversing velocity over the internal steps): growth laws
/// describe long runs, not one swing of a mechanism. Otherwise `reason` says why nothing was
/// fitted. Calibrated on the period-2 pendulum over 1000 periods (quarters of
/// index1: 2.10, 1.71, 2.32, 2.06; of GGL: 0.31, 0.72, 0.00, 0.16) against runs that are transients
/// (the inclined roller's GGL drift rises from 1e-28 to its Newton-tolerance bound within 8 s:
/// quarters 9.4, 21.6, 0.79, 0.50; Andrews over 0.03 s, one revolution: 4.2, 0.12, 4.5, 1.4).
struct DriftGrowthAssessment {
  std::optional<DriftGrowth> fit;         ///< set only when meaningful
  std::string reason;                     ///< why there is no fit (empty when there is one)
  std::vector<double> quarter_exponents;  ///< the steadiness check's figures, when computed
};

inline constexpr double kSteadyExponentSpread = 1.0;
inline constexpr double kMinDecades = 1.0;
inline constexpr int kMinStepsPerQuarter = 5;
inline constexpr double kMinOscillations = 10.0;

/// `floor`: the drift below which it is roundoff, e.g. 64 eps times the largest |u| of the run.
/// `oscillations`: those of the motion when counted elsewhere (compare counts them once for all
/// its schemes); by default half the velocity sign changes of `steps`.
[[nodiscard]] DriftGrowthAssessment assess_drift_growth(
    const std::vector<StepRecord>& steps, double floor,
    std::optional<double> oscillations = std::nullopt);

/// What theory predicts for the scheme's position drift, in words ("t^2", "bounded", ...).
[[nodiscard]] std::string predicted_drift_growth(Scheme scheme);

}  // namespace condyn
