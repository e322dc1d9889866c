#include "dae/formulations/multiplier_recovery.hpp"

#include "models/core/row_scales.hpp"

namespace condyn {

MultiplierRecovery::MultiplierRecovery(const Model& model) : model_(model) {
  if (model.constraint_count() > 0) {
    // Rows scaled by powers of two (exact): A Aᵀ of a row with a coefficient of 1e155
    // overflowed, and elimination reported zero reactions.
    scale_ = row_scales(model.A);
    scaled_ = scale_.asDiagonal() * model.A;
    const Eigen::SparseMatrix<double> At = scaled_.transpose();
    aat_.compute(scaled_ * At);  // m x m, sparse; positive definite (A has full row rank)
  }
}

Eigen::VectorXd MultiplierRecovery::operator()(double t, const Eigen::VectorXd& u,
                                               const Eigen::VectorXd& v,
                                               const Eigen::VectorXd& a) const {
  if (model_.constraint_count() == 0) return {};
  Eigen::VectorXd rho = model_.M * a + *model_.K * u - model_.applied_forces(t);
  if (model_.has_damping()) rho += model_.C * v;
  // λ = −(A Aᵀ)⁻¹ A ρ with A = D⁻¹ Â: λ = −D (Â Âᵀ)⁻¹ Â ρ.
  return -(scale_.asDiagonal() * aat_.solve(scaled_ * rho)).eval();
}

}  // namespace condyn
