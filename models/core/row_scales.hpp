#pragma once
/// Exact scaling of constraint rows: a row's units are the user's choice (1e12 u1 = 0 beside
/// u2 = 0), and what is judged on the rows (ranks, residuals, pivots) must not depend on them.

#include <Eigen/Sparse>

namespace condyn {

/// D: per row of A, the power of two nearest below 1/max_j |a_ij| (1 for an empty row), so that
/// D A has rows of largest entry in [0.5, 1) and the scaling is exact. A row with a coefficient of
/// 1e155 overflowed A Aᵀ, and one of 1e-150 beside a unit mass left KLU's pivots to roundoff.
[[nodiscard]] Eigen::VectorXd row_scales(const Eigen::SparseMatrix<double>& A);

/// Per row of A, 1/|a_i| (1 for an empty row): row i times it is its unit normal. |a_i| from the
/// row scaled exactly by row_scales() first, and 1/|a_i|² never formed (it overflows below
/// coefficients of 1e-154 and underflows above 1e154).
[[nodiscard]] Eigen::VectorXd unit_row_scales(const Eigen::SparseMatrix<double>& A);

}  // namespace condyn
