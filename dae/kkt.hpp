#pragma once
/// The saddle-point (KKT) matrix of the acceleration-level equations, [M Aᵀ; A 0]: solved for
/// [u''; λ] by the consistent initial values of the multiplier formulations and by the right-hand
/// side of the projected ODE.

#include <Eigen/Sparse>

#include "models/mechanical_system.hpp"

namespace condyn {

/// [M Aᵀ; A 0], (n + m) x (n + m), compressed. M is n x n, A is m x n.
[[nodiscard]] Eigen::SparseMatrix<double> kkt_matrix(const Eigen::SparseMatrix<double>& M,
                                                     const Eigen::SparseMatrix<double>& A);

/// The matrices of a linear system, M u'' + C u' + K u = f(t) with rows A u: M, C = −∂f/∂v,
/// K = −∂f/∂u and A (0 x n without constraints). Constant for a linear system: evaluated at t = 0
/// and u = v = 0 on a clone, so the system's own evaluator is left as it was.
struct LinearMatrices {
  Eigen::SparseMatrix<double> M, C, K, A;
};
[[nodiscard]] LinearMatrices linear_matrices(const MechanicalSystem& system);

}  // namespace condyn
