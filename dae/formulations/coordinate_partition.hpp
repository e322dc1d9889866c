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
/// models/core/master_slave.hpp). Throws std::invalid_argument when A is rank deficient
/// or a coupled group is too large for the dense pivoting block.
[[nodiscard]] CoordinatePartition choose_partition(const Eigen::SparseMatrix<double>& A);

/// How well the independent coordinates determine the configuration at A: 1 / ‖B‖₁, where
/// B = [I; −A_d⁻¹ A_i] (rows in the partition's order) is the basis of A's null space that is the
/// identity on the independent coordinates: the velocities u' = B q_i' a motion of the independent
/// ones imposes. At most 1 (dependent coordinates that do not move with the independent ones); it
/// falls to 0 where the independent coordinates stop determining the configuration (A_d turns
/// singular: a crank's tip coordinate at its extreme), like the distance to that position, and 0
/// when A_d is singular. B depends on A only through its null space: neither the rows' units nor
/// a constant small pivot of A_d (short links beside unit vectors) enter it, where they mask the
/// approach to a singular A_d in A_d's own conditioning. ‖A_d⁻¹ A_i‖₁ is estimated by Hager's
/// method (Higham 1988): a few solves with A_d and A_dᵀ (sparse LU), no dense block; the estimate
/// is a lower bound, exact when one coordinate is independent.
[[nodiscard]] double partition_quality(const Eigen::SparseMatrix<double>& A,
                                       const CoordinatePartition& partition);

/// "ux2, uy3" for the DOFs given (at most `limit` named, then "and N more").
[[nodiscard]] std::string dof_list(const std::vector<std::string>& names,
                                   const std::vector<int>& dofs, std::size_t limit = 8);

}  // namespace condyn
