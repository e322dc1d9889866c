// Reverse Cuthill–McKee and a factor's entry count (dae/linsolve/band_ordering.hpp).

#include "dae/linsolve/band_ordering.hpp"

#include <algorithm>
#include <cstddef>
#include <numeric>

namespace condyn {

namespace {

std::size_t at(long k) { return static_cast<std::size_t>(k); }
std::size_t at(int k) { return static_cast<std::size_t>(k); }

long degree(const SymmetricPattern& g, int v) { return g.outer[at(v) + 1] - g.outer[at(v)]; }

/// Breadth-first levels from `start` over the unvisited vertices, each vertex's unvisited
/// neighbours appended by increasing degree (ties by index); marks them in `level` (≥ 0) and
/// appends them to `order`. Returns the last level's number.
int cuthill_mckee_levels(const SymmetricPattern& g, int start, std::vector<int>& level,
                         std::vector<int>& order) {
  const std::size_t first = order.size();
  order.push_back(start);
  level[at(start)] = 0;
  for (std::size_t head = first; head < order.size(); ++head) {
    const int v = order[head];
    const std::size_t added = order.size();
    for (long p = g.outer[at(v)]; p < g.outer[at(v) + 1]; ++p) {
      const int w = g.inner[at(p)];
      if (level[at(w)] < 0) {
        level[at(w)] = level[at(v)] + 1;
        order.push_back(w);
      }
    }
    std::sort(order.begin() + static_cast<std::ptrdiff_t>(added), order.end(), [&](int a, int b) {
      const long da = degree(g, a), db = degree(g, b);
      return da != db ? da < db : a < b;
    });
  }
  return level[at(order.back())];
}

}  // namespace

SymmetricPattern symmetric_pattern(int n, const int* outer, const int* inner) {
  SymmetricPattern g;
  g.size = n;
  g.outer.assign(at(n) + 1, 0);
  for (int j = 0; j < n; ++j) {
    for (int p = outer[j]; p < outer[j + 1]; ++p) {
      const int i = inner[p];
      if (i == j) continue;
      ++g.outer[at(j) + 1];
      ++g.outer[at(i) + 1];
    }
  }
  std::partial_sum(g.outer.begin(), g.outer.end(), g.outer.begin());
  g.inner.resize(at(g.outer[at(n)]));
  std::vector<long> next(g.outer.begin(), g.outer.end() - 1);
  for (int j = 0; j < n; ++j) {
    for (int p = outer[j]; p < outer[j + 1]; ++p) {
      const int i = inner[p];
      if (i == j) continue;
      g.inner[at(next[at(j)]++)] = i;
      g.inner[at(next[at(i)]++)] = j;
    }
  }
  // Sort each column and drop the duplicates (an entry and its transpose both present), compacting
  // in place.
  long kept = 0;
  for (int j = 0; j < n; ++j) {
    const auto begin = g.inner.begin() + g.outer[at(j)];
    const auto end = g.inner.begin() + g.outer[at(j) + 1];
    std::sort(begin, end);
    const auto last = std::unique(begin, end);
    g.outer[at(j)] = kept;
    kept = std::copy(begin, last, g.inner.begin() + kept) - g.inner.begin();
  }
  g.outer[at(n)] = kept;
  g.inner.resize(at(kept));
  g.inner.shrink_to_fit();
  return g;
}

std::vector<int> reverse_cuthill_mckee(const SymmetricPattern& g) {
  const int n = g.size;
  std::vector<int> order;
  order.reserve(at(n));
  std::vector<int> level(at(n), -1);
  std::vector<int> by_degree(at(n));
  std::iota(by_degree.begin(), by_degree.end(), 0);
  std::stable_sort(by_degree.begin(), by_degree.end(),
                   [&](int a, int b) { return degree(g, a) < degree(g, b); });
  for (const int seed : by_degree) {
    if (level[at(seed)] >= 0) continue;  // in a component already ordered
    const std::size_t first = order.size();
    int eccentricity = cuthill_mckee_levels(g, seed, level, order);
    for (;;) {  // George and Liu's pseudo-peripheral vertex
      int candidate = order.back();
      for (std::size_t k = first; k < order.size(); ++k) {
        const int v = order[k];
        if (level[at(v)] == eccentricity && degree(g, v) < degree(g, candidate)) candidate = v;
      }
      for (std::size_t k = first; k < order.size(); ++k) level[at(order[k])] = -1;
      order.resize(first);
      const int reached = cuthill_mckee_levels(g, candidate, level, order);
      if (reached <= eccentricity) break;
      eccentricity = reached;
    }
  }
  std::reverse(order.begin(), order.end());
  return order;
}

long cholesky_entries_below_diagonal(const SymmetricPattern& g, const std::vector<int>& order,
                                     long limit) {
  const int n = g.size;
  std::vector<int> position(at(n));
  for (int k = 0; k < n; ++k) position[at(order[at(k)])] = k;
  // Row k of the factor is the union of the paths from each i < k adjacent to k up the
  // elimination tree, stopped at vertices already marked for row k (Liu; as in LDL's symbolic
  // analysis). Each step up a path is one entry L(k, i).
  std::vector<int> parent(at(n), -1);
  std::vector<int> mark(at(n), -1);
  long count = 0;
  for (int k = 0; k < n; ++k) {
    mark[at(k)] = k;
    const int v = order[at(k)];
    for (long p = g.outer[at(v)]; p < g.outer[at(v) + 1]; ++p) {
      for (int i = position[at(g.inner[at(p)])]; i < k && mark[at(i)] != k; i = parent[at(i)]) {
        if (parent[at(i)] < 0) parent[at(i)] = k;
        mark[at(i)] = k;
        if (++count > limit) return limit + 1;
      }
    }
  }
  return count;
}

}  // namespace condyn
