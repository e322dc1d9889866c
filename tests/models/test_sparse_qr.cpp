// SuiteSparseQR through its C interface (models/core/sparse_qr.cpp): the rank and column order of a
// deficient matrix, and least-squares solutions, checked against what the matrices are built to be.

#include <doctest/doctest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <vector>

#include "models/core/sparse_qr.hpp"

using namespace condyn;

namespace test_sparse_qr {

namespace {

/// Columns c0, c1, c2 = 2 c0 - 3 c1, c3 of a 6 x 4 matrix: rank 3, and c2 (or another column of
/// the triple) is the dependent one.
Eigen::SparseMatrix<double> deficient() {
  Eigen::MatrixXd d(6, 4);
  d.col(0) << 1, 0, 2, 0, 0, 1;
  d.col(1) << 0, 1, 0, 0, 3, 0;
  d.col(2) = 2.0 * d.col(0) - 3.0 * d.col(1);
  d.col(3) << 0, 0, 0, 4, 0, 0;
  return d.sparseView();
}

}  // namespace

TEST_CASE("SuiteSparseQR: rank and column order of a deficient matrix") {
  const Eigen::SparseMatrix<double> a = deficient();
  const SparseQrRank r = sparse_qr_rank(a, 1e-10);
  CHECK(sparse_qr_loaded());
  CHECK(r.rank == 3);
  // A permutation of the columns, the dependent one last: c3 is independent of the others.
  std::vector<int> sorted = r.order;
  std::sort(sorted.begin(), sorted.end());
  CHECK(sorted == std::vector<int>{0, 1, 2, 3});
  CHECK(r.order.back() != 3);
  // Full rank once the dependent column is dropped.
  Eigen::MatrixXd d(a);
  Eigen::MatrixXd three(6, 3);
  three << d.col(0), d.col(1), d.col(3);
  CHECK(sparse_qr_rank(three.sparseView(), 1e-10).rank == 3);
}

TEST_CASE("SuiteSparseQR: least squares in a basis of full column rank") {
  Eigen::MatrixXd basis(6, 3);
  basis.col(0) << 1, 0, 2, 0, 0, 1;
  basis.col(1) << 0, 1, 0, 0, 3, 0;
  basis.col(2) << 0, 0, 0, 4, 0, 0;
  const SparseLeastSquares ls(basis.sparseView(), 1e-10);
  // The columns are orthogonal with norms sqrt(6), sqrt(10) and 4 (condition number 1.6) and the
  // data are small integers: a QR solve is exact to a few units of roundoff, 1e-16 relative, so
  // 1e-14 (in the span) and 1e-13 (the normal equations' residual, |b| = 9.5) leave a margin of
  // 10 to 100 and still catch any wrong coefficient or permutation.
  // In the span: the exact coefficients.
  const Eigen::Vector3d y(2.0, -3.0, 0.5);
  const Eigen::VectorXd in_span = basis * y;
  CHECK((ls.solve(in_span) - y).norm() < 1e-14);
  // Outside it: the residual is orthogonal to the columns (the normal equations hold).
  Eigen::VectorXd b(6);
  b << 1, 2, 3, 4, 5, 6;
  const Eigen::VectorXd x = ls.solve(b);
  CHECK((basis.transpose() * (basis * x - b)).norm() < 1e-13);
}

}  // namespace test_sparse_qr
