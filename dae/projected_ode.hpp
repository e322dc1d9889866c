#pragma once
/// The projection scheme: the index-1 formulation as an ODE, y = [u; v],
///
///   u' = v,   v' = a  with  [M Aᵀ; A 0] [a; λ] = [f(t, u, v); γ]   (λ eliminated),
///
/// integrated by CVODE, which after every step projects the state back onto the constraint
/// manifold (CVodeSetProjFn), M-weighted (the closest point in the kinetic-energy metric):
///
///   u ← u − M⁻¹A_pᵀ (A_p M⁻¹ A_pᵀ)⁻¹ φ_p(t, u)    (position rows)
///   v ← v − M⁻¹Aᵀ (A M⁻¹ Aᵀ)⁻¹ ψ(t, u, v)         (all rows)
///
/// and projects the local error estimate the same way. Why CVODE and not IDA: IDA 6.4 has no
/// projection hook, and projecting between IDA steps needs IDAReInit, which restarts the BDF
/// method at order 1 after every step. CVODE's projection is part of its step, so the method
/// keeps its order and its history stays consistent with the projected solution.
///
/// Costs: the KKT system is factored once (M and A are constant here), every right-hand side is
/// one solve; CVODE uses a dense difference-quotient Jacobian, so this scheme suits small and
/// medium models. Needs a positive definite M (mass on every DOF).

#include <Eigen/SparseCholesky>
#include <Eigen/SparseLU>

#include "dae/mechanical_system.hpp"
#include "dae/ode_problem.hpp"

namespace condyn {

class ProjectedOde final : public OdeProblem {
 public:
  /// Keeps a reference to `system`. Throws std::invalid_argument when M is not positive definite
  /// or the system has curvature terms.
  explicit ProjectedOde(const MechanicalSystem& system);

  [[nodiscard]] int size() const override { return 2 * n_; }
  void rhs(double t, double step_reference, ConstRef y, Ref ydot) const override;
  [[nodiscard]] bool has_projection() const override { return m_ > 0; }
  void project(double t, ConstRef y, Ref corr) const override;
  void project_error(Ref err) const override;

  /// λ at a state, from the same KKT system (f_con = −Aᵀλ).
  [[nodiscard]] Eigen::VectorXd multipliers(double t, const Eigen::VectorXd& y) const;

 private:
  /// [a; λ] from the KKT system at (t, u, v).
  [[nodiscard]] Eigen::VectorXd accelerations(double t, double step_reference, const ConstRef& u,
                                              const ConstRef& v) const;

  const MechanicalSystem& system_;
  int n_, m_;
  Eigen::SparseLU<Eigen::SparseMatrix<double>> kkt_;
  Eigen::SimplicialLLT<Eigen::SparseMatrix<double>> mass_;
  Eigen::SparseMatrix<double> A_, Ap_;          ///< all rows, position rows
  Eigen::LDLT<Eigen::MatrixXd> gram_, gram_p_;  ///< A M⁻¹ Aᵀ, A_p M⁻¹ A_pᵀ
  Eigen::MatrixXd minv_at_, minv_apt_;          ///< M⁻¹Aᵀ, M⁻¹A_pᵀ (dense: m columns)
  std::vector<int> position_rows_;
  mutable Eigen::VectorXd force_, rows_;
};

}  // namespace condyn
