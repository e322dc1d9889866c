#pragma once
/// The Newton systems of the projection scheme's BDF steps, solved sparse (issue 12: CVODE's dense
/// difference-quotient Jacobian held (2n)² entries). For y = [u; v], u' = v, v' = a with
/// [M Aᵀ; A 0] [a; λ] = [f − C v − K u; γ_c] (the projected ODE of
/// dae/formulations/projected_ode.hpp), CVODE asks for x = [x_u; x_v] with (I − γ J) x = b, J =
/// ∂F/∂y. Eliminating x_u = b_u + γ x_v and the acceleration's multiplier leaves the saddle-point
/// system
///
///   [M + γC + γ²K  Aᵀ] [x_v]   [M b_v − γ K b_u]
///   [A             0 ] [ μ ] = [A b_v          ]
///
/// of n + m unknowns, which KLU factors (its pattern analysed once). It is exact for a linear model
/// (constant M, C, K, A); the projection scheme uses it for those, and CVODE's dense Jacobian for
/// nonlinear models.
///
/// Massless DOFs held by stiffness (their rows of M and columns of A are zero) take their
/// accelerations from their rows differentiated (dae/formulations/projected_ode.hpp): K_h· a = f̈_h
/// (undamped) or C_h· a + K_h· v = ḟ_h (damped). Linearised with a = (x_v − b_v)/γ, those rows
/// read γ² K_h· x_v = γ² K_h· b_v and γ (C_h· + γ K_h·) x_v = γ C_h· b_v: the matrix's rows h
/// as they stand, with these right-hand sides.

#include <Eigen/Sparse>

#include <memory>

#include "dae/interface/held_massless.hpp"
#include "dae/interface/ode_problem.hpp"
#include "dae/linsolve/fixed_pattern_klu.hpp"
#include "dae/linsolve/kkt.hpp"

namespace condyn {

class KktNewton final : public NewtonSystem {
 public:
  /// Takes the matrices over (M, C, K n x n with C possibly empty; A m x n; swapped, not copied).
  /// Throws std::invalid_argument when their sizes disagree.
  /// `held`: the massless DOFs held by stiffness among them, or null.
  explicit KktNewton(LinearMatrices&& matrices, std::shared_ptr<const HeldMassless> held = nullptr);

  /// Factors the saddle-point matrix for γ; false when it is singular.
  bool setup(double gamma) override;
  /// x = (I − γ J)⁻¹ b for the γ of the last setup, in place.
  void solve(Eigen::Ref<Eigen::VectorXd> b) override;
  [[nodiscard]] long nonzeros() const override { return nonzeros_; }

 private:
  [[nodiscard]] Eigen::SparseMatrix<double> saddle(double gamma) const;

  Eigen::SparseMatrix<double> M_, C_, K_, A_;
  std::shared_ptr<const HeldMassless> held_;
  int n_ = 0, m_ = 0;
  double gamma_ = 0.0;
  long nonzeros_ = 0;
  FixedPatternKlu klu_;
  Eigen::VectorXd work_;  ///< n + m: the saddle-point right-hand side, then its solution
};

}  // namespace condyn
