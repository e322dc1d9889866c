#pragma once
// The singular values of a dense matrix: the condition numbers of constraint blocks
// (models/core/master_slave.cpp, models/assembly/solve_settings_checks.cpp).
//
// Computed by LAPACK's dgesdd in OpenBLAS (Debian libopenblas0-pthread, already condyn's BLAS for
// CHOLMOD), loaded on first use as CHOLMOD is (models/core/load_library.hpp). Eigen's SVD
// (divide and conquer) gave the same values but was the most expensive code of the build to compile
// (36 s of g++ -O3 and about a minute under the sanitizers, for one call site's condition number);
// dgesdd is the well-kept routine for it, and a blocked one: faster on the large groups (up to
// 2,000 rows) too.

#include <Eigen/Core>

namespace condyn {

/// The singular values of `a`, largest first (min(rows, cols) of them; none for an empty matrix).
/// Throws LibraryUnavailable when OpenBLAS cannot be loaded, std::runtime_error when its
/// bidiagonal divide and conquer does not converge or `a` holds a value that is not finite.
[[nodiscard]] Eigen::VectorXd singular_values(Eigen::MatrixXd a);

}  // namespace condyn
