#pragma once
// The singular values of a dense matrix: the condition numbers of constraint blocks
// (models/core/master_slave.cpp, models/assembly/solve_settings_checks.cpp).
//
// Eigen's SVDs were the most expensive code of the build to compile (the divide-and-conquer one
// alone 36 s of g++ -O3, about a minute under the sanitizers) for these two condition numbers.
// Small blocks, the common case, take the eigenvalues of the symmetric [0 A; Aᵀ 0], which are
// ±σ (Eigen's symmetric eigensolver, compiled once in eigen_decompositions.cpp): backward stable
// like an SVD, with the same absolute error of a few eps × σ_max, and no library to load. Larger
// blocks, where that costs several times an SVD, take LAPACK's dgesdd from OpenBLAS (already
// condyn's BLAS for CHOLMOD, loaded on first use the same way: about 6 ms); a process that cannot
// load OpenBLAS still gets the values, by the symmetric path.

#include <Eigen/Core>

namespace condyn {

/// Blocks with more than this many singular values go to LAPACK.
inline constexpr Eigen::Index kSymmetricSingularValuesMax = 100;

/// The singular values of `a`, largest first (min(rows, cols) of them; none for an empty matrix).
/// Throws std::runtime_error when `a` holds a value that is not finite, or LAPACK's bidiagonal
/// divide and conquer does not converge.
[[nodiscard]] Eigen::VectorXd singular_values(Eigen::MatrixXd a);

/// The same by the symmetric eigenvalue path whatever the size (for the tests).
[[nodiscard]] Eigen::VectorXd symmetric_singular_values(const Eigen::MatrixXd& a);

}  // namespace condyn
