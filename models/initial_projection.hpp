#pragma once
/// [initial] project = true: moves (u0, v0) onto the constraint manifold by the smallest change
/// (Euclidean norm, so massless DOFs are no obstacle): Gauss-Newton on the position rows,
///   u ← u − A_pᵀ (A_p A_pᵀ)⁻¹ φ_p(t, u)     until the step is at roundoff,
/// then one exact step on the velocity level (ψ is affine in u'),
///   v ← v − Aᵀ (A Aᵀ)⁻¹ ψ(t, u, v).
/// Dense factorizations: meant for the initial state of small and medium models.

#include <Eigen/Dense>
#include <string>

#include "models/mechanical_system.hpp"

namespace condyn {

/// Projects in place; returns what changed ("u moved by 3.1e-02 (max), v by 0 in 4 iterations").
/// Throws std::runtime_error when the constraints are dependent at the state or the iteration
/// does not converge (no configuration near u0 satisfies them).
std::string project_initial_state(const MechanicalSystem& system, double t, Eigen::VectorXd& u,
                                  Eigen::VectorXd& v);

}  // namespace condyn
