#pragma once
/// Coordinate partitioning (Wehage and Haug 1982): the n coordinates split into m dependent ones,
/// whose block A_d of the constraint Jacobian is square and regular, and n − m independent ones
/// that the integrator advances. The chapter's master-slave elimination is the linear case (the
/// dependent coordinates are its slaves, chosen the same way).

#include <Eigen/Sparse>
#include <string>
#include <vector>

namespace condyn {

struct CoordinatePartition {
  std::vector<int> independent, dependent;  ///< DOF indices, ascending
  /// Per DOF, its place among the independent coordinates, or −1 for a dependent one.
  std::vector<int> independent_at;
  /// n x m: selects the dependent columns, A_d = A S_d.
  Eigen::SparseMatrix<double> select_dependent;
};

/// The partition a column-pivoted QR of A (m x n, full row rank at the state it was evaluated
/// at) picks: its pivots are the dependent coordinates (pivoted_slaves,
/// dae/formulations/master_slave.hpp). Throws std::invalid_argument when A is rank deficient
/// or a coupled group is too large for the dense pivoting block.
[[nodiscard]] CoordinatePartition choose_partition(const Eigen::SparseMatrix<double>& A);

/// The conditioning of the dependent block: min |R_ii| / max |R_ii| of the QR factor of D A_d
/// (D: exact row scales, models/core/row_scales.hpp, so a row's units do not count). At most
/// 1; 0 when A_d is singular (the product of the |R_ii| is |det D A_d|), and at least its
/// reciprocal condition number (every |R_ii| lies between σ_min and σ_max). Sparse QR: no dense
/// block.
[[nodiscard]] double pivot_ratio(const Eigen::SparseMatrix<double>& A,
                                 const CoordinatePartition& partition);

/// "ux2, uy3" for the DOFs given (at most `limit` named, then "and N more").
[[nodiscard]] std::string dof_list(const std::vector<std::string>& names,
                                   const std::vector<int>& dofs, std::size_t limit = 8);

}  // namespace condyn
