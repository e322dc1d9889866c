#pragma once
/// The least-change step of the initial projection (initial_projection.hpp): the smallest
/// mass-weighted change of the free DOFs that removes the residual of some constraint rows.

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <vector>

namespace condyn {

/// min ‖W^½ dx_F‖ over the free DOFs F (`free`) subject to A(rows, F) dx_F = −r(rows) in the
/// (row-weighted: `row_weight`, one per row of A) least-squares sense; dx is zero on the other
/// DOFs. `w_inv_sqrt` is W^-½, one per DOF (its size is dx's). With B the weighted,
/// row-normalised block and z = W^½ dx_F: z = B⁺ rhs, dense (a complete orthogonal
/// decomposition, which also treats rank-deficient rows) for blocks up to 4·10⁶ entries, sparse
/// (the normal equations of the minimum-norm problem) above. Throws std::runtime_error when the
/// sparse path finds the rows dependent.
[[nodiscard]] Eigen::VectorXd least_change_step(const Eigen::SparseMatrix<double>& A,
                                                const std::vector<int>& rows,
                                                const std::vector<int>& free,
                                                const Eigen::VectorXd& r,
                                                const Eigen::VectorXd& row_weight,
                                                const Eigen::VectorXd& w_inv_sqrt);

}  // namespace condyn
