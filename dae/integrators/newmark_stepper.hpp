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
/// The state the loop sees: y = [u; v; λ], y' = [v; ü; 0]; stabilized
/// (NewmarkSettings::constraints, dae/integrators/stabilized_newmark_newton.hpp) y = [u; v; λ; μ],
/// y' = [v; ü; 0; 0].

#include <Eigen/Dense>
#include <functional>
#include <memory>
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
  double step = 0.0;  ///< h > 0
  /// Newton's convergence: max_i |Δu_i| / (rtol |u_i| + atol) ≤ 1. A linear model stops there
  /// or after its second iteration, a refinement of the exact first one on the same factors.
  double rtol = 1e-8, atol = 1e-10;
  int max_newton_iterations = 10;
  /// At index 3, or stabilized at index 2 (the velocity constraints held too).
  NewmarkConstraints constraints = NewmarkConstraints::index3;
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
  /// Newton's iterations for the state at t_next from the predictor `x`; throws
  /// IntegrationError when they do not converge.
  void solve_step(double t_next, const StepCoefficients& c, StepState& x);
  [[nodiscard]] Eigen::VectorXd pack(const StepState& x, bool derivative) const;

  std::unique_ptr<MechanicalSystem> system_;
  NewmarkSettings settings_;
  ConsistentAccelerations consistent_;
  bool linear_;
  int n_, m_;
  std::unique_ptr<StepNewton> newton_;
  FixedStepGrid grid_;
  double stop_;
  double t_, t_prev_;
  StepState x_, x_prev_;
  Eigen::VectorXd a_;  ///< the algorithmic acceleration at t_
  long steps_ = 0, newton_iterations_ = 0;
  double last_step_ = 0.0;
};

}  // namespace condyn
