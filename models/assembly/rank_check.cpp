// The rank and redundancy check of the constraints (kRankTolerance), and dropping a redundant one.

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <optional>
#include <stdexcept>

#include "models/assembly/model_builder.hpp"
#include "models/core/constraint_groups.hpp"
#include "models/core/eigen_decompositions.hpp"
#include "models/core/sparse_qr.hpp"
#include "models/core/zero_sum.hpp"

namespace condyn {

/// Removes constraint `d.row` from the model and reports it. A nonlinear model's system keeps
/// every row until the set is final (keep_independent_rows); the dropped row must hold at the
/// start like the others, or the set conflicts there (its force is carried by the rest, but its
/// violation would go unseen).
void ModelBuilder::drop_constraint(const Dependent& d) {
  const auto row = static_cast<std::size_t>(d.row);
  if (model_.is_nonlinear()) {
    if (kept_rows_.empty()) {
      kept_rows_.resize(static_cast<std::size_t>(model_.constraint_count()));
      std::iota(kept_rows_.begin(), kept_rows_.end(), 0);
    }
    check_nonlinear_rows({d.row});
    kept_rows_.erase(kept_rows_.begin() + d.row);
  }
  // The constraints it combines take its force as well: their reactions are one way of sharing
  // the force among the redundant set, not the unique answer a determinate set gives.
  report_.dropped_constraints.push_back("'" + model_.constraints[row].name +
                                        "' (a combination of " + d.others +
                                        "; their reactions carry its force too: not unique)");
  model_.dropped_constraints.push_back(model_.constraints[row].name);
  model_.constraints.erase(model_.constraints.begin() + d.row);
  if (!row_joint_.empty()) {  // a mechanism's rows: their joints stay aligned with the rows
    dropped_joint_rows_.emplace_back(row_joint_[row], model_.dropped_constraints.back());
    row_joint_.erase(row_joint_.begin() + d.row);
    row_rheonomic_.erase(row_rheonomic_.begin() + d.row);
  }
  // Row d.row moves to the end (the others keep their order) and is cut off.
  const auto m = static_cast<int>(model_.A.rows());
  Eigen::VectorXi position(m);
  for (int i = 0; i < m; ++i) position[i] = i < d.row ? i : (i == d.row ? m - 1 : i - 1);
  const Eigen::PermutationMatrix<Eigen::Dynamic> to_end(position);
  const Eigen::SparseMatrix<double> moved = to_end * model_.A;
  model_.A = moved.topRows(m - 1);
}

namespace {

/// Rank of one connected group of constraints, given as the columns of its row-normalised
/// transpose (DOFs x constraints), and, when deficient, the first dependent column in pivot order
/// with its combination of the independent ones: at.col(dep) = sum_k y_k at.col(basis_k).
struct GroupRank {
  int rank = 0;
  int dep = -1;                               ///< local column; -1 when of full rank
  std::vector<std::pair<int, double>> combo;  ///< (local column, y_k)
};

/// Column-pivoted dense QR: kept for groups up to kDenseBlockEntries, where it is cheap, so the
/// decisions on every small scene stay exactly those of before.
GroupRank dense_group_rank(const Eigen::SparseMatrix<double>& at_sparse) {
  const Eigen::MatrixXd at(at_sparse);
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(at.rows(), at.cols());
  qr.setThreshold(kRankTolerance);
  qr.compute(at);
  GroupRank g;
  g.rank = static_cast<int>(qr.rank());
  if (g.rank == at.cols()) return g;
  // The first `rank` pivot columns are independent; express the first dependent one in them.
  const auto& perm = qr.colsPermutation().indices();
  g.dep = perm[g.rank];
  Eigen::MatrixXd basis(at.rows(), g.rank);
  for (int k = 0; k < g.rank; ++k) basis.col(k) = at.col(perm[k]);
  const Eigen::VectorXd y = basis.colPivHouseholderQr().solve(at.col(g.dep));
  for (int k = 0; k < g.rank; ++k) g.combo.emplace_back(perm[k], y[k]);
  return g;
}

/// SuiteSparseQR with the same meaning of the tolerance: the columns have unit norm, and a column
/// whose part outside the span of the earlier ones is below kRankTolerance is dependent. SPQR
/// orders the columns to limit fill (COLAMD) and moves dependent ones last; its rank detection
/// (Heath's) can miss a dependency that column pivoting would find, never invent one that the
/// least-squares residual below does not confirm.
GroupRank sparse_group_rank(const Eigen::SparseMatrix<double>& at) {
  const SparseQrRank qr = sparse_qr_rank(at, kRankTolerance);
  GroupRank g;
  g.rank = qr.rank;
  const auto cols = static_cast<int>(at.cols());
  if (g.rank == cols) return g;
  const auto& order = qr.order;  // column order[k] of A^T is the k-th
  // The independent columns, and the first dependent one expressed in them (least squares).
  std::vector<Eigen::Triplet<double>> t;
  for (int k = 0; k < g.rank; ++k) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(at, order[static_cast<std::size_t>(k)]); it;
         ++it)
      t.emplace_back(static_cast<int>(it.row()), k, it.value());
  }
  Eigen::SparseMatrix<double> basis(at.rows(), g.rank);
  basis.setFromTriplets(t.begin(), t.end());
  std::optional<SparseLeastSquares> ls;
  if (g.rank > 0) ls.emplace(basis, kRankTolerance);
  for (int k = g.rank; k < cols; ++k) {
    const int c = order[static_cast<std::size_t>(k)];
    const Eigen::VectorXd target = at.col(c);
    Eigen::VectorXd y = Eigen::VectorXd::Zero(g.rank);
    if (ls) y = ls->solve(target);
    if ((basis * y - target).norm() > kRankTolerance) continue;  // not confirmed
    g.dep = c;
    for (int j = 0; j < g.rank; ++j) g.combo.emplace_back(order[static_cast<std::size_t>(j)], y[j]);
    return g;
  }
  g.rank = cols;  // no dependency confirmed
  return g;
}

/// The refusal of a set dependent at the initial configuration with nonlinear rows among it
/// (`nonlinear`, quoted): their coefficients are those of t = 0, so the set may be independent
/// at every other configuration (a singular one) or everywhere dependent (a redundant joint).
std::string nonlinear_dependence(const std::string& names, const std::string& rank_text,
                                 const std::string& nonlinear) {
  return "the constraints " + names + " are linearly dependent at the initial configuration (" +
         rank_text + "): " + nonlinear +
         (nonlinear.find(',') == std::string::npos ? " is" : " are") +
         " nonlinear, so this is a singular configuration of the set, which may be independent "
         "everywhere else; the multipliers are not determined there and no scheme can start from "
         "it: start away from it (other [initial] displacements, or a prescribed motion that "
         "starts elsewhere); if the constraints are dependent everywhere (a redundant joint), "
         "remove one of them or set [solve] redundant = \"drop\" to drop it";
}

using RowMajor = Eigen::SparseMatrix<double, Eigen::RowMajor>;
using Combination = std::vector<std::pair<int, double>>;  ///< (constraint row, weight)

/// The Euclidean norm of each row of `a` (0 for a row without nonzeros).
std::vector<double> row_norms(const RowMajor& a) {
  std::vector<double> out;
  for (int j = 0; j < a.rows(); ++j) {
    Eigen::VectorXd values(a.row(j).nonZeros());
    Eigen::Index k = 0;
    for (RowMajor::InnerIterator it(a, j); it; ++it) values[k++] = it.value();
    // stableNorm: coefficients near the double range neither overflow nor underflow.
    out.push_back(values.size() ? values.stableNorm() : 0.0);
  }
  return out;
}

/// The rank of the rows of `a` (none of norm 0), and the first dependent row found with the
/// combination sum_k w_k c_k = 0 of normalised rows that shows it (dep -1 when of full rank).
struct Dependence {
  int rank = 0;
  int dep = -1;
  Combination combo;
  ConstraintGroup group;  ///< the connected group of the dependent row
};

/// The rank of one connected group of rows, factored as the columns of its normalised transpose:
/// small groups by a dense column-pivoted QR, larger ones by SuiteSparseQR. `local` maps every
/// DOF to -1 on entry and on return.
GroupRank group_rank(const RowMajor& a, const std::vector<double>& row_norm,
                     const ConstraintGroup& group, std::vector<int>& local) {
  const auto& rows = group.rows;
  const auto& dofs = group.dofs;
  for (std::size_t i = 0; i < dofs.size(); ++i) {
    local[static_cast<std::size_t>(dofs[i])] = static_cast<int>(i);
  }
  const auto mc = static_cast<Eigen::Index>(rows.size());
  const auto nc = static_cast<Eigen::Index>(dofs.size());
  // n_c x m_c, a column per constraint, normalised.
  std::vector<Eigen::Triplet<double>> entries;
  for (Eigen::Index c = 0; c < mc; ++c) {
    const int j = rows[static_cast<std::size_t>(c)];
    for (RowMajor::InnerIterator it(a, j); it; ++it) {
      entries.emplace_back(local[static_cast<std::size_t>(it.col())], static_cast<int>(c),
                           it.value() / row_norm[static_cast<std::size_t>(j)]);
    }
  }
  for (int d : dofs) local[static_cast<std::size_t>(d)] = -1;
  Eigen::SparseMatrix<double> at(nc, mc);
  at.setFromTriplets(entries.begin(), entries.end());
  return static_cast<double>(mc) * static_cast<double>(nc) <= kDenseBlockEntries
             ? dense_group_rank(at)
             : sparse_group_rank(at);
}

/// Constraints that share no DOF, even through others, are independent of each other: each
/// connected group is factored on its own, so the cost follows the nonzeros.
Dependence first_dependence(const RowMajor& a, const std::vector<double>& row_norm, int dofs) {
  Dependence out;
  std::vector<int> local(static_cast<std::size_t>(dofs), -1);
  for (const auto& group : constraint_groups(a)) {
    const GroupRank g = group_rank(a, row_norm, group, local);
    out.rank += g.rank;
    if (g.dep < 0 || out.dep >= 0) continue;
    const auto& rows = group.rows;
    out.dep = rows[static_cast<std::size_t>(g.dep)];
    out.group = group;
    // Combination sum_k w_k c_k = 0 over the involved constraints (normalised rows).
    out.combo = {{out.dep, 1.0}};
    for (const auto& [k, y] : g.combo) {
      if (std::abs(y) > 1e-12) out.combo.emplace_back(rows[static_cast<std::size_t>(k)], -y);
    }
  }
  return out;
}

/// The constraints of the combination but row `skip`, quoted; beyond kNamed, counted (a chain of
/// 4,000 tied rows named every one on a single 35 kB line).
std::string quoted_names(const Combination& combo, const std::vector<Constraint>& constraints,
                         int skip) {
  constexpr std::size_t kNamed = 12;
  std::string text;
  std::size_t shown = 0, all = 0;
  for (const auto& [j, w] : combo) {
    if (j == skip) continue;
    ++all;
    if (shown == kNamed) continue;
    text += (text.empty() ? "'" : ", '") + constraints[static_cast<std::size_t>(j)].name + "'";
    ++shown;
  }
  if (all > shown) {
    text += " and " + std::to_string(all - shown) + " more (" + std::to_string(all) + " in all)";
  }
  return text;
}

/// The constraints of the combination for which `pick` holds, all quoted.
template <class Pick>
std::string picked_names(const Combination& combo, const std::vector<Constraint>& constraints,
                         Pick pick) {
  std::string text;
  for (const auto& [j, w] : combo) {
    const auto& c = constraints[static_cast<std::size_t>(j)];
    if (pick(c)) text += (text.empty() ? "'" : ", '") + c.name + "'";
  }
  return text;
}

/// The member of a redundant combination to drop. Any member may go: the others span it. A
/// velocity-level row goes before a position-level one, whatever their order in the scene: a
/// position row holds the motion at position level under every scheme, and its drift stays
/// measured. A member of small weight stays (the rest would span it only by that margin).
int row_to_drop(const Combination& combo, const std::vector<Constraint>& constraints, int dep) {
  constexpr double kSwapWeight = 1e-3;
  const auto level = [&](int j) { return constraints[static_cast<std::size_t>(j)].level; };
  int drop = dep;
  for (const auto& [j, w] : combo) {
    if (level(drop) == ConstraintSpec::Level::position &&
        level(j) == ConstraintSpec::Level::velocity && std::abs(w) >= kSwapWeight) {
      drop = j;
    }
  }
  return drop;
}

/// The refusal of a dependent set of linear rows: redundant (`compatible`, with what would let
/// condyn drop one) or conflicting (`detail`: what the combination leaves on the right).
std::string linear_dependence(const std::string& names, const std::string& rank_text,
                              bool compatible, const std::string& drop_hint,
                              const std::string& detail, const std::string& velocity_rows) {
  // A velocity row's position form a·u = a·u(0) + ∫ h dt takes a·u(0) from [initial]: rows that
  // agree as written (one the other's derivative) conflict through the initial displacements.
  const std::string through_initial =
      velocity_rows.empty()
          ? std::string()
          : ". The velocity row" +
                std::string(velocity_rows.find(',') == std::string::npos ? " " : "s ") +
                velocity_rows +
                " holds at position level as a·u = a·u(0) + the integral of its value, with "
                "a·u(0) from the initial displacements: if the rows agree as written, the "
                "initial displacements ([initial]) are what conflicts with them";
  return "the constraints " + names + " are linearly dependent (" + rank_text +
         "); their right-hand sides are " +
         (compatible
              ? std::string("compatible, so the set is redundant: remove one of them") + drop_hint
              : "incompatible (the combination that vanishes on the left leaves " + detail +
                    " on the right), so the set is conflicting: no motion "
                    "satisfies it" +
                    through_initial);
}

}  // namespace

/// Rank of the row-normalised constraint matrix; a dependent set is named with the
/// compatibility of its right-hand sides over the horizon. Constraints that share no DOF, even
/// through others, are independent of each other: each connected group is factored on its own
/// (supports and other single-DOF rows cost nothing), small groups by a dense column-pivoted QR,
/// larger ones by SuiteSparseQR, so the cost follows the nonzeros.
/// Refuses dependent constraints, naming them, unless they are redundant and the scene asks to
/// drop them ([solve] redundant = "drop", linear models): then returns the one to drop.
std::optional<ModelBuilder::Dependent> ModelBuilder::check_rank() const {
  const int m = model_.constraint_count();
  if (m == 0) return std::nullopt;
  const auto& constraints = model_.constraints;
  const RowMajor a(model_.A);
  const std::vector<double> row_norm = row_norms(a);
  for (int j = 0; j < m; ++j) {
    if (row_norm[static_cast<std::size_t>(j)] == 0.0) {
      fail(constraints[static_cast<std::size_t>(j)].where,
           "constraint '" + constraints[static_cast<std::size_t>(j)].name +
               "' has no nonzero coefficient");
    }
  }
  const auto [rank, dep, combo, group] = first_dependence(a, row_norm, model_.dofs());
  if (dep < 0) return std::nullopt;
  // "rank r < m", and when more than one row depends on others, that these are the first found.
  const std::string rank_text =
      "constraint matrix rank " + std::to_string(rank) + " < " + std::to_string(m) +
      (m - rank > 1 ? ": " + std::to_string(m - rank) +
                          " constraints depend on others, these are the first found"
                    : std::string());
  const std::string names = quoted_names(combo, constraints, -1);
  const SourcePoint& where = constraints[static_cast<std::size_t>(dep)].where;
  // A nonlinear row's coefficients are those of the initial configuration: dependent there, the
  // set may be independent at every other one (a pendulum driven along x from the horizontal:
  // the rod's row and the drive are parallel at t = 0 only), and its right-hand sides say
  // nothing about a conflict. The schemes need independent rows where they start.
  const std::string nonlinear_rows = picked_names(
      combo, constraints, [](const Constraint& c) { return !c.nonlinear_kind.empty(); });
  if (!nonlinear_rows.empty()) {
    if (!spec_.solve.drop_redundant)
      fail(where, nonlinear_dependence(names, rank_text, nonlinear_rows));
    // Their right-hand sides are 0 or drives: redundant when the dependence holds along the
    // motion, which the second-order test screens (a singular start is refused there).
    check_redundant_at_second_order(combo, row_norm, group, names, rank_text);
    const int drop = row_to_drop(combo, constraints, dep);
    return Dependent{drop, quoted_names(combo, constraints, drop)};
  }
  // Compatible when the same combination of the right-hand sides vanishes identically over
  // [0, t_end]: decided from the terms (zero_sum.hpp), never from samples, which two
  // different functions can share (0 and 1 - cos(64 pi t) agree at every multiple of 1/32).
  std::vector<std::pair<double, const TimeFunction*>> sum;
  for (const auto& [j, w] : combo) {
    const auto& c = constraints[static_cast<std::size_t>(j)];
    sum.emplace_back(w / row_norm[static_cast<std::size_t>(j)], &c.position_value);
  }
  const ZeroSumVerdict verdict = weighted_sum_vanishes(sum, spec_.solve.t_end);
  if (verdict.kind == ZeroSumVerdict::Kind::undecided) {
    fail(where, "the constraints " + names + " are linearly dependent (" + rank_text +
                    "), and condyn cannot decide whether their right-hand sides are compatible: " +
                    verdict.detail +
                    "; write the same numbers where the functions are meant to be equal, or "
                    "remove one of the constraints");
  }
  const bool compatible = verdict.kind == ZeroSumVerdict::Kind::zero;
  if (compatible && spec_.solve.drop_redundant) {
    const int drop = row_to_drop(combo, constraints, dep);
    return Dependent{drop, quoted_names(combo, constraints, drop)};
  }
  std::string drop_hint = ", or set [solve] redundant = \"drop\" to drop it";
  if (m - rank > 1) drop_hint += " (a run then lists each redundant constraint it drops)";
  const std::string velocity_rows = picked_names(combo, constraints, [](const Constraint& c) {
    return c.level == ConstraintSpec::Level::velocity;
  });
  fail(where,
       linear_dependence(names, rank_text, compatible, drop_hint, verdict.detail, velocity_rows));
}

}  // namespace condyn
