// KLU's solves over the factors copied in reading order (dae/linsolve/klu_streamed_solve.hpp),
// through FixedPatternKlu: bitwise klu_solve's results on matrices with several diagonal blocks,
// singletons among them, row pivoting and scaling, after refactorizations and fresh pivoting.

#include <doctest/doctest.h>

#include <Eigen/Sparse>
#include <algorithm>
#include <limits>
#include <numeric>
#include <random>
#include <vector>

#include "dae/linsolve/fixed_pattern_klu.hpp"

using namespace condyn;

namespace test_klu_streamed_solve {

namespace {

using Sparse = Eigen::SparseMatrix<double>;

/// A matrix that is block upper triangular (blocks of `sizes`, each a random sparse
/// nonsymmetric block, the singletons 1 × 1) after a random permutation of its rows and of its
/// columns, so that KLU's block triangular form finds the blocks again. Each block's diagonal is
/// small against its other entries (`weak`), so that KLU pivots off the diagonal; the rows' scales
/// differ by up to 10⁴ (KLU's row scaling). The values depend on `seed`, the pattern on
/// `pattern_seed`.
Sparse block_triangular(const std::vector<int>& sizes, unsigned pattern_seed, unsigned seed,
                        double weak) {
  const int n = std::accumulate(sizes.begin(), sizes.end(), 0);
  std::mt19937 pattern_rng(pattern_seed), value_rng(seed);
  std::uniform_real_distribution<double> value(-1.0, 1.0), scale(0.0, 4.0);
  std::bernoulli_distribution within(0.3), above(0.02);
  std::vector<int> block_of;
  for (int b = 0; b < static_cast<int>(sizes.size()); ++b) {
    block_of.insert(block_of.end(), static_cast<std::size_t>(sizes[static_cast<std::size_t>(b)]),
                    b);
  }
  std::vector<int> rows(static_cast<std::size_t>(n)), cols(static_cast<std::size_t>(n));
  std::iota(rows.begin(), rows.end(), 0);
  std::iota(cols.begin(), cols.end(), 0);
  std::shuffle(rows.begin(), rows.end(), pattern_rng);
  std::shuffle(cols.begin(), cols.end(), pattern_rng);
  std::vector<double> row_scale(static_cast<std::size_t>(n));
  for (double& s : row_scale) s = std::pow(10.0, scale(value_rng));
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const int bi = block_of[static_cast<std::size_t>(i)];
      const int bj = block_of[static_cast<std::size_t>(j)];
      // Within a block: a cycle through its rows (so that it is irreducible) and random entries.
      const int first =
          static_cast<int>(std::find(block_of.begin(), block_of.end(), bi) - block_of.begin());
      const int size = sizes[static_cast<std::size_t>(bi)];
      const bool cycle = bi == bj && size > 1 && j == first + (i - first + 1) % size;
      bool entry = i == j || cycle;
      if (bi == bj && !entry) entry = within(pattern_rng);
      if (bi < bj) entry = above(pattern_rng);
      if (!entry) continue;
      const double v =
          i == j ? weak * value(value_rng) + (size == 1 ? 1.0 : 0.0) : value(value_rng);
      t.emplace_back(rows[static_cast<std::size_t>(i)], cols[static_cast<std::size_t>(j)],
                     v * row_scale[static_cast<std::size_t>(i)]);
    }
  }
  Sparse a(n, n);
  a.setFromTriplets(t.begin(), t.end());
  a.makeCompressed();
  return a;
}

KluSettings streamed_from(long entries) {
  KluSettings s;
  s.streamed_solve_from = entries;
  return s;
}

/// The solutions of both solvers for a few right-hand sides, which must be bitwise equal; and
/// the residual of the streamed one.
void check_same_solutions(const Sparse& a, const FixedPatternKlu& streamed,
                          const FixedPatternKlu& plain) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  for (int r = 0; r < 3; ++r) {
    Eigen::VectorXd b(a.rows());
    for (Eigen::Index i = 0; i < b.size(); ++i) b[i] = value(rng);
    const Eigen::VectorXd x = streamed.solve(b);
    const Eigen::VectorXd y = plain.solve(b);
    CHECK((x.array() == y.array()).all());  // klu_solve's arithmetic, in its order
    CHECK((a * x - b).lpNorm<Eigen::Infinity>() <= 1e-8 * (1.0 + a.cwiseAbs().sum() / a.rows()));
  }
}

}  // namespace

TEST_CASE("KluStreamedSolve: klu_solve's results bitwise on blocks and singletons") {
  const std::vector<int> sizes{1, 7, 1, 1, 40, 3, 1, 25, 2};
  const Sparse a = block_triangular(sizes, 11, 1, 1e-3);
  FixedPatternKlu streamed(streamed_from(0)), plain(streamed_from(1L << 40));
  REQUIRE(streamed.factor(a));
  REQUIRE(plain.factor(a));
  CHECK(streamed.streamed());
  CHECK_FALSE(plain.streamed());
  check_same_solutions(a, streamed, plain);

  // New values on the same pattern: refactorizations with the pivots kept, the copy's values
  // refreshed.
  for (unsigned seed = 2; seed < 5; ++seed) {
    const Sparse b = block_triangular(sizes, 11, seed, 1e-3);
    REQUIRE(streamed.factor(b));
    REQUIRE(plain.factor(b));
    check_same_solutions(b, streamed, plain);
  }
  CHECK(streamed.refactorizations() + streamed.pivoting_factorizations() == 4);

  // Pivoting afresh after restart(): the copy is built again.
  streamed.restart();
  plain.restart();
  const Sparse c = block_triangular(sizes, 11, 9, 1.0);
  REQUIRE(streamed.factor(c));
  REQUIRE(plain.factor(c));
  CHECK(streamed.streamed());
  check_same_solutions(c, streamed, plain);
}

TEST_CASE("KluStreamedSolve: a diagonal matrix (singletons only) and the size threshold") {
  const Sparse d = block_triangular({1, 1, 1, 1, 1}, 3, 4, 1.0);
  FixedPatternKlu streamed(streamed_from(0)), plain(streamed_from(1L << 40));
  REQUIRE(streamed.factor(d));
  REQUIRE(plain.factor(d));
  check_same_solutions(d, streamed, plain);

  // Below the threshold (the factor's L and U entries), klu_solve itself.
  const Sparse a = block_triangular({30}, 5, 6, 1.0);
  FixedPatternKlu small(streamed_from(1'000'000));
  REQUIRE(small.factor(a));
  CHECK_FALSE(small.streamed());
}

TEST_CASE("KluStreamedSolve: no copy where the factorization outweighs the solves") {
  // One dense block of 200: about (2/3) 200³ flops over 200² entries, some 130 an entry, beyond
  // kStreamedSolveMostFlopsPerEntry (a mesh's fill; a banded strip's costs about 10).
  const Sparse a = block_triangular({200}, 13, 14, 1.0);
  FixedPatternKlu by_default(streamed_from(0));
  REQUIRE(by_default.factor(a));
  CHECK_FALSE(by_default.streamed());
  KluSettings any_flops = streamed_from(0);
  any_flops.streamed_solve_most_flops_per_entry = std::numeric_limits<double>::infinity();
  FixedPatternKlu forced(any_flops);
  REQUIRE(forced.factor(a));
  CHECK(forced.streamed());
  check_same_solutions(a, forced, by_default);
  // The decision stays with the pivots: a refactorization keeps it.
  const Sparse b = block_triangular({200}, 13, 15, 1.0);
  REQUIRE(by_default.factor(b));
  CHECK_FALSE(by_default.streamed());
}

}  // namespace test_klu_streamed_solve
