// Supernodal triangular solves on two lanes (models/core/supernodal_solve.hpp).

#include "models/core/supernodal_solve.hpp"

#include <Eigen/Core>
#include <algorithm>
#include <cstddef>
#include <functional>
#include <numeric>

#include "models/core/second_lane.hpp"

namespace condyn {

namespace {

using Column = Eigen::Map<Eigen::VectorXd>;
using ConstColumn = Eigen::Map<const Eigen::VectorXd>;

/// A lane may hold at most this share of the two lanes' entries: the split goes down the tree
/// until it does (or nothing is left to split).
constexpr double kBalancedShare = 0.55;
/// The supernodes split on the way (the caller sweeps them alone) may hold at most this share of
/// the factor's entries: a chain-like tree (a strip's band) stops splitting early, and its solve
/// then runs mostly on one lane.
constexpr double kMostShared = 0.2;

/// The supernodal elimination tree: parent[s] (−1 at a root) and entries of each supernode.
struct SupernodeTree {
  std::vector<int> parent;
  std::vector<double> entries;
  std::vector<std::vector<int>> children;
  std::vector<int> roots;
};

SupernodeTree tree_of(const SupernodalFactorView& f) {
  SupernodeTree t;
  t.parent.assign(f.nsuper, -1);
  t.entries.resize(f.nsuper);
  t.children.resize(f.nsuper);
  std::vector<int> owner(f.n);
  for (int s = 0; s < f.nsuper; ++s) std::fill(&owner[f.super[s]], &owner[f.super[s + 1]], s);
  for (int s = 0; s < f.nsuper; ++s) {
    const int ncol = f.super[s + 1] - f.super[s], nrow = f.pi[s + 1] - f.pi[s];
    t.entries[s] = static_cast<double>(nrow) * ncol;
    if (nrow > ncol) t.parent[s] = owner[f.s_rows[f.pi[s] + ncol]];
    (t.parent[s] >= 0 ? t.children[t.parent[s]] : t.roots).push_back(s);
  }
  return t;
}

}  // namespace

SupernodalSolve::SupernodalSolve(const SupernodalFactorView& factor, SecondLane& lane)
    : factor_(factor), lane_runner_(&lane) {
  const SupernodeTree tree = tree_of(factor_);
  const int ns = factor_.nsuper;
  // Entries of each subtree: children come before their parent.
  std::vector<double> subtree = tree.entries;
  for (int s = 0; s < ns; ++s) {
    if (tree.parent[s] >= 0) subtree[tree.parent[s]] += subtree[s];
  }
  // Split the largest subtree into its children until two bins, filled largest first, balance,
  // or the split supernodes (swept by the caller alone) would hold too much of the factor.
  double total = 0.0;
  for (int s : tree.roots) total += subtree[s];
  std::vector<int> candidates = tree.roots;
  const auto by_size = [&](int a, int b) {
    return subtree[a] > subtree[b] || (subtree[a] == subtree[b] && a < b);
  };
  std::vector<int> tops[2];
  double split_entries = 0.0;
  for (;;) {
    std::sort(candidates.begin(), candidates.end(), by_size);
    double filled[2] = {0.0, 0.0};
    tops[0].clear();
    tops[1].clear();
    for (int s : candidates) {
      const int b = filled[0] <= filled[1] ? 0 : 1;
      filled[b] += subtree[s];
      tops[b].push_back(s);
    }
    const double both = filled[0] + filled[1];
    larger_lane_share_ = both > 0.0 ? std::max(filled[0], filled[1]) / both : 0.0;
    if (larger_lane_share_ <= kBalancedShare || candidates.empty()) break;
    const int split = candidates.front();
    if (tree.children[split].empty() || split_entries + tree.entries[split] > kMostShared * total) {
      break;
    }
    split_entries += tree.entries[split];
    candidates.erase(candidates.begin());
    candidates.insert(candidates.end(), tree.children[split].begin(), tree.children[split].end());
  }
  // Each top's subtree goes to its bin; the rest (their ancestors) is shared.
  std::vector<int> bin(ns, -1);
  subtree_end_.assign(ns, factor_.n);
  for (int b = 0; b < 2; ++b) {
    for (int top : tops[b]) {
      std::vector<int> stack{top};
      while (!stack.empty()) {
        const int s = stack.back();
        stack.pop_back();
        bin[s] = b;
        subtree_end_[s] = factor_.super[top + 1];
        stack.insert(stack.end(), tree.children[s].begin(), tree.children[s].end());
      }
    }
  }
  double shared_entries = 0.0;
  for (int s = 0; s < ns; ++s) {
    if (bin[s] < 0) {
      shared_.push_back(s);
      shared_entries += tree.entries[s];
      for (int k = factor_.super[s]; k < factor_.super[s + 1]; ++k) shared_columns_.push_back(k);
    } else {
      lane_[bin[s]].push_back(s);
    }
  }
  shared_share_ = total > 0.0 ? shared_entries / total : 0.0;
  int widest = 0;
  for (int s = 0; s < ns; ++s) widest = std::max(widest, factor_.pi[s + 1] - factor_.pi[s]);
  y_.resize(factor_.n);
  shared_rows_.assign(factor_.n, 0.0);
  work_[0].resize(widest);
  work_[1].resize(widest);
}

SupernodalSolve::~SupernodalSolve() = default;

int SupernodalSolve::lanes() const { return lane_runner_->lanes(); }

/// L₁₁ y₁ = y₁ on supernode sn's columns, then y₂ −= L₂₁ y₁ on the rows below, column by column
/// (each entry of the block read once, in storage order); rows from `first_shared_row` on are
/// subtracted from `shared_rows` instead of y. `work` holds the block's rows.
void SupernodalSolve::forward(int sn, double* y, double* shared_rows, int first_shared_row,
                              double* work) const {
  const SupernodalFactorView& f = factor_;
  const int k1 = f.super[sn], ncol = f.super[sn + 1] - k1;
  const int p = f.pi[sn], nrow = f.pi[sn + 1] - p;
  const double* block = f.x + f.px[sn];
  std::copy_n(y + k1, ncol, work);
  std::fill(work + ncol, work + nrow, 0.0);
  for (int j = 0; j < ncol; ++j) {
    const double* column = block + static_cast<std::ptrdiff_t>(j) * nrow;
    const double yj = work[j] / column[j];
    work[j] = yj;
    Column(work + j + 1, nrow - j - 1) -= yj * ConstColumn(column + j + 1, nrow - j - 1);
  }
  std::copy_n(work, ncol, y + k1);
  const int* rows = f.s_rows + p;
  int i = ncol;
  for (; i < nrow && rows[i] < first_shared_row; ++i) y[rows[i]] += work[i];
  for (; i < nrow; ++i) shared_rows[rows[i]] += work[i];
}

/// y₁ −= L₂₁ᵀ y₂ from the rows below supernode sn, then L₁₁ᵀ y₁ = y₁, column by column from the
/// last (one dot product with each column).
void SupernodalSolve::backward(int sn, double* y, double* work) const {
  const SupernodalFactorView& f = factor_;
  const int k1 = f.super[sn], ncol = f.super[sn + 1] - k1;
  const int p = f.pi[sn], nrow = f.pi[sn + 1] - p;
  const double* block = f.x + f.px[sn];
  const int* rows = f.s_rows + p;
  std::copy_n(y + k1, ncol, work);
  for (int i = ncol; i < nrow; ++i) work[i] = y[rows[i]];
  for (int j = ncol - 1; j >= 0; --j) {
    const double* column = block + static_cast<std::ptrdiff_t>(j) * nrow;
    const int below = nrow - j - 1;
    work[j] = (work[j] - ConstColumn(column + j + 1, below).dot(ConstColumn(work + j + 1, below))) /
              column[j];
  }
  std::copy_n(work, ncol, y + k1);
}

void SupernodalSolve::solve_in_place(double* x) {
  const int n = factor_.n;
  double* y = y_.data();
  for (int k = 0; k < n; ++k) y[k] = x[factor_.perm[k]];
  for (int k : shared_columns_) shared_rows_[k] = 0.0;
  // Forward: the lanes' subtrees side by side (lane 1's updates to shared rows kept apart),
  // then the shared ancestors.
  lane_runner_->run(
      [&] {
        for (int s : lane_[0]) forward(s, y, y, n, work_[0].data());
      },
      [&] {
        for (int s : lane_[1]) forward(s, y, shared_rows_.data(), subtree_end_[s], work_[1].data());
      });
  for (int k : shared_columns_) y[k] += shared_rows_[k];
  for (int s : shared_) forward(s, y, y, n, work_[0].data());
  // Backward: the shared ancestors, then the lanes' subtrees side by side.
  for (auto s = shared_.rbegin(); s != shared_.rend(); ++s) backward(*s, y, work_[0].data());
  lane_runner_->run(
      [&] {
        for (auto s = lane_[0].rbegin(); s != lane_[0].rend(); ++s)
          backward(*s, y, work_[0].data());
      },
      [&] {
        for (auto s = lane_[1].rbegin(); s != lane_[1].rend(); ++s)
          backward(*s, y, work_[1].data());
      });
  for (int k = 0; k < n; ++k) x[factor_.perm[k]] = y[k];
}

}  // namespace condyn
