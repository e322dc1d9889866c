#pragma once
/// The Newton systems of the projection scheme's BDF steps, solved sparse (issue 12: CVODE's dense
/// difference-quotient Jacobian held (2n)² entries). For y = [u; v], u' = v, v' = a with
///
///   M(u) a + A(u)ᵀ λ = f(t, u, v),   A(u) a = γ(t, u, v)
///
/// (the projected ODE of dae/formulations/projected_ode.hpp), CVODE asks for x = [x_u; x_v] with
/// (I − γ J) x = b, J = ∂F/∂y. Linearising the two equations at a state (with its a and λ),
///
///   M δa + Aᵀ δλ + K δu + C δv = 0,   A δa + P δu + Q δv = 0,
///
/// K = −∂f/∂u + ∂(M a)/∂u + ∂(Aᵀλ)/∂u, C = −∂f/∂v, P = ∂(A a)/∂u − ∂γ/∂u, Q = −∂γ/∂v; then
/// eliminating x_u = b_u + γ x_v and δa = (x_v − b_v)/γ leaves the saddle-point system
///
///   [M + γC + γ²K  Aᵀ] [x_v]   [M b_v − γ K b_u]
///   [A + γQ + γ²P  0 ] [ μ ] = [A b_v − γ P b_u]
///
/// of n + m unknowns (μ = γ δλ, discarded), which KLU factors, its pattern analysed once (every
/// block's pattern is fixed: MechanicalSystem's contract). For a linear model (constant M, C, K,
/// A; P = Q = 0) the matrices are constant. For a nonlinear one they are the exact derivatives
/// at the state the integrator linearises at (NewtonSystem::linearize_at), from the system's
/// curvature blocks: no dense matrix, no difference quotients.
///
/// Massless DOFs held by stiffness (linear models; their rows of M and columns of A are zero)
/// take their accelerations from their rows differentiated (dae/formulations/projected_ode.hpp):
/// K_h· a = f̈_h (undamped) or C_h· a + K_h· v = ḟ_h (damped). Linearised with
/// a = (x_v − b_v)/γ, those rows read γ² K_h· x_v = γ² K_h· b_v and γ (C_h· + γ K_h·) x_v =
/// γ C_h· b_v: the matrix's rows h as they stand, with these right-hand sides.

#include <Eigen/Sparse>

#include <functional>
#include <memory>

#include "dae/interface/held_massless.hpp"
#include "dae/interface/ode_problem.hpp"
#include "dae/linsolve/fixed_pattern_klu.hpp"
#include "dae/linsolve/kkt.hpp"
#include "models/core/mechanical_system.hpp"

namespace condyn {

class KktNewton final : public NewtonSystem {
 public:
  using ConstRef = Eigen::Ref<const Eigen::VectorXd>;
  /// [a; λ] (n + m) at (t, u, v): the projected ODE's accelerations and multipliers.
  using Accelerations = std::function<Eigen::VectorXd(double t, ConstRef u, ConstRef v)>;

  /// A linear model: takes the matrices over (M, C, K n x n with C possibly empty; A m x n;
  /// swapped, not copied). Throws std::invalid_argument when their sizes disagree.
  /// `held`: the massless DOFs held by stiffness among them, or null.
  explicit KktNewton(LinearMatrices&& matrices, std::shared_ptr<const HeldMassless> held = nullptr);
  /// A nonlinear model: the matrices are evaluated by `system` (an evaluator the caller owns and
  /// keeps alive, in the integration's segment) at each state linearize_at() gives, with the a
  /// and λ there from `accelerations`. Until the first linearize_at, they hold the patterns only.
  KktNewton(MechanicalSystem& system, Accelerations accelerations);

  /// Factors the saddle-point matrix for γ; false when it is singular.
  bool setup(double gamma) override;
  /// x = (I − γ J)⁻¹ b for the γ of the last setup, in place.
  void solve(Eigen::Ref<Eigen::VectorXd> b) override;
  [[nodiscard]] long nonzeros() const override { return nonzeros_; }
  [[nodiscard]] bool state_dependent() const override { return system_ != nullptr; }
  /// A nonlinear model's matrices at y = [u; v] (nothing for a linear one). Throws
  /// RecoverableError when the KKT system giving a and λ is singular there.
  void linearize_at(double t, const ConstRef& y) override;

 private:
  /// The nonlinear model's matrices at (t, u, v) with accelerations a and multipliers λ.
  void assemble(double t, const ConstRef& u, const ConstRef& v, const ConstRef& a,
                const ConstRef& lambda);
  /// Checks the sizes, sizes an empty C, and counts the saddle-point matrix's entries.
  void finish();
  [[nodiscard]] Eigen::SparseMatrix<double> saddle(double gamma) const;

  Eigen::SparseMatrix<double> M_, C_, K_, A_, P_, Q_;  ///< P, Q empty for a linear model
  std::shared_ptr<const HeldMassless> held_;
  MechanicalSystem* system_ = nullptr;  ///< a nonlinear model's evaluator; null: linear
  Accelerations accelerations_;
  int n_ = 0, m_ = 0;
  double gamma_ = 0.0;
  long nonzeros_ = 0;
  FixedPatternKlu klu_;
  Eigen::VectorXd work_;  ///< n + m: the saddle-point right-hand side, then its solution
};

}  // namespace condyn
