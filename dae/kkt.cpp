#include "dae/kkt.hpp"

#include <vector>

namespace condyn {

Eigen::SparseMatrix<double> kkt_matrix(const Eigen::SparseMatrix<double>& M,
                                       const Eigen::SparseMatrix<double>& A) {
  const auto n = static_cast<int>(M.rows()), m = static_cast<int>(A.rows());
  std::vector<Eigen::Triplet<double>> trip;
  trip.reserve(static_cast<std::size_t>(M.nonZeros() + 2 * A.nonZeros()));
  for (int k = 0; k < M.outerSize(); ++k) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(M, k); it; ++it) {
      trip.emplace_back(static_cast<int>(it.row()), static_cast<int>(it.col()), it.value());
    }
  }
  for (int k = 0; k < A.outerSize(); ++k) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, k); it; ++it) {
      trip.emplace_back(n + static_cast<int>(it.row()), static_cast<int>(it.col()), it.value());
      trip.emplace_back(static_cast<int>(it.col()), n + static_cast<int>(it.row()), it.value());
    }
  }
  Eigen::SparseMatrix<double> kkt(n + m, n + m);
  kkt.setFromTriplets(trip.begin(), trip.end());
  kkt.makeCompressed();
  return kkt;
}

LinearMatrices linear_matrices(const MechanicalSystem& system) {
  const auto s = system.clone();
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(s->dofs());
  LinearMatrices out;
  out.M = s->mass(0.0, zero);
  out.K = -s->force_jacobian_u(0.0, zero, zero);
  out.C = -s->force_jacobian_v(0.0, zero, zero);
  out.A = s->constraints() > 0 ? s->constraint_jacobian(0.0, zero)
                               : Eigen::SparseMatrix<double>(0, s->dofs());
  return out;
}

}  // namespace condyn
