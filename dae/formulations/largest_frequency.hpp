#pragma once
/// The largest eigenvalue ω²_max of K x = ω² M x (M positive definite, K symmetric) by a few
/// restarted Lanczos iterations (Spectra's SymGEigsSolver, Debian libspectra-dev): what the
/// model's scales need from a model too large for the dense eigensolver, at the cost of some
/// hundred products with K and solves with M's sparse Cholesky factor.

#include <Eigen/Sparse>
#include <optional>

namespace condyn {

/// ω²_max to about kLargestFrequencyTolerance relative, or nothing when M is not positive
/// definite (massless DOFs) or the iteration does not converge within its budget. Without the
/// constraints: by Courant-Fischer, restricting the pencil to null(A) can only lower its largest
/// eigenvalue, so this bounds the constrained ω²_max from above (to the tolerance).
[[nodiscard]] std::optional<double> largest_eigenvalue(const Eigen::SparseMatrix<double>& K,
                                                       const Eigen::SparseMatrix<double>& M);

/// Relative accuracy asked of the Ritz value: a scale, not a result (it sets Baumgarte's gains and
/// the first step of the higher-index schemes): a tighter one costs several times the products
/// for a change far below what a scale needs (docs/benchmarks.md).
inline constexpr double kLargestFrequencyTolerance = 1e-2;

}  // namespace condyn
