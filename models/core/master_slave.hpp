#pragma once
/// The master-slave transformation of the chapter's elimination path (§5.5, §5.6):
///
///   u = T û + G g(t),   T (n x nm), G (n x m):  A T = 0, A G = I,
///
/// of which direct elimination of single-freedom constraints is the special case where every slave
/// is the DOF its constraint names. Built group by group (models/core/constraint_groups.hpp): rows
/// that share no DOF are independent, so each group's slaves, A_S⁻¹ A_R and A_S⁻¹ come from its own
/// small dense block, and T and G are sparse with nonzeros only inside the groups (a support is a 1
/// x 1 group: its slave row of T is empty). The cost follows the groups, not m x n.

#include <Eigen/Sparse>
#include <stdexcept>
#include <vector>

namespace condyn {

/// Named slaves whose block of the constraint matrix has a condition number above this are
/// refused (by the scene check of `solve.slaves` and by the transformation itself): the slave
/// displacements would carry cond * eps relative error from roundoff alone.
inline constexpr double kMaxSlaveCondition = 1e12;

/// u = T û + G g. Slaves are chosen by column pivoting on each group's row-normalised block
/// unless the caller names them.
struct MasterSlave {
  std::vector<int> masters, slaves;  ///< DOF indices, ascending
  Eigen::SparseMatrix<double> T;     ///< n x nm
  Eigen::SparseMatrix<double> G;     ///< n x m
};

/// A group of coupled constraints too large for the dense per-group factorization.
class CoupledGroupTooLarge : public std::invalid_argument {
 public:
  CoupledGroupTooLarge(int first, int row_count, int dof_count, const std::string& what)
      : std::invalid_argument(what), first_row(first), rows(row_count), dofs(dof_count) {}
  int first_row, rows, dofs;
};

/// A group's dense block may hold this many entries (32 MB; its QR takes seconds). Realistic
/// coupled groups (ties, rigid links, a floor's MFCs) are far smaller.
inline constexpr double kMaxDenseGroupEntries = 4e6;

/// Whether a coupled group of `rows` constraints over `dofs` DOFs can be eliminated: its dense
/// block (rows × dofs) and the dense coupling its elimination leaves among its masters in the
/// reduced M, C and K ((dofs − rows)²: a row over 3,000 DOFs couples 2,999 masters) each within
/// kMaxDenseGroupEntries.
[[nodiscard]] inline bool group_within_dense_limits(std::size_t rows, std::size_t dofs) {
  const double r = static_cast<double>(rows), d = static_cast<double>(dofs);
  return r * d <= kMaxDenseGroupEntries && (d - r) * (d - r) <= kMaxDenseGroupEntries;
}

/// The m columns (DOFs, ascending) a column-pivoted QR picks as slaves of A (m x n, full row
/// rank), pivoting on each coupled group's row-normalised block so that no row's units bias the
/// choice: the best-conditioned slave block the greedy pivoting finds. Coordinate partitioning
/// (dae/formulations/coordinate_partition.hpp) takes its dependent coordinates from it. Throws
/// std::invalid_argument when the rows are dependent, CoupledGroupTooLarge for a group whose
/// rows x DOFs exceed kMaxDenseGroupEntries.
[[nodiscard]] std::vector<int> pivoted_slaves(const Eigen::SparseMatrix<double>& A);

/// Builds the transformation. `preferred_slaves` (DOF indices, size m) overrides the pivoting
/// choice. Throws std::invalid_argument when A is rank deficient or the named slaves do not form
/// an invertible block (naming the condition number), CoupledGroupTooLarge beyond the dense limit.
[[nodiscard]] MasterSlave master_slave_transform(const Eigen::SparseMatrix<double>& A,
                                                 const std::vector<int>& preferred_slaves = {});

}  // namespace condyn
