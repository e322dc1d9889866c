#include "models/core/row_scales.hpp"

#include <algorithm>
#include <cmath>

namespace condyn {

Eigen::VectorXd row_scales(const Eigen::SparseMatrix<double>& A) {
  Eigen::VectorXd largest = Eigen::VectorXd::Zero(A.rows());
  for (int k = 0; k < A.outerSize(); ++k) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, k); it; ++it) {
      largest[it.row()] = std::max(largest[it.row()], std::abs(it.value()));
    }
  }
  Eigen::VectorXd scale = Eigen::VectorXd::Ones(A.rows());
  for (Eigen::Index i = 0; i < largest.size(); ++i) {
    int exponent = 0;
    if (largest[i] > 0.0) (void)std::frexp(largest[i], &exponent);
    scale[i] = std::ldexp(1.0, -exponent);
  }
  return scale;
}

Eigen::VectorXd unit_row_scales(const Eigen::SparseMatrix<double>& A) {
  const Eigen::VectorXd exact = row_scales(A);  // largest entry of each row in [0.5, 1)
  Eigen::VectorXd sum = Eigen::VectorXd::Zero(A.rows());
  for (int k = 0; k < A.outerSize(); ++k) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, k); it; ++it) {
      const double r = it.value() * exact[it.row()];
      sum[it.row()] += r * r;
    }
  }
  Eigen::VectorXd scale(A.rows());
  for (Eigen::Index i = 0; i < scale.size(); ++i) {
    scale[i] = sum[i] > 0.0 ? exact[i] / std::sqrt(sum[i]) : 1.0;
  }
  return scale;
}

}  // namespace condyn
