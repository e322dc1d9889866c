// SymmetricFactor (models/core/symmetric_factor.hpp): Eigen's LDLᵀ at or below kCholmodAbove
// rows, CHOLMOD's Cholesky above, the same answers from both: solves, the pivot ratio's bounds,
// a singular matrix, an indefinite one named.

#include <doctest/doctest.h>

#include <Eigen/Sparse>
#include <cmath>
#include <stdexcept>
#include <string>

#include "models/core/symmetric_factor.hpp"
#include "tests/grid_matrix.hpp"

using namespace condyn;

namespace test_symmetric_factor {

using condyn::test::grid_matrix;
using condyn::test::kSolveRoundoff;
using condyn::test::relative_residual;

namespace {

/// A square grid of about `rows` unknowns: 30 × 30 (900, Eigen's) or 110 × 110 (12,100, CHOLMOD's).
int grid_side(bool above) {
  const int side = above ? 110 : 30;
  REQUIRE((side * side > kCholmodAbove) == above);
  return side;
}

}  // namespace

TEST_CASE("SymmetricFactor: solves, and every pivot within the spectrum's bounds, on both paths") {
  for (const bool above : {false, true}) {
    CAPTURE(above);
    const int side = grid_side(above);
    // Eigenvalues of the grid's Laplacian + I lie in (1, 9): the pivots of L D Lᵀ of a positive
    // definite matrix lie between its extreme eigenvalues, whatever the ordering, so their ratio
    // is at least 1/9.
    const Eigen::SparseMatrix<double> a = grid_matrix(side, side, 1.0);
    const SymmetricFactor factor(a);
    REQUIRE(factor.positive_definite());
    CHECK(factor.finding().empty());
    CHECK(factor.method() == (above ? "a sparse Cholesky factorization" : "a sparse LDLt"));
    CHECK(factor.pivot_ratio() >= 1.0 / 9.0);
    CHECK(factor.pivot_ratio() <= 1.0);
    Eigen::VectorXd b(a.rows());
    for (Eigen::Index i = 0; i < b.size(); ++i) b[i] = std::cos(0.11 * static_cast<double>(i));
    CHECK(relative_residual(a, factor.solve(b), b) <= kSolveRoundoff);
  }
}

TEST_CASE(
    "SymmetricFactor: a singular matrix leaves a pivot at roundoff, or a pivot not positive") {
  for (const bool above : {false, true}) {
    CAPTURE(above);
    const int side = grid_side(above);
    // The grid's graph Laplacian: each diagonal the sum of its row's couplings, so that the
    // constant vector is its null space (a free body's rigid motion).
    Eigen::SparseMatrix<double> a = grid_matrix(side, side, 0.0);
    const Eigen::VectorXd off = a * Eigen::VectorXd::Ones(a.cols()) - a.diagonal();
    for (Eigen::Index i = 0; i < a.rows(); ++i) a.coeffRef(i, i) = -off[i];
    const SymmetricFactor factor(a);
    // Exact arithmetic leaves a zero last pivot; roundoff leaves it tiny, of either sign. The
    // others are at least the Fiedler value, ~π²/side² ≈ 8e-4 of a largest near 8.
    if (factor.positive_definite()) {
      CHECK(factor.pivot_ratio() < 1e-9);
    } else {
      CHECK_FALSE(factor.finding().empty());
    }
  }
}

TEST_CASE("SymmetricFactor: an indefinite matrix is named, and neither solved nor measured") {
  for (const bool above : {false, true}) {
    CAPTURE(above);
    const int side = grid_side(above);
    // Laplacian − 9 I: every eigenvalue negative.
    const SymmetricFactor factor(grid_matrix(side, side, -9.0));
    CHECK_FALSE(factor.positive_definite());
    CHECK(factor.finding() == (above ? std::string("meets a pivot that is not positive")
                                     : "has " + std::to_string(side * side) + " negative pivots"));
    CHECK_THROWS_AS((void)factor.pivot_ratio(), std::logic_error);
    CHECK_THROWS_AS((void)factor.solve(Eigen::VectorXd::Ones(side * side)), std::logic_error);
  }
}

}  // namespace test_symmetric_factor
