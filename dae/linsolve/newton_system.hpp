#pragma once
/// A Newton system an integrator asks for, solved by the problem itself (sparse, condensed,
/// without forming the integrator's Jacobian): CVODE's (I − γ ∂F/∂y) x = b, IDA's
/// (∂F/∂y + cj ∂F/∂y') x = b. dae/integrators/newton_linear_solver.hpp wraps one for SUNDIALS.

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <string>

namespace condyn {

class NewtonSystem {
 public:
  virtual ~NewtonSystem() = default;
  /// Prepares solves with this scalar (γ or cj: a factorization); false when singular.
  virtual bool setup(double scalar) = 0;
  /// b ← (Newton matrix)⁻¹ b for the scalar of the last setup.
  virtual void solve(Eigen::Ref<Eigen::VectorXd> b) = 0;
  /// Nonzeros of the matrix factored (for the summary's Jacobian size).
  [[nodiscard]] virtual long nonzeros() const = 0;
  /// true when the matrix depends on the integrator's state (a nonlinear model): each setup is
  /// then preceded by linearize_at, and the matrix is renewed every few steps even when the
  /// scalar stays (dae/integrators/newton_linear_solver.hpp).
  [[nodiscard]] virtual bool state_dependent() const { return false; }
  /// The matrix factored when it is symmetric positive definite by construction (its pattern, and
  /// the values of the last setup), which CHOLMOD can factor; nullptr for any other (a saddle
  /// point with multipliers, an unsymmetric matrix), which KLU factors.
  [[nodiscard]] virtual const Eigen::SparseMatrix<double>* symmetric_matrix() const {
    return nullptr;
  }
  /// Factors with CHOLMOD from the next setup on (models/core/fixed_pattern_cholmod.hpp), its
  /// analysis under `ordering` (empty: the least fill of every ordering); false, and nothing
  /// changed, when symmetric_matrix() is nullptr.
  virtual bool use_cholmod(const std::string& /*ordering*/) { return false; }
  /// The state (t, y) the next setup linearises at: the integrator's predicted state, where
  /// SUNDIALS' own matrix-based solvers evaluate their Jacobians. Nothing by default.
  virtual void linearize_at(double /*t*/, const Eigen::Ref<const Eigen::VectorXd>& /*y*/) {}
};

}  // namespace condyn
