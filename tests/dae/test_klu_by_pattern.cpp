// KluByPattern (dae/linsolve/fixed_pattern_klu.hpp): one analysis while the pattern stays, a new
// one when it changes, each solve against its own matrix; a singular matrix refused.

#include <doctest/doctest.h>

#include <Eigen/Sparse>
#include <cmath>
#include <stdexcept>

#include "dae/linsolve/fixed_pattern_klu.hpp"
#include "tests/grid_matrix.hpp"

using namespace condyn;

namespace test_klu_by_pattern {

using condyn::test::grid_matrix;
using condyn::test::kSolveRoundoff;
using condyn::test::relative_residual;

TEST_CASE("KluByPattern: one analysis while the pattern stays, a new one when it changes") {
  KluByPattern lu;
  Eigen::VectorXd b(64);
  for (Eigen::Index i = 0; i < b.size(); ++i) b[i] = std::sin(0.3 * static_cast<double>(i) + 1.0);
  CHECK_THROWS_AS((void)lu.solve(b), std::logic_error);  // nothing factored yet
  // An unsymmetric matrix: the 8 x 8 grid's Laplacian plus a skew coupling along x.
  Eigen::SparseMatrix<double> a = grid_matrix(8, 8, 0.5);
  for (int i = 0; i + 1 < 64; ++i) {
    if (a.coeff(i, i + 1) != 0.0) a.coeffRef(i, i + 1) += 0.3;
  }
  a.makeCompressed();
  REQUIRE(lu.factor(a));
  CHECK(relative_residual(a, lu.solve(b), b) <= kSolveRoundoff);
  // New values, same pattern: the same analysis (pivots searched afresh).
  Eigen::SparseMatrix<double> scaled = a * 3.0;
  for (int i = 0; i < 64; ++i) scaled.coeffRef(i, i) += 1.0;  // stored already: same pattern
  REQUIRE(lu.factor(scaled));
  CHECK(lu.analyses() == 1);
  CHECK(relative_residual(scaled, lu.solve(b), b) <= kSolveRoundoff);
  // Another pattern of the same size (the 4 x 16 grid): a new analysis, its own solution.
  const Eigen::SparseMatrix<double> other = grid_matrix(4, 16, 0.5);
  REQUIRE(lu.factor(other));
  CHECK(lu.analyses() == 2);
  CHECK(relative_residual(other, lu.solve(b), b) <= kSolveRoundoff);
  // A singular matrix (a zero column): refused, and no stale factor is solved with.
  Eigen::SparseMatrix<double> singular = other;
  for (Eigen::SparseMatrix<double>::InnerIterator it(singular, 5); it; ++it) it.valueRef() = 0.0;
  CHECK_FALSE(lu.factor(singular));
  CHECK_THROWS_AS((void)lu.solve(b), std::logic_error);
}

}  // namespace test_klu_by_pattern
