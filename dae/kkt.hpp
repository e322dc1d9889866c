#pragma once
/// The saddle-point (KKT) matrix of the acceleration-level equations, [M Aᵀ; A 0]: solved for
/// [u''; λ] by the consistent initial values of the multiplier formulations and by the right-hand
/// side of the projected ODE.

#include <Eigen/Sparse>

namespace condyn {

/// [M Aᵀ; A 0], (n + m) x (n + m), compressed. M is n x n, A is m x n.
[[nodiscard]] Eigen::SparseMatrix<double> kkt_matrix(const Eigen::SparseMatrix<double>& M,
                                                     const Eigen::SparseMatrix<double>& A);

}  // namespace condyn
