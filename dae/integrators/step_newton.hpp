#pragma once
/// What the Newmark family's stepper (dae/integrators/newmark_stepper.hpp) asks of the Newton
/// system of one step, whichever constraint form it holds: at index 3
/// (dae/integrators/newmark_newton.hpp) or stabilized at index 2
/// (dae/integrators/stabilized_newmark_newton.hpp). Both solve for the state at t_{n+1} in
/// scaled unknowns whose first n entries are Δu, and both keep v and ü tied to the step's
/// formulas, Δv = γ' Δw and Δü = β' Δw, w the step's Newmark displacement.

#include <Eigen/Dense>

namespace condyn {

/// β' and γ' of the step: β' = (1 − αm) / (h² β (1 − αf)), γ' = γ / (h β).
struct StepCoefficients {
  double beta_prime = 0.0, gamma_prime = 0.0;
  bool operator==(const StepCoefficients&) const = default;
};

/// One state of the step's unknowns at t_{n+1}.
struct StepState {
  Eigen::VectorXd u, v, acc, lambda;  ///< displacements, velocities, ü, λ
  /// The stabilized form's μ, one per position-level row (empty at index 3): the correction
  /// u = w + A_pᵀ μ of the positions that lets the velocity constraints hold too.
  Eigen::VectorXd mu;
};

class StepNewton {
 public:
  virtual ~StepNewton() = default;
  StepNewton() = default;
  StepNewton(const StepNewton&) = delete;
  StepNewton& operator=(const StepNewton&) = delete;

  /// Prepares the predictor `x` (u on the step's formulas) for Newton's iterations.
  virtual void begin_step(StepState& /*x*/) {}
  /// The scaled residual at (t, x).
  virtual void residual(double t, const StepState& x, const StepCoefficients& c,
                        Eigen::VectorXd& out) = 0;
  /// Factors the scaled matrix at (t, x); false when it is singular.
  [[nodiscard]] virtual bool factor(double t, const StepState& x, const StepCoefficients& c) = 0;
  /// rhs ← (scaled matrix)⁻¹ rhs.
  virtual void solve_in_place(Eigen::VectorXd& rhs) const = 0;
  /// x ← x + the increment d that solve_in_place returned (its first n entries are Δu).
  virtual void apply(double t, const Eigen::VectorXd& d, const StepCoefficients& c,
                     StepState& x) = 0;

  /// The size of μ (0 at index 3).
  [[nodiscard]] virtual int mu_size() const { return 0; }
  [[nodiscard]] virtual long factorizations() const = 0;
  [[nodiscard]] virtual long residuals() const = 0;
  [[nodiscard]] virtual long nonzeros() const = 0;
};

}  // namespace condyn
