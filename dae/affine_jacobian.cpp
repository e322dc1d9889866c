#include "dae/affine_jacobian.hpp"

#include <stdexcept>

namespace condyn {

AffineJacobian::AffineJacobian(const Eigen::SparseMatrix<double>& J0,
                               const Eigen::SparseMatrix<double>& J1) {
  if (J0.rows() != J1.rows() || J0.cols() != J1.cols()) {
    throw std::invalid_argument("AffineJacobian: J0 and J1 differ in size");
  }
  // Structural union: mark every position of J0, J1 and the diagonal, then align values.
  Eigen::SparseMatrix<double> marks0 = J0, marks1 = J1;
  for (auto* m : {&marks0, &marks1}) {
    for (int k = 0; k < m->outerSize(); ++k) {
      for (Eigen::SparseMatrix<double>::InnerIterator it(*m, k); it; ++it) it.valueRef() = 1.0;
    }
  }
  Eigen::SparseMatrix<double> eye(J0.rows(), J0.cols());
  eye.setIdentity();
  pattern_ = marks0 + marks1 + eye;
  pattern_.makeCompressed();
  const auto nnz = static_cast<std::size_t>(pattern_.nonZeros());
  v0_.assign(nnz, 0.0);
  v1_.assign(nnz, 0.0);
  auto scatter = [&](const Eigen::SparseMatrix<double>& src, std::vector<double>& dst) {
    for (int k = 0; k < src.outerSize(); ++k) {
      Eigen::SparseMatrix<double>::InnerIterator it(src, k);
      for (Eigen::SparseMatrix<double>::InnerIterator p(pattern_, k); p && it; ++p) {
        if (p.row() == it.row()) {
          dst[static_cast<std::size_t>(&p.valueRef() - pattern_.valuePtr())] += it.value();
          ++it;
        }
      }
    }
  };
  scatter(J0, v0_);
  scatter(J1, v1_);
}

void AffineJacobian::fill(double cj, Eigen::SparseMatrix<double>& J) const {
  double* values = J.valuePtr();
  for (std::size_t k = 0; k < v0_.size(); ++k) values[k] = v0_[k] + cj * v1_[k];
}

}  // namespace condyn
