// Reverse Cuthill–McKee and the factor entry count (dae/linsolve/band_ordering.hpp), and KLU
// keeping that ordering only where its factor is no larger (dae/linsolve/fixed_pattern_klu.hpp).

#include <doctest/doctest.h>

#include <Eigen/Sparse>
#include <algorithm>
#include <numeric>
#include <random>
#include <vector>

#include "dae/linsolve/band_ordering.hpp"
#include "dae/linsolve/fixed_pattern_klu.hpp"

using namespace condyn;

namespace test_band_ordering {

namespace {

using Sparse = Eigen::SparseMatrix<double>;

/// A symmetric positive definite matrix whose graph has the given edges, relabelled by `label`.
Sparse graph_matrix(int n, const std::vector<std::pair<int, int>>& edges,
                    const std::vector<int>& label) {
  std::vector<Eigen::Triplet<double>> t;
  std::vector<double> diagonal(static_cast<std::size_t>(n), 1.0);
  for (const auto& [a, b] : edges) {
    const int i = label[static_cast<std::size_t>(a)], j = label[static_cast<std::size_t>(b)];
    t.emplace_back(i, j, -1.0);
    t.emplace_back(j, i, -1.0);
    diagonal[static_cast<std::size_t>(i)] += 1.0;
    diagonal[static_cast<std::size_t>(j)] += 1.0;
  }
  for (int i = 0; i < n; ++i) t.emplace_back(i, i, diagonal[static_cast<std::size_t>(i)]);
  Sparse a(n, n);
  a.setFromTriplets(t.begin(), t.end());
  a.makeCompressed();
  return a;
}

std::vector<int> shuffled(int n, unsigned seed) {
  std::vector<int> label(static_cast<std::size_t>(n));
  std::iota(label.begin(), label.end(), 0);
  std::shuffle(label.begin(), label.end(), std::mt19937(seed));
  return label;
}

/// A strip of `length` × `width` grid vertices with both diagonals of each cell.
std::vector<std::pair<int, int>> strip_edges(int length, int width) {
  std::vector<std::pair<int, int>> e;
  const auto v = [&](int x, int y) { return x * width + y; };
  for (int x = 0; x < length; ++x) {
    for (int y = 0; y < width; ++y) {
      if (y + 1 < width) e.emplace_back(v(x, y), v(x, y + 1));
      if (x + 1 < length) {
        e.emplace_back(v(x, y), v(x + 1, y));
        if (y + 1 < width) {
          e.emplace_back(v(x, y), v(x + 1, y + 1));
          e.emplace_back(v(x, y + 1), v(x + 1, y));
        }
      }
    }
  }
  return e;
}

SymmetricPattern pattern_of(const Sparse& a) {
  return symmetric_pattern(static_cast<int>(a.rows()), a.outerIndexPtr(), a.innerIndexPtr());
}

int bandwidth(const SymmetricPattern& g, const std::vector<int>& order) {
  std::vector<int> position(order.size());
  for (std::size_t k = 0; k < order.size(); ++k)
    position[static_cast<std::size_t>(order[k])] = static_cast<int>(k);
  int band = 0;
  for (int v = 0; v < g.size; ++v) {
    for (long p = g.outer[static_cast<std::size_t>(v)];
         p < g.outer[static_cast<std::size_t>(v) + 1]; ++p) {
      band = std::max(
          band, std::abs(position[static_cast<std::size_t>(v)] -
                         position[static_cast<std::size_t>(g.inner[static_cast<std::size_t>(p)])]));
    }
  }
  return band;
}

/// The entries below the diagonal of the factor by elimination on a dense boolean matrix.
long dense_fill_count(const SymmetricPattern& g, const std::vector<int>& order) {
  const auto n = static_cast<std::size_t>(g.size);
  std::vector<int> position(n);
  for (std::size_t k = 0; k < n; ++k)
    position[static_cast<std::size_t>(order[k])] = static_cast<int>(k);
  std::vector<std::vector<char>> s(n, std::vector<char>(n, 0));
  for (std::size_t v = 0; v < n; ++v) {
    for (long p = g.outer[v]; p < g.outer[v + 1]; ++p) {
      s[static_cast<std::size_t>(position[v])][static_cast<std::size_t>(
          position[static_cast<std::size_t>(g.inner[static_cast<std::size_t>(p)])])] = 1;
    }
  }
  long count = 0;
  for (std::size_t k = 0; k < n; ++k) {
    for (std::size_t i = k + 1; i < n; ++i) {
      if (s[i][k] == 0) continue;
      ++count;
      for (std::size_t j = k + 1; j < n; ++j) {
        if (s[j][k] != 0) s[i][j] = s[j][i] = 1;
      }
    }
  }
  return count;
}

}  // namespace

TEST_CASE(
    "symmetric_pattern: the pattern of A + Aᵀ without the diagonal, sorted, each entry once") {
  // A = [1 2 0; 0 3 4; 5 0 6] (entries (0,1), (1,2), (2,0) off the diagonal).
  Sparse a(3, 3);
  a.insert(0, 0) = 1;
  a.insert(0, 1) = 2;
  a.insert(1, 1) = 3;
  a.insert(1, 2) = 4;
  a.insert(2, 0) = 5;
  a.insert(2, 2) = 6;
  a.makeCompressed();
  const SymmetricPattern g = pattern_of(a);
  CHECK(g.outer == std::vector<long>{0, 2, 4, 6});
  CHECK(g.inner == std::vector<int>{1, 2, 0, 2, 0, 1});
}

TEST_CASE("reverse_cuthill_mckee: a permutation that finds the band of a relabelled strip") {
  for (const unsigned seed : {1U, 2U, 3U}) {
    CAPTURE(seed);
    const int length = 60, width = 4, n = length * width;
    const SymmetricPattern g =
        pattern_of(graph_matrix(n, strip_edges(length, width), shuffled(n, seed)));
    const std::vector<int> order = reverse_cuthill_mckee(g);
    std::vector<int> sorted = order;
    std::sort(sorted.begin(), sorted.end());
    std::vector<int> all(static_cast<std::size_t>(n));
    std::iota(all.begin(), all.end(), 0);
    CHECK(sorted == all);
    CHECK(bandwidth(g, std::vector<int>(all)) > 4 * width);  // the labels scattered it
    // RCM's band is below the sizes of two adjacent levels: from a corner the levels are L-shaped
    // (1, 3, 5, 7 vertices) and then the strip's columns (4): at most 7 + 4 - 1. Numbered column
    // by column the band would be width + 1 = 5.
    CHECK(bandwidth(g, order) <= 10);
  }
  SUBCASE("a path and isolated vertices: every component ordered, a path's band is 1") {
    const int n = 50;
    std::vector<std::pair<int, int>> edges;
    for (int v = 0; v + 1 < 40; ++v) edges.emplace_back(v, v + 1);  // 40..49 isolated
    const SymmetricPattern g = pattern_of(graph_matrix(n, edges, shuffled(n, 7)));
    const std::vector<int> order = reverse_cuthill_mckee(g);
    CHECK(order.size() == static_cast<std::size_t>(n));
    CHECK(bandwidth(g, order) == 1);
  }
}

TEST_CASE("cholesky_entries_below_diagonal: the count of elimination on a dense boolean matrix") {
  std::mt19937 random(11);
  for (int trial = 0; trial < 20; ++trial) {
    CAPTURE(trial);
    const int n = 30;
    std::vector<std::pair<int, int>> edges;
    std::uniform_int_distribution<int> vertex(0, n - 1);
    for (int e = 0; e < 45; ++e) {
      const int a = vertex(random), b = vertex(random);
      if (a != b) edges.emplace_back(a, b);
    }
    const SymmetricPattern g =
        pattern_of(graph_matrix(n, edges, shuffled(n, 100U + static_cast<unsigned>(trial))));
    for (const std::vector<int>& order :
         {shuffled(n, 200U + static_cast<unsigned>(trial)), reverse_cuthill_mckee(g)}) {
      const long expected = dense_fill_count(g, order);
      CHECK(cholesky_entries_below_diagonal(g, order, 1'000'000) == expected);
      if (expected > 0) {
        CHECK(cholesky_entries_below_diagonal(g, order, expected) == expected);
        CHECK(cholesky_entries_below_diagonal(g, order, expected - 1) == expected);  // limit + 1
      }
    }
  }
}

TEST_CASE("FixedPatternKlu keeps the band ordering where its factor is no larger, and solves") {
  const auto solves = [](const Sparse& a, FixedPatternKlu& klu) {
    const Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(a.rows(), 1.0, 2.0);
    const Eigen::VectorXd b = a * x;
    return (klu.solve(b) - x).lpNorm<Eigen::Infinity>();
  };
  KluSettings settings;
  settings.ordering = 1;  // COLAMD, as the integrator's solver
  settings.band_ordering_from = 0;
  SUBCASE("a relabelled strip: banded, and refactored values solve too") {
    const int n = 400 * 5;
    Sparse a = graph_matrix(n, strip_edges(400, 5), shuffled(n, 5));
    FixedPatternKlu klu(settings);
    REQUIRE(klu.factor(a));
    CHECK(klu.band_ordered());
    CHECK(solves(a, klu) < 1e-10);
    a *= 3.0;
    a.coeffRef(0, 0) += 1.0;
    REQUIRE(klu.factor(a));
    CHECK(klu.refactorizations() == 1);
    CHECK(solves(a, klu) < 1e-10);
  }
  SUBCASE("a square grid: the band's fill is larger, KLU's own ordering stays") {
    const int side = 40, n = side * side;
    std::vector<std::pair<int, int>> edges;
    for (int x = 0; x < side; ++x) {
      for (int y = 0; y < side; ++y) {
        if (x + 1 < side) edges.emplace_back(x * side + y, (x + 1) * side + y);
        if (y + 1 < side) edges.emplace_back(x * side + y, x * side + y + 1);
      }
    }
    const Sparse a = graph_matrix(n, edges, shuffled(n, 9));
    FixedPatternKlu klu(settings);
    REQUIRE(klu.factor(a));
    CHECK_FALSE(klu.band_ordered());
    CHECK(solves(a, klu) < 1e-10);
  }
  SUBCASE("below band_ordering_from, no trial") {
    const int n = 400 * 5;
    const Sparse a = graph_matrix(n, strip_edges(400, 5), shuffled(n, 5));
    settings.band_ordering_from = n + 1;
    FixedPatternKlu klu(settings);
    REQUIRE(klu.factor(a));
    CHECK_FALSE(klu.band_ordered());
    CHECK(solves(a, klu) < 1e-10);
  }
}

}  // namespace test_band_ordering
