// The rank and redundancy check of the constraints (kRankTolerance), and dropping a redundant one.

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "models/model_builder.hpp"
#include "models/zero_sum.hpp"

namespace condyn {

/// Removes constraint `d.row` from the linear model and reports it.
void ModelBuilder::drop_constraint(const Dependent& d) {
  const auto row = static_cast<std::size_t>(d.row);
  report_.dropped_constraints.push_back("'" + model_.constraints[row].name +
                                        "' (a combination of " + d.others + ")");
  model_.constraints.erase(model_.constraints.begin() + d.row);
  // Row d.row moves to the end (the others keep their order) and is cut off.
  const auto m = static_cast<int>(model_.A.rows());
  Eigen::VectorXi position(m);
  for (int i = 0; i < m; ++i) position[i] = i < d.row ? i : (i == d.row ? m - 1 : i - 1);
  const Eigen::PermutationMatrix<Eigen::Dynamic> to_end(position);
  const Eigen::SparseMatrix<double> moved = to_end * model_.A;
  model_.A = moved.topRows(m - 1);
}

/// Rank of the row-normalised constraint matrix; a dependent set is named with the
/// compatibility of its right-hand sides over the horizon. Constraints that share no DOF, even
/// through others, are independent of each other: each connected group is factored on its own
/// (supports and other single-DOF rows cost nothing), and a group too large for a dense QR is
/// refused rather than left to run out of memory or time.
/// Refuses dependent constraints, naming them, unless they are redundant and the scene asks to
/// drop them ([solve] redundant = "drop", linear models): then returns the one to drop.
std::optional<ModelBuilder::Dependent> ModelBuilder::check_rank() const {
  const int m = model_.constraint_count();
  if (m == 0) return std::nullopt;
  const auto& constraints = model_.constraints;
  const Eigen::SparseMatrix<double, Eigen::RowMajor> a(model_.A);
  std::vector<double> row_norm;
  std::vector<int> parent(static_cast<std::size_t>(m));
  std::vector<int> owner(static_cast<std::size_t>(model_.dofs()), -1);  // first row on a DOF
  const auto root = [&parent](int j) {
    while (parent[static_cast<std::size_t>(j)] != j) {
      j = parent[static_cast<std::size_t>(j)] =
          parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(j)])];
    }
    return j;
  };
  for (int j = 0; j < m; ++j) {
    parent[static_cast<std::size_t>(j)] = j;
    Eigen::VectorXd values(a.row(j).nonZeros());
    Eigen::Index k = 0;
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(a, j); it; ++it) {
      values[k++] = it.value();
      int& first = owner[static_cast<std::size_t>(it.col())];
      if (first < 0) {
        first = j;
      } else {  // join the groups; the root stays the group's first row
        const int r1 = root(first), r2 = root(j);
        parent[static_cast<std::size_t>(std::max(r1, r2))] = std::min(r1, r2);
      }
    }
    // stableNorm: coefficients near the double range neither overflow nor underflow.
    const double norm = values.size() ? values.stableNorm() : 0.0;
    row_norm.push_back(norm);
    if (norm == 0.0) {
      fail(constraints[static_cast<std::size_t>(j)].where,
           "constraint '" + constraints[static_cast<std::size_t>(j)].name +
               "' has no nonzero coefficient");
    }
  }
  std::vector<std::vector<int>> groups(static_cast<std::size_t>(m));
  for (int j = 0; j < m; ++j) groups[static_cast<std::size_t>(root(j))].push_back(j);
  int rank = 0;
  int dep = -1;  // the first dependent constraint, and the combination that shows it
  std::vector<std::pair<int, double>> combo;
  std::vector<int> local(static_cast<std::size_t>(model_.dofs()), -1);
  for (const auto& rows : groups) {
    if (rows.empty()) continue;
    std::vector<int> dofs;
    for (int j : rows) {
      for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(a, j); it; ++it) {
        if (local[static_cast<std::size_t>(it.col())] < 0) {
          local[static_cast<std::size_t>(it.col())] = 0;
          dofs.push_back(static_cast<int>(it.col()));
        }
      }
    }
    std::sort(dofs.begin(), dofs.end());
    for (std::size_t i = 0; i < dofs.size(); ++i) {
      local[static_cast<std::size_t>(dofs[i])] = static_cast<int>(i);
    }
    const auto mc = static_cast<Eigen::Index>(rows.size());
    const auto nc = static_cast<Eigen::Index>(dofs.size());
    if (static_cast<double>(mc) * static_cast<double>(nc) > kMaxDenseEntries) {
      fail(constraints[static_cast<std::size_t>(rows.front())].where,
           "constraint '" + constraints[static_cast<std::size_t>(rows.front())].name +
               "' is coupled through shared DOFs to " + std::to_string(mc - 1) + " others over " +
               std::to_string(nc) + " DOFs: too many for the dense rank check (limit " +
               fmt(kMaxDenseEntries) +
               " constraint-DOF pairs); condyn treats small and medium models");
    }
    // n_c x m_c, a column per constraint, normalised.
    Eigen::MatrixXd at = Eigen::MatrixXd::Zero(nc, mc);
    for (Eigen::Index c = 0; c < mc; ++c) {
      const int j = rows[static_cast<std::size_t>(c)];
      for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(a, j); it; ++it) {
        at(local[static_cast<std::size_t>(it.col())], c) =
            it.value() / row_norm[static_cast<std::size_t>(j)];
      }
    }
    for (int d : dofs) local[static_cast<std::size_t>(d)] = -1;
    Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(at.rows(), at.cols());
    qr.setThreshold(kRankTolerance);
    qr.compute(at);
    const int group_rank = static_cast<int>(qr.rank());
    rank += group_rank;
    if (group_rank == mc || dep >= 0) continue;
    // The first `group_rank` pivot columns are independent; express the first dependent one in
    // them.
    const auto& perm = qr.colsPermutation().indices();
    dep = rows[static_cast<std::size_t>(perm[group_rank])];
    Eigen::MatrixXd basis(at.rows(), group_rank);
    for (int k = 0; k < group_rank; ++k) basis.col(k) = at.col(perm[k]);
    const Eigen::VectorXd y = basis.colPivHouseholderQr().solve(at.col(perm[group_rank]));
    // Combination sum_k w_k c_k = 0 over the involved constraints (normalised rows).
    combo = {{dep, 1.0}};
    for (int k = 0; k < group_rank; ++k) {
      if (std::abs(y[k]) > 1e-12)
        combo.emplace_back(rows[static_cast<std::size_t>(perm[k])], -y[k]);
    }
  }
  if (dep < 0) return std::nullopt;
  std::string names;
  for (const auto& [j, w] : combo) {
    names += (names.empty() ? "'" : ", '") + constraints[static_cast<std::size_t>(j)].name + "'";
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
    fail(constraints[static_cast<std::size_t>(dep)].where,
         "the constraints " + names + " are linearly dependent (constraint matrix rank " +
             std::to_string(rank) + " < " + std::to_string(m) +
             "), and condyn cannot decide whether their right-hand sides are compatible: " +
             verdict.detail +
             "; write the same numbers where the functions are meant to be equal, or remove "
             "one of the constraints");
  }
  const bool compatible = verdict.kind == ZeroSumVerdict::Kind::zero;
  if (compatible && spec_.solve.drop_redundant && !model_.is_nonlinear()) {
    std::string others;
    for (const auto& [j, w] : combo) {
      if (j == dep) continue;
      others +=
          (others.empty() ? "'" : ", '") + constraints[static_cast<std::size_t>(j)].name + "'";
    }
    return Dependent{dep, others};
  }
  fail(constraints[static_cast<std::size_t>(dep)].where,
       "the constraints " + names + " are linearly dependent (constraint matrix rank " +
           std::to_string(rank) + " < " + std::to_string(m) + "); their right-hand sides are " +
           (compatible
                ? std::string("compatible, so the set is redundant: remove one of them") +
                      (model_.is_nonlinear() ? ""
                                             : ", or set [solve] redundant = \"drop\" to drop it")
                : "incompatible (the combination that vanishes on the left leaves " +
                      verdict.detail +
                      " on the right), so the set is conflicting: no motion "
                      "satisfies it"));
}

}  // namespace condyn
