#pragma once
/// The Newton system of one step of the Newmark family stabilized at index 2, the GGL form of
/// Arnold and Brüls (2007, "Convergence of the generalized-α scheme for constrained mechanical
/// systems", Multibody Syst. Dyn. 18, §4) analysed by Arnold, Brüls and Cardona (2015, "Error
/// analysis of generalized-α Lie group time integration methods for constrained mechanical
/// systems", Numer. Math. 129, 149-179): the step's positions are corrected by a second
/// multiplier μ, one per position-level row, so that the velocity constraints hold at t_{n+1}
/// beside the position constraints,
///
///   u_{n+1} = w_{n+1} + A_p(u_{n+1})ᵀ μ_{n+1},  w_{n+1} = u_n + h v_n + h² [(½ − β) a_n + β
///   a_{n+1}] v_{n+1}, ü_{n+1} from w_{n+1} by the step's formulas (Δv = γ' Δw, Δü = β' Δw) r =
///   M(u) ü − f(t, u, v) + A(u)ᵀ λ = 0                             (n rows) φ(t, u) = 0 (position
///   rows), ψ(t, u, v) = 0 (velocity rows)       (m rows) ψ_p(t, u, v) = 0 (the velocity form of
///   the position rows)         (m_p rows)
///
/// λ keeps its meaning (f_con = −Aᵀλ, the other schemes'); μ is the correction, zero for the
/// exact solution, as GGL's μ under BDF. Newton's unknowns are Δu, Δλ̃ = Δλ / β' and Δμ; with
/// H = ∂(A_pᵀ μ)/∂u (nonlinear rows only) Δw = (I − H) Δu − A_pᵀ Δμ, and the matrix, scaled as
/// at index 3 (Bottasso, Bauchau and Cardona 2008: momentum rows over β', velocity rows over γ'),
///
///   [ S − (M + (γ'/β') C) H,       Aᵀ,  −(M + (γ'/β') C) A_pᵀ ]   S, B: the index-3 blocks
///   [ B − D_v A H,                 0,   −D_v A A_pᵀ           ]
///   (dae/integrators/newmark_newton.hpp), [ P (ψ_u / γ' + A (I − H)),    0,   −A_p A_pᵀ ]   D_v on
///   velocity rows, P picks
///                                                                    the position rows
///
/// tends as h → 0 to a matrix whose last block row and column (A_p, −A_p A_pᵀ) keep it regular
/// where the index-3 one is: a condition bounded in h. One sparse matrix of a fixed pattern
/// (n + m + m_p), KLU with its pivots reused; a linear model's depends on the step alone and is
/// factored once per step size. No dense block: A_p A_pᵀ and M A_pᵀ have the sparsity of the rows.

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <memory>

#include "dae/integrators/newmark_newton.hpp"
#include "dae/integrators/step_newton.hpp"
#include "dae/linsolve/fixed_pattern_klu.hpp"
#include "models/core/mechanical_system.hpp"
#include "models/core/newmark_parameters.hpp"

namespace condyn {

class StabilizedNewmarkNewton final : public StepNewton {
 public:
  /// `linear`: M, C, K and A are constant (the matrix is factored once per coefficient set). The
  /// system has position rows (make_step_newton below).
  StabilizedNewmarkNewton(MechanicalSystem& system, bool linear);

  /// μ ← 0 (a correction of this step alone), w ← the predictor's u.
  void begin_step(StepState& x) override;
  /// The scaled residual [r / β'; φ, ψ_v / γ'; ψ_p / γ'] (n + m + m_p) at (t, x).
  void residual(double t, const StepState& x, const StepCoefficients& c,
                Eigen::VectorXd& out) override;
  [[nodiscard]] bool factor(double t, const StepState& x, const StepCoefficients& c) override;
  void solve_in_place(Eigen::VectorXd& rhs) const override { klu_.solve_in_place(rhs); }
  /// The matrix's absolute row sums over its Δu columns.
  [[nodiscard]] Eigen::VectorXd row_sensitivities(double t, const StepState& x,
                                                  const StepCoefficients& c) override {
    return absolute_row_sums(matrix(t, x, c), n_);
  }
  /// u += Δu, λ += β' Δλ̃, μ += Δμ; then w = u − A_p(u)ᵀ μ exactly, and v, ü moved with w.
  void apply(double t, const Eigen::VectorXd& d, const StepCoefficients& c, StepState& x) override;
  /// w back to x's: u − A_pᵀ μ.
  void return_to(double t, const StepState& x) override;
  [[nodiscard]] int mu_size() const override { return mp_; }

  [[nodiscard]] long factorizations() const override { return factorizations_; }
  [[nodiscard]] long residuals() const override { return index3_.residuals(); }
  [[nodiscard]] long nonzeros() const override { return nonzeros_; }

  /// The scaled matrix at (t, x), compressed (its pattern is every state's: `info` counts it).
  [[nodiscard]] Eigen::SparseMatrix<double> matrix(double t, const StepState& x,
                                                   const StepCoefficients& c);

 private:
  /// The Newmark displacement w = u − A_p(t, u)ᵀ μ.
  [[nodiscard]] Eigen::VectorXd newmark_displacement(double t, const StepState& x);

  MechanicalSystem& system_;
  NewmarkNewton index3_;  ///< the first n + m rows' residual and the index-3 blocks
  bool linear_;
  int n_, m_, mp_;
  Eigen::VectorXd velocity_rows_;     ///< 1 on velocity-level rows, 0 on position rows
  Eigen::SparseMatrix<double> pick_;  ///< P, m_p x m: the position rows
  Eigen::VectorXd w_;                 ///< the current iterate's Newmark displacement
  FixedPatternKlu klu_;
  long factorizations_ = 0, nonzeros_ = 0;
  Eigen::VectorXd psi_;
};

/// The size of μ and the stored entries of the stabilized matrix at (t0, u, v), as `info` reports
/// them ({0, 0} without position rows, where the index-3 matrix serves).
struct StabilizedSize {
  int mu = 0;
  long nonzeros = 0;
};
[[nodiscard]] StabilizedSize stabilized_size(MechanicalSystem& system, bool linear, double t0,
                                             const Eigen::VectorXd& u, const Eigen::VectorXd& v);

/// The step's Newton system for the constraint form `form` (the index-3 one for a stabilized form
/// of a system without position rows, which has nothing to stabilize).
[[nodiscard]] std::unique_ptr<StepNewton> make_step_newton(MechanicalSystem& system, bool linear,
                                                           NewmarkConstraints form);

}  // namespace condyn
