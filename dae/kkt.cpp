#include "dae/kkt.hpp"

#include <vector>

namespace condyn {

Eigen::SparseMatrix<double> kkt_matrix(const Eigen::SparseMatrix<double>& M,
                                       const Eigen::SparseMatrix<double>& A) {
  using Sparse = Eigen::SparseMatrix<double>;
  const Eigen::Index n = M.rows(), m = A.rows();
  // Column by column into the compressed arrays (rows ascending: M's below n, A's from n on),
  // no triplets: at 10^6 DOFs they were 300 MB and a sort. Aᵀ's columns are A's rows.
  const Sparse At = m > 0 ? Sparse(A.transpose()) : Sparse(n, 0);
  Sparse kkt(n + m, n + m);
  kkt.resizeNonZeros(M.nonZeros() + 2 * At.nonZeros());
  auto* outer = kkt.outerIndexPtr();
  auto* inner = kkt.innerIndexPtr();
  double* value = kkt.valuePtr();
  Eigen::Index k = 0;
  const auto put = [&](Eigen::Index row, double v) {
    inner[k] = static_cast<Sparse::StorageIndex>(row);
    value[k++] = v;
  };
  for (Eigen::Index j = 0; j < n; ++j) {
    outer[j] = static_cast<Sparse::StorageIndex>(k);
    for (Sparse::InnerIterator it(M, j); it; ++it) put(it.row(), it.value());
    if (m > 0) {
      for (Sparse::InnerIterator it(A, j); it; ++it) put(n + it.row(), it.value());
    }
  }
  for (Eigen::Index i = 0; i < m; ++i) {
    outer[n + i] = static_cast<Sparse::StorageIndex>(k);
    for (Sparse::InnerIterator it(At, i); it; ++it) put(it.row(), it.value());
  }
  outer[n + m] = static_cast<Sparse::StorageIndex>(k);
  return kkt;
}

LinearMatrices linear_matrices(const MechanicalSystem& system) {
  const auto s = system.clone();
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(s->dofs());
  LinearMatrices out;
  out.M = s->mass(0.0, zero);
  out.K = s->stiffness(0.0, zero, zero);
  out.C = s->damping(0.0, zero, zero);
  out.A = s->constraints() > 0 ? s->constraint_jacobian(0.0, zero)
                               : Eigen::SparseMatrix<double>(0, s->dofs());
  return out;
}

}  // namespace condyn
