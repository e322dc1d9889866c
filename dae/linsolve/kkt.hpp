#pragma once
/// The saddle-point (KKT) matrix of the acceleration-level equations, [M Aᵀ; A 0]: solved for
/// [u''; λ] by the consistent initial values of the multiplier formulations and by the right-hand
/// side of the projected ODE.

#include <Eigen/Sparse>
#include <memory>

#include "models/core/eigen_decompositions.hpp"
#include "models/core/mechanical_system.hpp"

namespace condyn {

/// [M Aᵀ; A 0], (n + m) x (n + m), compressed. M is n x n, A is m x n.
[[nodiscard]] Eigen::SparseMatrix<double> kkt_matrix(const Eigen::SparseMatrix<double>& M,
                                                     const Eigen::SparseMatrix<double>& A);
/// [M Aᵀ; B 0] with lower rows B (m x n) of their own (a linearised constraint: the projection
/// scheme's Newton matrix of a nonlinear model, dae/formulations/kkt_newton.hpp); stored zeros
/// kept.
[[nodiscard]] Eigen::SparseMatrix<double> kkt_matrix(const Eigen::SparseMatrix<double>& M,
                                                     const Eigen::SparseMatrix<double>& A,
                                                     const Eigen::SparseMatrix<double>& B);

/// A sparse LU of such a matrix (or of any square one), factored afresh at each compute() by KLU
/// (AMD order, block triangular form, partial pivoting), with Eigen::SparseLU's calls: compute,
/// info, solve. Why not Eigen::SparseLU, which these factorizations used before: a constraint over
/// many DOFs (a floor's average drift) is a dense row and column of the KKT matrix, and Eigen's
/// supernodal LU filled in around it under either of its orders (the multipliers' block dense),
/// where KLU's factors stay sparse (figures in docs/benchmarks.md;
/// tests/dae/test_dense_constraint_rows.cpp).
class KktLu {
 public:
  KktLu();
  explicit KktLu(const Eigen::SparseMatrix<double>& matrix);
  ~KktLu();
  KktLu(KktLu&&) noexcept;
  KktLu& operator=(KktLu&&) noexcept;
  KktLu(const KktLu&) = delete;
  KktLu& operator=(const KktLu&) = delete;

  /// Factors `matrix` (square; compressed or not).
  void compute(const Eigen::SparseMatrix<double>& matrix);
  /// Success, or NumericalIssue when the matrix is singular (or was never factored).
  [[nodiscard]] Eigen::ComputationInfo info() const;
  /// x with matrix x = rhs.
  [[nodiscard]] Eigen::VectorXd solve(const Eigen::VectorXd& rhs) const;
  /// Entries of L and U (diagonals included) and of the off-diagonal blocks.
  [[nodiscard]] long factor_entries() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// The matrices of a linear system, M u'' + C u' + K u = f(t) with rows A u: M, C = −∂f/∂v,
/// K = −∂f/∂u and A (0 x n without constraints). Constant for a linear system: evaluated at t = 0
/// and u = v = 0 on a clone, so the system's own evaluator is left as it was.
struct LinearMatrices {
  Eigen::SparseMatrix<double> M, C, K, A;
};
[[nodiscard]] LinearMatrices linear_matrices(const MechanicalSystem& system);

}  // namespace condyn
