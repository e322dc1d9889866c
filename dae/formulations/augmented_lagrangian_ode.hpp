#pragma once
/// The augmented Lagrangian formulation of Bayo, García de Jalón and Serna (1988) and Bayo and
/// Ledesma (1996): penalty on nonlinear models. The accelerations a = q̈ come from
///
///   (M + Āᵀ α Ā) a = f − Āᵀ α r − Āᵀ λ̄_k,   r = −γ̄ + 2ξω ψ̄ + ω² φ̄,
///   λ̄_{k+1} = λ̄_k + α (Ā a + r),
///
/// iterated until a no longer changes (Ā, φ̄, ψ̄, γ̄: the rows scaled to unit gradient at the
/// start, so that α is a mass whatever the rows' units). At the fixed point Ā a + r = 0 (the
/// constraints at acceleration level, with the critically damped stabilization ξ = 1 of
/// Baumgarte's form) and M a = f − Āᵀλ̄: λ̄ is the multiplier (f_con = −Aᵀλ, λ = D λ̄ with D the row
/// scales), the same meaning as in every other scheme.
///
/// Why: the leading matrix M + Āᵀ α Ā is symmetric positive definite whenever M is, whatever the
/// rank of A, so the formulation stays well posed at singular positions (where A loses rank and
/// the index-1 KKT matrix turns singular) and with redundant rows. There a mode with singular
/// value σ → 0 gets a → its free acceleration, which is what the mechanism does when it passes
/// through (its accelerations then those of the regularization the iteration cap leaves:
/// augmented_lagrangian_parameters()). The state y = [q; q̇] is integrated by CVODE as an ODE (no
/// projection): Adams with functional iteration (OdeProblem::non_stiff). The stabilization's
/// eigenvalues are −ω (double), and the penalty never enters the ODE's Jacobian as a stiff term (it
/// is iterated to convergence, not a spring): a rigid mechanism's ODE is non-stiff, and the
/// functional iteration needs no Jacobian at all (no dense difference quotient, nothing growing
/// with the model but M + ĀᵀαĀ's sparse Cholesky factor).
///
/// Sparse throughout: M + Āᵀ α Ā is factored by Eigen's SimplicialLDLT, its pattern analysed once
/// at the start (the patterns of M and A do not depend on the state).

#include <Eigen/SparseCholesky>
#include <memory>
#include <string>

#include "dae/interface/ode_problem.hpp"
#include "models/core/eigen_decompositions.hpp"
#include "models/core/mechanical_system.hpp"
#include "models/core/model.hpp"

namespace condyn {

struct AugmentedLagrangianParameters {
  double alpha = 0.0;  ///< α, a mass (the rows are scaled to unit gradient)
  double xi = 1.0;     ///< ξ, the stabilization's damping ratio
  double omega = 0.0;  ///< ω, the stabilization's frequency (rad per unit time)
  std::string rule;    ///< how they were chosen, printed in the summary
};

/// α = 1e4 × the largest diagonal of M at the start, on rows of unit gradient (α is then a mass).
/// Each constraint mode's multiplier error contracts by 1/(1 + α σ̄²/m) per iteration, 1e-4 for a
/// regular row (three or four solves to convergence). Near a singular position, where σ̄ → 0, the
/// modes with α σ̄² below m converge slowly and stop at the iteration cap: there the formulation
/// is a penalty-like regularization of width σ̄ ≈ √(m/α), smooth in the state, which carries the
/// mechanism through on its branch. The literature's α = 1e7 (Bayo and Ledesma) narrows that
/// window until the integrator's steps land inside it and the run leaves the branch: on A02 at
/// rtol 1e-10, N = 4 left it at α = 1e7 and held it at 1e4 and 1e5, and N = 40 over 20 s was
/// 100 times closer to the reference at 1e4 than at 1e5 (docs/limitations.md has the figures).
/// ξ = 1 (critical damping: the violation decays without overshoot), ω = 10 rad/s as the
/// literature advises for mechanisms: the stabilization only has to keep the drift bounded (the
/// iteration holds the rows at acceleration level), and its eigenvalues −10 stay inside Adams'
/// stability region at the steps a mechanism's motion needs, so it adds no stiffness.
[[nodiscard]] AugmentedLagrangianParameters augmented_lagrangian_parameters(const Model& model);

class AugmentedLagrangianOde final : public OdeProblem {
 public:
  /// Evaluates its own clones of `system`, starting at displacements u0 (the row scales). Throws
  /// std::invalid_argument when M + ĀᵀαĀ is not positive definite at u0.
  AugmentedLagrangianOde(const MechanicalSystem& system, const Eigen::VectorXd& u0,
                         const AugmentedLagrangianParameters& parameters);

  [[nodiscard]] int size() const override { return 2 * n_; }
  void begin_segment(double t0) override { system_->begin_segment(t0); }
  void rhs(double t, ConstRef y, Ref ydot) const override;
  [[nodiscard]] std::vector<UnknownKind> unknown_kinds() const override {
    return condyn::unknown_kinds(n_);
  }
  [[nodiscard]] bool has_projection() const override { return false; }
  bool project(double /*t*/, ConstRef /*y*/, Ref /*corr*/,
               const Eigen::VectorXd& /*settled*/) const override {
    return true;
  }
  void project_error(Ref /*err*/) const override {}
  [[nodiscard]] bool non_stiff() const override { return true; }

  /// λ at a state (f_con = −Aᵀλ), from the converged iteration, evaluated outside the run's
  /// segment (the loads on at t).
  [[nodiscard]] Eigen::VectorXd multipliers(double t, const Eigen::VectorXd& y) const;

 private:
  struct Solution {
    Eigen::VectorXd a, lambda;  ///< λ in the rows' own units
  };
  /// The converged accelerations and multipliers at (t, u, v), with `system`'s forces; `lambda`
  /// (λ̄, scaled rows) starts the iteration and returns its end.
  [[nodiscard]] Solution solve(MechanicalSystem& system, double t, const ConstRef& u,
                               const ConstRef& v, Eigen::VectorXd& lambda) const;
  /// Factors M + ĀᵀαĀ at (t, u) into factor_ (its pattern analysed once).
  void factor(MechanicalSystem& system, double t, const ConstRef& u) const;

  std::unique_ptr<MechanicalSystem> system_;    ///< this run's evaluator
  std::unique_ptr<MechanicalSystem> observer_;  ///< outside any segment: for multipliers()
  AugmentedLagrangianParameters parameters_;
  int n_, m_;
  Eigen::VectorXd row_scale_;  ///< D: row i times it has unit gradient at u0
  mutable Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> factor_;
  mutable bool analysed_ = false;
  mutable Eigen::SparseMatrix<double> scaled_a_;  ///< D A at the last factor()
};

}  // namespace condyn
