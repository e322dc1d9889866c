#pragma once
/// One step of RATTLE (Andersen 1983, "Rattle: a velocity version of the Shake algorithm",
/// J. Comput. Phys. 52, 24-34; Leimkuhler and Skeel 1994, "Symplectic numerical integrators in
/// constrained Hamiltonian systems", J. Comput. Phys. 112, 117-125; Hairer, Lubich and Wanner,
/// Geometric Numerical Integration, 2nd ed. 2006, §VII.1.4) for
///
///   M u'' = f(t, u) − A(u)ᵀ λ,   φ(u) = 0   (A = ∂φ/∂u)
///
/// with M constant and f independent of u' (a conservative mechanism: f = −∂V/∂u). From (u_n, v_n)
/// on the constraint manifold (φ = 0 and A v = 0):
///
///   v_{n+½} = v_n + (h/2) M⁻¹ (f(t_n, u_n) − A(u_n)ᵀ λ_n)
///   u_{n+1} = u_n + h v_{n+½},                 φ(t_{n+1}, u_{n+1}) = 0          (λ_n: m unknowns)
///   v_{n+1} = v_{n+½} + (h/2) M⁻¹ (f(t_{n+1}, u_{n+1}) − A(u_{n+1})ᵀ μ_n),
///                                              ψ(t_{n+1}, u_{n+1}, v_{n+1}) = 0  (μ_n: m unknowns)
///
/// symplectic, time-reversible and of order 2, its positions and velocities on the manifold at
/// every step. No M⁻¹ is formed. The position stage is solved by Newton in u = u_{n+1} and
/// Λ = (h²/2) λ_n:
///
///   M (u − u_n − h v_n) − (h²/2) f(t_n, u_n) + A(u_n)ᵀ Λ = 0,   φ(t_{n+1}, u) = 0,
///
/// with the exact Jacobian [M A(u_n)ᵀ; A(u^k) 0], whose condition does not grow as h → 0 (the
/// multiplier scaled by h², as Bottasso, Bauchau and Cardona scale the Newmark family's); the
/// velocity stage is one linear solve in v_{n+1} and N = (h/2) μ_n:
///
///   [M A(u_{n+1})ᵀ; A(u_{n+1}) 0] [v_{n+1}; N] = [M v_{n+½} + (h/2) f(t_{n+1}, u_{n+1}); −b]
///
/// with b = ψ(t_{n+1}, u_{n+1}, 0) (zero on scleronomic rows), refined once on its residual so
/// that the velocity rows hold to the roundoff of |v|, not of the matrix's condition. One sparse
/// matrix of a fixed
/// pattern, factored by KLU (pivots kept): once for the whole run when A is constant, else at each
/// Newton iteration and for the velocity stage. The explicit force makes the method conditionally
/// stable, h ω < 2 on every mode (Störmer–Verlet).

#include <Eigen/Dense>
#include <Eigen/Sparse>

#include "dae/linsolve/fixed_pattern_klu.hpp"
#include "models/core/mechanical_system.hpp"

namespace condyn {

struct RattleSettings {
  /// Newton's convergence in the position stage: max_i |Δu_i| / (rtol |u_i| + atol) ≤ 1.
  double rtol = 1e-8, atol = 1e-10;
  int max_newton_iterations = 10;
};

class RattleStep {
 public:
  /// `system`: an evaluator the caller owns and keeps alive, with constant M and forces
  /// independent of u' (the scheme's refusals, dae/run/scheme_choice.cpp, see to it).
  RattleStep(MechanicalSystem& system, const RattleSettings& settings);

  /// Advances (u, v) from t to t + h in place, and sets `mu` to the velocity stage's multiplier
  /// μ_n (m). Throws IntegrationError when Newton does not converge, a matrix is singular or a
  /// residual is not finite, (u, v) then unchanged.
  void advance(double t, double h, Eigen::VectorXd& u, Eigen::VectorXd& v, Eigen::VectorXd& mu);

  [[nodiscard]] long factorizations() const { return factorizations_; }
  [[nodiscard]] long force_evaluations() const { return forces_; }
  [[nodiscard]] long newton_iterations() const { return newton_iterations_; }
  [[nodiscard]] long nonzeros() const { return nonzeros_; }

 private:
  /// The position stage: u_{n+1} into `u` (from u_n + h v_n) for the constant part `c` =
  /// M (u_n + h v_n) + (h²/2) f_n of its momentum rows and the rows A_n of its multiplier.
  void solve_positions(double t_next, const Eigen::SparseMatrix<double>& A_n,
                       const Eigen::VectorXd& c, Eigen::VectorXd& u);
  /// Factors [M Uᵀ; L 0] (once for the run when A is constant); throws when singular.
  void factor(double t, const Eigen::SparseMatrix<double>& U, const Eigen::SparseMatrix<double>& L);

  MechanicalSystem& system_;
  RattleSettings settings_;
  int n_, m_;
  bool constant_rows_;  ///< A does not depend on u: the matrix is the same at every state
  Eigen::SparseMatrix<double> M_;
  Eigen::SparseMatrix<double> matrix_;  ///< the matrix factored last
  FixedPatternKlu klu_;
  bool factored_ = false;
  Eigen::VectorXd lambda_scaled_;  ///< Λ of the last step: the next one's Newton predictor
  Eigen::VectorXd f_, phi_, d_;
  long factorizations_ = 0, forces_ = 0, newton_iterations_ = 0, nonzeros_ = 0;
};

}  // namespace condyn
