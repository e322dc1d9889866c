// L X R with fixed patterns (dae/linsolve/fixed_product.hpp) against Eigen's general product.

#include <doctest/doctest.h>

#include <Eigen/Dense>
#include <Eigen/Sparse>

#include "dae/linsolve/fixed_product.hpp"

using namespace condyn;

namespace test_fixed_product {

using Sparse = Eigen::SparseMatrix<double>;

namespace {

/// A sparse matrix with entries where (i * 7 + j * 3 + seed) % 5 == 0, values from both indices.
Sparse pattern_matrix(int rows, int cols, int seed, double scale) {
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < rows; ++i)
    for (int j = 0; j < cols; ++j)
      if ((i * 7 + j * 3 + seed) % 5 == 0) t.emplace_back(i, j, scale * (1.0 + i - 0.5 * j));
  Sparse s(rows, cols);
  s.setFromTriplets(t.begin(), t.end());
  return s;
}

double max_difference(const Sparse& a, const Sparse& b) {
  return (Eigen::MatrixXd(a) - Eigen::MatrixXd(b)).cwiseAbs().maxCoeff();
}

}  // namespace

TEST_CASE("fixed product: L X R as Eigen computes it, values refilled for new values") {
  const Sparse left = pattern_matrix(6, 9, 1, 0.5), right = pattern_matrix(8, 5, 2, -0.25);
  FixedProduct product(left, right);
  const Sparse x = pattern_matrix(9, 8, 3, 1.0);
  const Sparse expected = left * x * right;
  CHECK(max_difference(product(x), expected) <= 1e-13);
  // Same pattern, other values: refilled, pattern unchanged.
  const Sparse x2 = pattern_matrix(9, 8, 3, -3.0);
  const Eigen::Index stored = product(x).nonZeros();
  CHECK(max_difference(product(x2), Sparse(left * x2 * right)) <= 1e-12);
  CHECK(product(x2).nonZeros() == stored);
  // Another pattern: the plan is made again.
  const Sparse x3 = pattern_matrix(9, 8, 4, 2.0);
  CHECK(max_difference(product(x3), Sparse(left * x3 * right)) <= 1e-12);
  // Zero values keep their place in the pattern (a Jacobian pattern must not depend on values).
  const Sparse zero = x * 0.0;
  CHECK(product(zero).nonZeros() == stored);
}

}  // namespace test_fixed_product
