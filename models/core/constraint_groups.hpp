#pragma once
/// Constraints that share no DOF, even through others, are independent of each other: the rank
/// check and the master-slave transform treat each connected group on its own, so their cost
/// follows the groups (supports are 1 x 1 groups), not m x n.

#include <Eigen/Sparse>
#include <vector>

namespace condyn {

struct ConstraintGroup {
  std::vector<int> rows;  ///< ascending; the group's first row first
  std::vector<int> dofs;  ///< the DOFs its rows touch (stored entries), ascending
};

/// The connected groups of A's rows (rows joined when they share a stored entry's column), in the
/// order of their first rows. A row without stored entries is a group without DOFs.
[[nodiscard]] std::vector<ConstraintGroup> constraint_groups(
    const Eigen::SparseMatrix<double, Eigen::RowMajor>& a);

}  // namespace condyn
