#pragma once
/// The Newmark family (newmark, hht, generalized_alpha) as a Stepper of the shared loop
/// (dae/integrators/step_driver.hpp): the generalized-α method of Chung and Hulbert (1993) in the
/// form of Arnold and Brüls (2007), which holds the equations of motion and the constraints at
/// t_{n+1} (index 3: positions and multipliers) and carries the algorithmic acceleration a
/// beside the true one ü:
///
///   (1 − αm) a_{n+1} + αm a_n = (1 − αf) ü_{n+1} + αf ü_n
///   u_{n+1} = u_n + h v_n + h² [(½ − β) a_n + β a_{n+1}]
///   v_{n+1} = v_n + h [(1 − γ) a_n + γ a_{n+1}]
///   M(u_{n+1}) ü_{n+1} = f(t_{n+1}, u_{n+1}, v_{n+1}) − A(u_{n+1})ᵀ λ_{n+1},  φ(u_{n+1}) = 0
///
/// For a linear model this is Chung and Hulbert's method itself (multiply the first line by M),
/// so Newmark's (αm = αf = 0) and HHT's recurrences are reproduced exactly.
///
/// Steps: the fixed step h on the grid t0 + k h; a load step or the end of the run off the grid
/// is reached by a shorter step, after which the steps return to the grid. At t0 and at every
/// load step, ü and λ are solved from the constraints at acceleration level and a = ü (a
/// restart, as BDF's). Between steps (output times off the grid, the energy balance's quadrature
/// points) u and v come from the cubic Hermite interpolant of (u, v) at the step's ends, ü and λ
/// linearly: step results exactly at the ends.
///
/// Without a fixed step (step = 0), each step is judged by the local error estimate of
/// dae/integrators/newmark_error_control.hpp, retried shorter when rejected or when Newton's
/// iterations fail, and ends on every stop time (dae/integrators/newmark_controlled_step.cpp).
///
/// The state the loop sees: y = [u; v; λ], y' = [v; ü; 0]; stabilized
/// (NewmarkSettings::constraints, dae/integrators/stabilized_newmark_newton.hpp) y = [u; v; λ; μ],
/// y' = [v; ü; 0; 0].

#include <Eigen/Dense>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <utility>

#include "dae/integrators/fixed_step_grid.hpp"
#include "dae/integrators/step_driver.hpp"
#include "dae/integrators/step_newton.hpp"
#include "models/core/mechanical_system.hpp"
#include "models/core/newmark_parameters.hpp"

namespace condyn {

/// What the stepper is given besides the system.
struct NewmarkSettings {
  AlphaParameters parameters;
  double step = 0.0;  ///< h > 0: the fixed step; 0: error-controlled steps
  /// Newton's convergence: max_i |Δu_i| / (rtol |u_i| + atol) ≤ 1. A linear model stops there
  /// or after its second iteration, a refinement of the exact first one on the same factors.
  /// The error-controlled steps use the same rtol and atol (the displacements') in their test.
  double rtol = 1e-8, atol = 1e-10;
  /// Newton stops at a weighted increment of at most this fraction of the tolerance
  /// (newmark_newton_fraction for error-controlled steps).
  double newton_fraction = 1.0;
  int max_newton_iterations = 10;
  /// At index 3, or stabilized at index 2 (the velocity constraints held too).
  NewmarkConstraints constraints = NewmarkConstraints::index3;
  /// Error-controlled steps: the first step stays below half of the time from t0 to this one
  /// (IntegratorSettings::first_kink, the first sample of a tabulated load).
  double first_kink = std::numeric_limits<double>::infinity();
  /// What a failed fixed step's message advises after its step size (a bridge, whose step the
  /// user does not set, advises nothing).
  std::string step_advice = "; a smaller [solve] step may converge";
};

/// ü and λ at (t, u, v) from the constraints at acceleration level, [M Aᵀ; A 0][ü; λ] = [f; γ]
/// (dae/formulations/row_multipliers.hpp); nothing when that system is singular.
using ConsistentAccelerations =
    std::function<std::optional<std::pair<Eigen::VectorXd, Eigen::VectorXd>>(
        double t, const Eigen::VectorXd& u, const Eigen::VectorXd& v)>;

class NewmarkStepper : public Stepper {
 public:
  /// Starts at (t0, u0, v0), consistent with the constraints; ü and λ from `consistent`, there
  /// and at every load step. `linear`: M, C, K, A constant. Throws IntegrationError when the
  /// acceleration-level system is singular at t0.
  NewmarkStepper(const MechanicalSystem& system, bool linear, const NewmarkSettings& settings,
                 ConsistentAccelerations consistent, double t0, const Eigen::VectorXd& u0,
                 const Eigen::VectorXd& v0);

  double step(double tout) override;
  void interpolate(double t, Eigen::VectorXd& y, Eigen::VectorXd& yp) override;
  [[nodiscard]] Eigen::VectorXd y() override;
  [[nodiscard]] Eigen::VectorXd yp() override;
  void restart(double t) override;
  void set_stop_time(double t) override { stop_ = t; }
  void fill_summary(SolveSummary& summary) override;

  [[nodiscard]] long jacobian_nonzeros() const { return newton_->nonzeros(); }
  [[nodiscard]] int size() const { return 2 * n_ + m_ + newton_->mu_size(); }

 private:
  /// ü and λ at the current state from `consistent_`; a = ü (the method restarts there).
  void consistent_accelerations();
  /// How a step attempt failed: the kind and what happened.
  struct StepFailure {
    FailureKind kind;
    std::string what;
  };
  /// One step of the fixed step on grid_ (step() with settings_.step > 0).
  double fixed_step(double tout);
  /// One accepted error-controlled step (dae/integrators/newmark_controlled_step.cpp).
  double controlled_step(double tout);
  /// The step from t_ to t_next = t_ + h: the predictor and Newton's iterations, into x and the
  /// algorithmic acceleration a; the failure when Newton's iterations fail.
  std::optional<StepFailure> attempt(double t_next, double h, StepState& x, Eigen::VectorXd& a);
  /// Takes the attempt (x, a) to t_next as the current state.
  void accept(double t_next, double h, StepState x, Eigen::VectorXd a);
  /// Newton's iterations for the state at t_next from the predictor `x`; the failure when they
  /// do not converge.
  std::optional<StepFailure> solve_step(double t_next, const StepCoefficients& c, StepState& x);
  /// The backward error of the iterate x whose scaled residual is r, row by row against the
  /// tolerance of the largest displacement: the largest |r_i| / (Σ_j |∂r_i/∂u_j| τ),
  /// τ = rtol ‖u‖∞ + atol. At most the Newton fraction: every equation holds to within what a
  /// change of u by that fraction of τ makes of it (a coordinate passing zero, as A02's at its
  /// passages, is judged by the mechanism's size, not by atol alone). Near a singular configuration
  /// Newton's corrections amplify the residual's last digits by the inverse of a nearly singular
  /// matrix along the direction in which the root is not determined, and never pass the correction
  /// test; this one they pass (IFToMM A02 at steps from 2e-3 to 5e-5, docs/validation.md).
  [[nodiscard]] double backward_error(double t, const StepState& x, const StepCoefficients& c,
                                      const Eigen::VectorXd& r) const;
  [[nodiscard]] Eigen::VectorXd pack(const StepState& x, bool derivative) const;

  std::unique_ptr<MechanicalSystem> system_;
  NewmarkSettings settings_;
  ConsistentAccelerations consistent_;
  bool linear_;
  int n_, m_;
  std::unique_ptr<StepNewton> newton_;
  FixedStepGrid grid_;  ///< the fixed step's grid (unused under error control)
  double stop_;
  double t_, t_prev_;
  StepState x_, x_prev_;
  Eigen::VectorXd a_;  ///< the algorithmic acceleration at t_
  long steps_ = 0, newton_iterations_ = 0;
  long rejected_steps_ = 0, newton_failures_ = 0;  ///< error-controlled attempts that failed
  double last_step_ = 0.0;
  double next_step_ = 0.0;  ///< the error-controlled step proposed next (0: none yet)
};

}  // namespace condyn
