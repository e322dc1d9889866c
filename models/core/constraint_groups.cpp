// Connected groups of constraint rows by shared DOFs (union-find),
// models/core/constraint_groups.hpp.

#include "models/core/constraint_groups.hpp"

#include <algorithm>

namespace condyn {

std::vector<ConstraintGroup> constraint_groups(
    const Eigen::SparseMatrix<double, Eigen::RowMajor>& a) {
  const auto m = static_cast<std::size_t>(a.rows());
  std::vector<int> parent(m);
  std::vector<int> owner(static_cast<std::size_t>(a.cols()), -1);  // first row on a DOF
  const auto root = [&parent](int j) {
    while (parent[static_cast<std::size_t>(j)] != j) {
      j = parent[static_cast<std::size_t>(j)] =
          parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(j)])];
    }
    return j;
  };
  for (std::size_t j = 0; j < m; ++j) {
    parent[j] = static_cast<int>(j);
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(a, static_cast<int>(j)); it;
         ++it) {
      int& first = owner[static_cast<std::size_t>(it.col())];
      if (first < 0) {
        first = static_cast<int>(j);
      } else {  // join the groups; the root stays the group's first row
        const int r1 = root(first), r2 = root(static_cast<int>(j));
        parent[static_cast<std::size_t>(std::max(r1, r2))] = std::min(r1, r2);
      }
    }
  }
  std::vector<int> slot(m, -1);  // root row -> index in `out`
  std::vector<ConstraintGroup> out;
  for (std::size_t j = 0; j < m; ++j) {
    const auto r = static_cast<std::size_t>(root(static_cast<int>(j)));
    if (slot[r] < 0) {
      slot[r] = static_cast<int>(out.size());
      out.emplace_back();
    }
    out[static_cast<std::size_t>(slot[r])].rows.push_back(static_cast<int>(j));
  }
  std::vector<bool> seen(static_cast<std::size_t>(a.cols()), false);
  for (auto& g : out) {
    for (int j : g.rows) {
      for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(a, j); it; ++it) {
        if (!seen[static_cast<std::size_t>(it.col())]) {
          seen[static_cast<std::size_t>(it.col())] = true;
          g.dofs.push_back(static_cast<int>(it.col()));
        }
      }
    }
    std::sort(g.dofs.begin(), g.dofs.end());
  }
  return out;
}

}  // namespace condyn
