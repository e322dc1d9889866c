// The master-slave transformation, group by group (models/core/master_slave.hpp).

#include "models/core/master_slave.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <sstream>

#include "models/core/constraint_groups.hpp"
#include "models/core/eigen_decompositions.hpp"
#include "models/core/singular_values.hpp"

namespace condyn {

namespace {

// Column-pivoting rank threshold on the row-normalised A (same meaning as in build_model).
constexpr double kSlaveRankTolerance = 1e-10;

using RowMajor = Eigen::SparseMatrix<double, Eigen::RowMajor>;

/// The group's block of A: its rows, and the given DOFs as columns (in their order).
Eigen::MatrixXd block(const RowMajor& a, const std::vector<int>& rows, const std::vector<int>& cols,
                      std::vector<int>& local) {
  for (std::size_t k = 0; k < cols.size(); ++k)
    local[static_cast<std::size_t>(cols[k])] = static_cast<int>(k);
  Eigen::MatrixXd b = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(rows.size()),
                                            static_cast<Eigen::Index>(cols.size()));
  for (std::size_t i = 0; i < rows.size(); ++i) {
    for (RowMajor::InnerIterator it(a, rows[i]); it; ++it) {
      const int c = local[static_cast<std::size_t>(it.col())];
      if (c >= 0) b(static_cast<Eigen::Index>(i), c) = it.value();
    }
  }
  for (int c : cols) local[static_cast<std::size_t>(c)] = -1;
  return b;
}

/// The Euclidean norm of row r of `a` (compressed), without overflow or underflow.
double row_norm(const RowMajor& a, int r) {
  const auto begin = a.outerIndexPtr()[r], end = a.outerIndexPtr()[r + 1];
  return Eigen::Map<const Eigen::VectorXd>(a.valuePtr() + begin, end - begin).stableNorm();
}

/// Refuses a group whose dense block (rows x DOFs) would not fit.
void check_block_sizes(const std::vector<ConstraintGroup>& groups) {
  for (const auto& g : groups) {
    const double entries = static_cast<double>(g.rows.size()) * static_cast<double>(g.dofs.size());
    if (entries > kMaxDenseGroupEntries) {
      std::ostringstream s;
      s << g.rows.size() << " constraints coupled through shared DOFs over " << g.dofs.size()
        << " DOFs: beyond the master-slave transform's dense block per group ("
        << kMaxDenseGroupEntries << " entries); use index1 or ggl";
      throw CoupledGroupTooLarge(g.rows.front(), static_cast<int>(g.rows.size()),
                                 static_cast<int>(g.dofs.size()), s.str());
    }
  }
}

/// Refuses a group whose dense blocks would not fit: its rows x DOFs, or its masters coupled with
/// each other in the reduced matrices.
void check_group_sizes(const std::vector<ConstraintGroup>& groups) {
  check_block_sizes(groups);
  for (const auto& g : groups) {
    // Few rows over many DOFs (a floor's average): each slave is replaced by all the group's
    // masters, which then couple with each other in T^T M T, T^T C T and T^T K T, a dense
    // block of masters^2 entries that nothing else bounds (3,000 masters: 9e6 entries, where GGL
    // with the row as a multiplier keeps the model sparse; docs/schemes.md).
    const double masters = static_cast<double>(g.dofs.size() - g.rows.size());
    if (masters * masters > kMaxDenseGroupEntries) {
      std::ostringstream s;
      s << g.rows.size() << " constraint(s) over " << g.dofs.size()
        << " DOFs; eliminating their slaves couples the " << masters
        << " masters with each other, a dense block of " << masters * masters
        << " entries in the reduced M, C and K (beyond " << kMaxDenseGroupEntries
        << "); use index1 or ggl, or auto, whose mixed treatment keeps such rows as multipliers";
      throw CoupledGroupTooLarge(g.rows.front(), static_cast<int>(g.rows.size()),
                                 static_cast<int>(g.dofs.size()), s.str());
    }
  }
}

/// The slaves a column-pivoted QR picks. Pivots on each group's row-normalised block so that a
/// constraint's scale does not bias the choice: the columns a global column-pivoted QR of A
/// would pick, group by group (pivoting on one group never changes another's column norms).
/// Throws std::invalid_argument when the m rows are dependent.
std::vector<int> pivot_slaves(const RowMajor& a, const std::vector<ConstraintGroup>& groups, int m,
                              std::vector<int>& local) {
  std::vector<int> slaves;
  int rank = 0;
  for (const auto& g : groups) {
    Eigen::MatrixXd scaled = block(a, g.rows, g.dofs, local);
    for (Eigen::Index i = 0; i < scaled.rows(); ++i) {
      const double norm = scaled.row(i).stableNorm();  // no underflow
      if (norm > 0.0) scaled.row(i) /= norm;
    }
    Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(scaled.rows(), scaled.cols());
    qr.setThreshold(kSlaveRankTolerance);
    qr.compute(scaled);
    const auto r = static_cast<int>(qr.rank());
    rank += r;
    for (int k = 0; k < r; ++k) {
      slaves.push_back(g.dofs[static_cast<std::size_t>(qr.colsPermutation().indices()[k])]);
    }
  }
  if (rank < m) {
    throw std::invalid_argument("constraint matrix is rank deficient (rank " +
                                std::to_string(rank) + " < " + std::to_string(m) + ")");
  }
  return slaves;
}

/// Where each DOF stands among the slaves and among the masters (-1 where it is not one).
struct DofPlaces {
  std::vector<int> slave_at, master_at;
};

/// One group's slaves solved from its own rows: appends −A_S⁻¹ A_R to T's entries `t` and A_S⁻¹
/// to G's `gt`, and returns the condition number of its row-normalised slave block (infinite
/// when the group has not as many slaves as rows).
double solve_group(const RowMajor& a, const ConstraintGroup& g, const DofPlaces& at,
                   std::vector<int>& local, std::vector<Eigen::Triplet<double>>& t,
                   std::vector<Eigen::Triplet<double>>& gt) {
  std::vector<int> slaves_in, masters_in;
  for (int d : g.dofs)
    (at.slave_at[static_cast<std::size_t>(d)] >= 0 ? slaves_in : masters_in).push_back(d);
  if (slaves_in.size() != g.rows.size()) return INFINITY;
  // The group's rows normalised, D A with D = 1 / |row|: the slave block's condition is the
  // user's constraints', not their units', and the LU below solves D A_S x = D b. On A_S itself
  // FullPivLU's rank threshold (relative to its largest pivot) took a tie written at 1e-150
  // beside a row at 1 for a zero pivot, and its solve set that slave to 0: the tie was broken
  // without a word.
  Eigen::VectorXd inverse_norm(static_cast<Eigen::Index>(g.rows.size()));
  for (Eigen::Index i = 0; i < inverse_norm.size(); ++i) {
    const double norm = row_norm(a, g.rows[static_cast<std::size_t>(i)]);
    inverse_norm[i] = norm > 0.0 ? 1.0 / norm : 1.0;
  }
  const Eigen::MatrixXd normalised = inverse_norm.asDiagonal() * block(a, g.rows, slaves_in, local);
  const Eigen::MatrixXd a_r = inverse_norm.asDiagonal() * block(a, g.rows, masters_in, local);
  const Eigen::VectorXd sv = singular_values(normalised);
  const double smin = sv(sv.size() - 1);
  const double condition = smin > 0.0 ? sv(0) / smin : INFINITY;
  const Eigen::FullPivLU<Eigen::MatrixXd> lu(normalised);
  // A_S⁻¹ A_R; a group without masters (a support, say) has none to solve for: Eigen's solve
  // with an empty right-hand side binds a reference through a null pointer (UBSan).
  const Eigen::MatrixXd s_r =
      masters_in.empty() ? Eigen::MatrixXd(normalised.rows(), 0) : Eigen::MatrixXd(lu.solve(a_r));
  // A_S⁻¹ = (D A_S)⁻¹ D.
  const Eigen::MatrixXd s_g = lu.solve(Eigen::MatrixXd(inverse_norm.asDiagonal()));
  for (std::size_t i = 0; i < slaves_in.size(); ++i) {
    const auto ii = static_cast<Eigen::Index>(i);
    for (std::size_t j = 0; j < masters_in.size(); ++j) {
      const double v = -s_r(ii, static_cast<Eigen::Index>(j));
      if (v != 0.0)
        t.emplace_back(slaves_in[i], at.master_at[static_cast<std::size_t>(masters_in[j])], v);
    }
    for (std::size_t j = 0; j < g.rows.size(); ++j) {
      const double v = s_g(ii, static_cast<Eigen::Index>(j));
      if (v != 0.0) gt.emplace_back(slaves_in[i], g.rows[j], v);
    }
  }
  return condition;
}

}  // namespace

std::vector<int> pivoted_slaves(const Eigen::SparseMatrix<double>& A) {
  const int m = static_cast<int>(A.rows());
  if (m == 0) return {};
  const RowMajor a(A);
  const std::vector<ConstraintGroup> groups = constraint_groups(a);
  check_block_sizes(groups);
  std::vector<int> local(static_cast<std::size_t>(A.cols()), -1);
  std::vector<int> slaves = pivot_slaves(a, groups, m, local);
  std::sort(slaves.begin(), slaves.end());
  return slaves;
}

MasterSlave master_slave_transform(const Eigen::SparseMatrix<double>& A,
                                   const std::vector<int>& preferred_slaves) {
  const int m = static_cast<int>(A.rows()), n = static_cast<int>(A.cols());
  MasterSlave out;
  if (m == 0) {
    out.T.resize(n, n);
    out.T.setIdentity();
    out.G.resize(n, 0);
    for (int i = 0; i < n; ++i) out.masters.push_back(i);
    return out;
  }
  const RowMajor a(A);
  const std::vector<ConstraintGroup> groups = constraint_groups(a);
  std::vector<int> local(static_cast<std::size_t>(n), -1);
  check_group_sizes(groups);
  out.slaves = preferred_slaves.empty() ? pivot_slaves(a, groups, m, local) : preferred_slaves;
  std::sort(out.slaves.begin(), out.slaves.end());
  if (static_cast<int>(out.slaves.size()) != m ||
      std::adjacent_find(out.slaves.begin(), out.slaves.end()) != out.slaves.end()) {
    throw std::invalid_argument("need " + std::to_string(m) +
                                " distinct slave DOFs, one per constraint");
  }
  DofPlaces at{std::vector<int>(static_cast<std::size_t>(n), -1),
               std::vector<int>(static_cast<std::size_t>(n), -1)};
  for (std::size_t k = 0; k < out.slaves.size(); ++k) {
    const int s = out.slaves[k];
    if (s < 0 || s >= n) throw std::invalid_argument("a slave DOF index is out of range");
    at.slave_at[static_cast<std::size_t>(s)] = static_cast<int>(k);
  }
  for (int i = 0; i < n; ++i) {
    if (at.slave_at[static_cast<std::size_t>(i)] < 0) {
      at.master_at[static_cast<std::size_t>(i)] = static_cast<int>(out.masters.size());
      out.masters.push_back(i);
    }
  }
  // Per group: A_S (its rows, its slaves) and A_R (its rows, its masters). Each group's slaves are
  // solved from its own rows, so what roundoff does to them is that group's condition number,
  // of its rows normalised (a row's scale is the user's choice of units: 1e12 u1 = 0 beside
  // u2 = 0 is two well-posed supports, not a condition of 1e12). A group with fewer slaves than
  // rows leaves its block singular (and one with more leaves another short).
  std::vector<Eigen::Triplet<double>> t, gt;
  t.reserve(out.masters.size());
  for (std::size_t k = 0; k < out.masters.size(); ++k) {
    t.emplace_back(out.masters[k], static_cast<int>(k), 1.0);
  }
  double worst = 1.0;  // the largest condition number of a group's row-normalised slave block
  for (const auto& g : groups) worst = std::max(worst, solve_group(a, g, at, local, t, gt));
  if (!(worst <= kMaxSlaveCondition)) {
    std::ostringstream s;
    s << "the slave DOFs do not determine the constraints (slave block condition number " << worst
      << ", rows normalised): choose other slaves";
    throw std::invalid_argument(s.str());
  }
  out.T.resize(n, static_cast<Eigen::Index>(out.masters.size()));
  out.T.setFromTriplets(t.begin(), t.end());
  out.G.resize(n, m);
  out.G.setFromTriplets(gt.begin(), gt.end());
  return out;
}

}  // namespace condyn
