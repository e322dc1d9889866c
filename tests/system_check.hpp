#pragma once
/// A generic derivative checker for MechanicalSystem implementations (analytic Jacobian and
/// curvature blocks against central differences of the system's own functions).

#include <Eigen/Dense>
#include <string>
#include <vector>

#include "models/core/mechanical_system.hpp"

namespace condyn::test {

/// Checks every derivative a MechanicalSystem reports against central differences of its own
/// functions at (t, u, v), with accelerations a (n) and multipliers w (m): stiffness and damping
/// against −∂f/∂u and −∂f/∂u' of force(); on position rows A = ∂φ/∂u and ψ = dφ/dt along (1, u');
/// ∂ψ/∂u' = A on all rows; γ = A a − dψ/dt along (1, u', a); mass_jacobian = ∂(M a)/∂u;
/// constraint_force_jacobian = ∂(Aᵀw)/∂u; constraint_product_jacobian = ∂(A a)/∂u;
/// velocity_residual_jacobian = ∂ψ/∂u; acceleration_bias_jacobian_u/_v = ∂γ/∂u, ∂γ/∂u' (an empty
/// block is checked to be zero). Returns one message per mismatch (naming the block, the worst
/// entry, both values); empty when all agree within rel_tol (relative to the block's max-norm, plus
/// a small absolute floor). Also reports a block whose sparsity pattern differs from its pattern at
/// the zero state (t, u, u', a, w all zero: where the multiplier formulations declare their
/// Jacobian pattern).
[[nodiscard]] std::vector<std::string> check_system_derivatives(
    const MechanicalSystem& system, double t, const Eigen::VectorXd& u, const Eigen::VectorXd& v,
    const Eigen::VectorXd& a, const Eigen::VectorXd& w, double rel_tol = 1e-6);

}  // namespace condyn::test
