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
/// the first step of the higher-index schemes). On the benchmark lattice of 10^5 DOFs, 1e-2 took
/// 21 products and 0.05 s, with ω² 0.17% below the value at 1e-3 (81 products, 0.2 s); at 10^6
/// DOFs 1e-3 took 6 s.
inline constexpr double kLargestFrequencyTolerance = 1e-2;

}  // namespace condyn
