#pragma once
/// [initial] static = true for a linear model: the constrained static equilibrium
///
///   [K  Aᵀ] [u]   [f]
///   [A  0 ] [λ] = [g]      (n + m unknowns; K n x n, A m x n)
///
/// solved by a sparse LU (Eigen SparseLU) of the saddle-point matrix, with A's rows scaled to K's
/// size so the two blocks' pivots compare. Sparse throughout: nothing dense of size n.

#include <Eigen/Sparse>
#include <stdexcept>
#include <string>
#include <vector>

#include "models/core/eigen_decompositions.hpp"

namespace condyn {

/// Thrown when K is singular on the motions A allows (a mechanism): no unique static equilibrium.
class NoStaticEquilibrium : public std::runtime_error {
 public:
  NoStaticEquilibrium(const std::string& what, std::vector<int> dofs)
      : std::runtime_error(what), free_dofs(std::move(dofs)) {}
  /// DOFs that move in the mechanism (largest first, at most a few), when they could be found
  /// cheaply: DOFs no stiffness or constraint touches, or the largest entries of a probe solve.
  std::vector<int> free_dofs;
};

struct StaticEquilibrium {
  Eigen::VectorXd u;       ///< n
  Eigen::VectorXd lambda;  ///< m, with K u + Aᵀ λ = f
  double residual = 0.0;  ///< ‖K u + Aᵀλ − f‖∞ / max(‖f‖∞, ‖K‖∞ ‖u‖∞), after one refinement
  double condition = 0.0;  ///< a lower estimate of the (scaled) saddle matrix's 1-norm condition
};

/// Solves the system above. `f` has n entries, `g` m. Throws NoStaticEquilibrium when the saddle
/// matrix is singular (an exact zero pivot) or its condition estimate exceeds 1e13 (a mechanism
/// to roundoff); std::invalid_argument when the sizes disagree.
[[nodiscard]] StaticEquilibrium solve_static_equilibrium(const Eigen::SparseMatrix<double>& K,
                                                         const Eigen::SparseMatrix<double>& A,
                                                         const Eigen::VectorXd& f,
                                                         const Eigen::VectorXd& g);

}  // namespace condyn
