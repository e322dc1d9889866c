#pragma once
/// The Newmark family's error control (dae/integrators/newmark_stepper.hpp without a fixed step):
/// the local error estimate of Zienkiewicz and Xie (1991, "A simple error estimator and adaptive
/// time stepping procedure for dynamic analysis", Earthquake Eng. Struct. Dyn. 20, 871-887) and
/// the step-size rules around it.
///
/// The estimate: the step's displacement formula u_{n+1} = u_n + h v_n + h² [(½ − β) a_n +
/// β a_{n+1}] against Taylor's expansion of the exact solution leaves the local error
/// (β − 1/6) h³ u''' + O(h⁴), and u''' ≈ (a_{n+1} − a_n) / h, so
///
///   e_{n+1} = (β − 1/6) h² (a_{n+1} − a_n),
///
/// from the step's own results at no extra cost. u''' is taken from the mean accelerations of this
/// step and the one before, ā = (v_{n+1} − v_n)/h, which approximate ü at the steps' midpoints
/// for every second-order member (γ = ½ − αm + αf): u''' ≈ 2 (ā_n − ā_{n−1}) / (h_n + h_{n−1}).
/// Not from the algorithmic accelerations a, as Zienkiewicz and Xie do: at index 3 a carries a
/// spurious alternating mode, undamped under average acceleration (ρ∞ = 1), which the velocities
/// average out (with it, a pendulum's steps shrank to 3e-8 under newmark). Without a step before
/// (the start, a restart, where a = ü), u''' ≈ (a_{n+1} − a_n)/h. Every accepted parameter set
/// has β ≥ γ/2 ≥ ¼ (models/core/newmark_parameters.hpp), so the factor β − 1/6 never vanishes.

#include <Eigen/Dense>

namespace condyn {

/// The step's ends and the step before it, what the estimate is made of (n each).
struct StepHistory {
  double h = 0.0, h_before = 0.0;  ///< this step and the one before (0: none, a restart)
  const Eigen::VectorXd *v_before, *v_old, *v_new;  ///< v at t_{n−1}, t_n, t_{n+1}
  const Eigen::VectorXd *a_old, *a_new;             ///< algorithmic accelerations at t_n, t_{n+1}
};

/// The estimate e above in the weighted root-mean-square norm of IDA's error test,
/// sqrt(mean_i (e_i / (rtol |u_n,i| + atol))²), with the displacements' rtol and atol: a step is
/// accepted when it is at most 1. `u_old`: the displacements at the step's start.
[[nodiscard]] double zienkiewicz_xie_norm(double beta, const StepHistory& s,
                                          const Eigen::VectorXd& u_old, double rtol, double atol);

/// The step-size rules of the controlled Newmark family (the error is O(h³): exponent 1/3).
struct NewmarkStepRules {
  static constexpr double kSafety = 0.9;     ///< the step aims at 0.9 of the allowed error
  static constexpr double kMaxGrowth = 2.0;  ///< at most doubled after a step (IDA's limit)
  static constexpr double kMinShrink = 0.2;  ///< at least a fifth of the rejected step
  /// A growth below this factor is not taken: a linear model's matrix depends on the step alone
  /// and keeps its factors while the step stays.
  static constexpr double kHoldBelow = 1.2;
  static constexpr double kNewtonCut = 0.25;  ///< the step after a Newton failure (IDA's cut)
  static constexpr int kMaxFailures = 10;     ///< failed attempts at one step (IDA's maxnef)
  /// A step that ends within this fraction of h before the stop time goes to the stop time.
  static constexpr double kStretch = 0.1;
  /// The smallest step, relative to the time: a few thousand ulps, the loop's collapsed step.
  static constexpr double kMinStepRelative = 1e-12;
  static constexpr double kNewtonFraction = 1e-3;  ///< newmark_newton_fraction
  /// A linear model's factors serve steps whose β' (∝ 1/h²) is within this factor of theirs
  /// (StepNewton::set_stale_ratio): h within about ±20 %, where Newton's iterations on them
  /// contract by |1 − β'_factored/β'| ≤ 0.5 on the stiffest modes.
  static constexpr double kStaleRatio = 1.5;
  /// Iterations on stale factors before the step factors its own matrix.
  static constexpr int kStaleIterations = 6;
  /// Halvings of a Newton correction whose full length would raise the residual's norm
  /// (NewmarkStepper::solve_step): down to 1/1024 of it.
  static constexpr int kMaxHalvings = 10;
  /// Armijo's sufficient decrease: a correction of length θ (1, ½, ¼ …) must lower the residual's
  /// norm to at most (1 − 0.1 θ) of it.
  static constexpr double kSufficientDecrease = 0.1;
};

/// The step after one of size h whose error norm was `error` (≥ 0): h · 0.9 (1/error)^(1/3),
/// within [kMinShrink, kMaxGrowth] · h, at most h when `no_growth` (the step was just rejected),
/// and h itself for a growth below kHoldBelow.
[[nodiscard]] double next_newmark_step(double h, double error, bool no_growth);

/// The fraction of the tolerance Newton's weighted increment must reach under error control:
/// kNewtonFraction = 1e-3, or 100 eps / rtol where that is larger (the increments' roundoff), at
/// most 1. At index 3 an error ε left in u by Newton puts ε/(γ'h) into v (and ε/(βh²) into a and
/// λ: Bottasso, Bauchau and Cardona 2008), which the estimate would see at about the size ε: it
/// is kept far below the error test's tolerance, as IDA keeps its Newton test at a third of it.
[[nodiscard]] double newmark_newton_fraction(double rtol);

/// The first step from a start where the accelerations are a0 and the displacements u0: the h
/// whose estimate is the allowed error when a changes over the step by as much as its size,
/// (β − 1/6) h² ‖a0‖ = 1 in the norm above, at most `span` (the first output interval, half the
/// first kink of a tabulated load, the stop time); `span` itself when a0 vanishes.
[[nodiscard]] double first_newmark_step(double beta, const Eigen::VectorXd& a0,
                                        const Eigen::VectorXd& u0, double rtol, double atol,
                                        double span);

}  // namespace condyn
