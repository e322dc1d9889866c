// Sums of sparse products by rows on two lanes (models/core/symmetric_products.hpp): against
// Eigen's products, symmetric matrices read in place and others through a copy, the rows split at
// half the entries, and one lane or two giving the same bits.

#include <doctest/doctest.h>

#include <Eigen/Sparse>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "models/core/second_lane.hpp"
#include "models/core/symmetric_products.hpp"
#include "tests/grid_matrix.hpp"

using namespace condyn;

namespace test_symmetric_products {

using condyn::test::grid_matrix;
using Inputs = std::vector<ProductInput>;

Eigen::VectorXd wave(Eigen::Index n, double phase) {
  Eigen::VectorXd v(n);
  for (Eigen::Index i = 0; i < n; ++i) v[i] = std::sin(0.37 * static_cast<double>(i) + phase);
  return v;
}

/// The grid's pattern with the entries above the diagonal changed: not symmetric.
Eigen::SparseMatrix<double> lopsided(int nx, int ny) {
  Eigen::SparseMatrix<double> a = grid_matrix(nx, ny, 1.0);
  for (int j = 0; j < a.outerSize(); ++j) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(a, j); it; ++it) {
      if (it.row() < j) it.valueRef() = 0.25 + 1e-3 * static_cast<double>(j % 7);
    }
  }
  return a;
}

/// Roundoff of a row's sum of at most 2 × 5 products of entries and values of size ≤ 5 and 1.5:
/// a few ulps of 40, generously.
constexpr double kRowRoundoff = 1e3 * std::numeric_limits<double>::epsilon();

TEST_CASE("products by rows agree with Eigen's, symmetric in place and others through a copy") {
  const Eigen::SparseMatrix<double> m = grid_matrix(40, 30, 2.0), k = lopsided(40, 30);
  CHECK(exactly_symmetric(m));
  CHECK_FALSE(exactly_symmetric(k));
  CHECK_FALSE(exactly_symmetric(Eigen::SparseMatrix<double>(3, 4)));
  const SymmetricProducts products({&m, &k});
  CHECK(products.copies() == 1);
  const Eigen::Index n = m.rows();
  // Half of the entries before the split row, the split inside the matrix.
  CHECK(products.split_row() > 0);
  CHECK(products.split_row() < n);
  const Eigen::VectorXd u = wave(n, 0.1), v = wave(n, 0.7), w = wave(n, 1.3);
  Eigen::VectorXd y(n);
  products.apply(Inputs{{u.data(), 1.0}, {v.data(), -0.5, w.data(), 2.0}}, y.data());
  const Eigen::VectorXd expected = m * u + k * (-0.5 * v + 2.0 * w);
  CHECK((y - expected).lpNorm<Eigen::Infinity>() <= kRowRoundoff);
  CHECK_THROWS_AS(products.apply(Inputs{{u.data()}}, y.data()), std::invalid_argument);
  const Eigen::SparseMatrix<double> small = grid_matrix(3, 3, 1.0);
  CHECK_THROWS_AS(SymmetricProducts({&m, &small}), std::invalid_argument);
}

TEST_CASE("one lane or two give the same products bit for bit") {
  const Eigen::SparseMatrix<double> m = grid_matrix(60, 50, 2.0), c = grid_matrix(60, 50, 0.3);
  const Eigen::Index n = m.rows();
  const Eigen::VectorXd u = wave(n, 0.2), v = wave(n, 0.9);
  Eigen::VectorXd one(n), two(n);
  SecondLane single(1), pair(2);
  const SymmetricProducts by_one({&m, &c}, single), by_two({&m, &c}, pair);
  const Inputs inputs{{u.data(), 3.0}, {u.data(), 1.0, v.data(), 0.5}};
  by_one.apply(inputs, one.data());
  by_two.apply(inputs, two.data());
  CHECK(one == two);
  CHECK((one - (3.0 * (m * u) + c * (u + 0.5 * v))).lpNorm<Eigen::Infinity>() <= kRowRoundoff);
}

}  // namespace test_symmetric_products
