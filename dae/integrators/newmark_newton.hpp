#pragma once
/// The Newton system of one step of the Newmark family at index 3 (Arnold and Brüls 2007,
/// "Convergence of the generalized-α scheme for constrained mechanical systems", Multibody
/// Syst. Dyn. 18, 185-202, their Algorithm 1): the equations of motion and the constraints at
/// t_{n+1},
///
///   r = M(u) ü − f(t, u, v) + A(u)ᵀ λ = 0       (n rows)
///   φ(t, u) = 0 (position rows),  ψ(t, u, v) = 0 (velocity rows)   (m rows)
///
/// in the unknowns Δu and Δλ, with v and ü tied to u by the step's formulas: Δv = γ' Δu,
/// Δü = β' Δu (β' = (1 − αm) / (h² β (1 − αf)), γ' = γ / (h β)). Its matrix
/// [β' M + γ' C + K + (Mü)_u + (Aᵀλ)_u, Aᵀ; A, 0] has a condition number that grows as h⁻⁴; the
/// scaling of Bottasso, Bauchau and Cardona (2008, "Time-step-size-independent conditioning and
/// sensitivity to perturbations in the numerical solution of index three differential algebraic
/// equations", SIAM J. Sci. Comput. 29, 397-414) divides the momentum rows by β' and takes
/// Δλ̃ = Δλ / β' as the unknown, and here also divides the velocity rows by γ':
///
///   [M + (γ'/β') C + (K + (Mü)_u + (Aᵀλ)_u)/β',  Aᵀ;  A + D_v ψ_u / γ',  0] [Δu; Δλ̃]
///       = −[r / β';  φ, ψ / γ']
///
/// whose matrix tends to [M Aᵀ; A 0] as h → 0: a condition bounded in h. One sparse matrix of a
/// fixed pattern, factored by KLU (its pivots reused across refactorizations); for a linear
/// model (constant M, C, K, A) it depends on the step alone and is factored once per step size
/// (under error control also kept for nearby steps: StepNewton::set_stale_ratio).

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <vector>

#include "dae/integrators/step_newton.hpp"
#include "dae/linsolve/fixed_pattern_klu.hpp"
#include "models/core/mechanical_system.hpp"

namespace condyn {

class NewmarkNewton final : public StepNewton {
 public:
  /// `linear`: M, C, K and A are constant (the matrix is factored once per coefficient set).
  NewmarkNewton(MechanicalSystem& system, bool linear);

  /// The scaled residual [r / β'; φ, ψ / γ'] (n + m) at (t, x).
  void residual(double t, const StepState& x, const StepCoefficients& c,
                Eigen::VectorXd& out) override;
  /// Factors the scaled matrix at (t, x) (a linear model's only when c changed); false when it
  /// is singular.
  [[nodiscard]] bool factor(double t, const StepState& x, const StepCoefficients& c) override;
  /// rhs ← (scaled matrix)⁻¹ rhs.
  void solve_in_place(Eigen::VectorXd& rhs) const override { klu_.solve_in_place(rhs); }
  /// The momentum block's absolute row sums on the first n rows, the constraint block's on the
  /// last m.
  [[nodiscard]] Eigen::VectorXd row_sensitivities(double t, const StepState& x,
                                                  const StepCoefficients& c) override;
  /// u += Δu, v += γ' Δu, ü += β' Δu, λ += β' Δλ̃.
  void apply(double t, const Eigen::VectorXd& d, const StepCoefficients& c, StepState& x) override;

  [[nodiscard]] long factorizations() const override { return factorizations_; }
  [[nodiscard]] long residuals() const override { return residuals_; }
  [[nodiscard]] long nonzeros() const override { return nonzeros_; }

  /// The matrix's blocks in the Δu column: the momentum rows' (n x n) and the constraint rows'
  /// (m x n), as the stabilized form reuses them (dae/integrators/stabilized_newmark_newton.hpp).
  [[nodiscard]] Eigen::SparseMatrix<double> momentum_block(double t, const StepState& x,
                                                           const StepCoefficients& c);
  [[nodiscard]] Eigen::SparseMatrix<double> constraint_block(double t, const StepState& x,
                                                             const StepCoefficients& c);

 private:
  MechanicalSystem& system_;
  bool linear_;
  int n_, m_;
  Eigen::VectorXd velocity_rows_;  ///< 1 on velocity-level rows, 0 on position rows
  FixedPatternKlu klu_;
  long factorizations_ = 0, residuals_ = 0, nonzeros_ = 0;
  Eigen::VectorXd f_, phi_, psi_;
};

}  // namespace condyn
