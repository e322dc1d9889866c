#pragma once
/// An orthonormal basis of null(A), dense: the constrained motions of a linear model, for the
/// dense computations on them (the exact modal reference, modal damping). A must have full row
/// rank (build_model checks it); n x (n − m), the identity without constraints.

#include <Eigen/Dense>
#include <Eigen/Sparse>

#include "models/core/eigen_decompositions.hpp"

namespace condyn {

[[nodiscard]] inline Eigen::MatrixXd null_space_basis(const Eigen::SparseMatrix<double>& A,
                                                      Eigen::Index n) {
  const Eigen::Index m = A.rows();
  if (m == 0) return Eigen::MatrixXd::Identity(n, n);
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(Eigen::MatrixXd(A).transpose());
  return (qr.householderQ() * Eigen::MatrixXd::Identity(n, n)).rightCols(n - m);
}

}  // namespace condyn
