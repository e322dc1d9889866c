#include "dae/linsolve/kkt.hpp"

#include <klu.h>

#include <stdexcept>
#include <string>
#include <vector>

namespace condyn {

Eigen::SparseMatrix<double> kkt_matrix(const Eigen::SparseMatrix<double>& M,
                                       const Eigen::SparseMatrix<double>& A) {
  return kkt_matrix(M, A, A);
}

Eigen::SparseMatrix<double> kkt_matrix(const Eigen::SparseMatrix<double>& M,
                                       const Eigen::SparseMatrix<double>& A,
                                       const Eigen::SparseMatrix<double>& B) {
  using Sparse = Eigen::SparseMatrix<double>;
  const Eigen::Index n = M.rows(), m = A.rows();
  if (B.rows() != m || (m > 0 && (A.cols() != n || B.cols() != n))) {
    throw std::invalid_argument("kkt_matrix: the sizes of M, A and B disagree");
  }
  // Column by column into the compressed arrays (rows ascending: M's below n, B's from n on),
  // no triplets (16 bytes an entry and a sort; docs/benchmarks.md). Aᵀ's columns are A's rows.
  const Sparse At = m > 0 ? Sparse(A.transpose()) : Sparse(n, 0);
  Sparse kkt(n + m, n + m);
  kkt.resizeNonZeros(M.nonZeros() + At.nonZeros() + (m > 0 ? B.nonZeros() : 0));
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
      for (Sparse::InnerIterator it(B, j); it; ++it) put(n + it.row(), it.value());
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

struct KktLu::Impl {
  klu_common common{};
  klu_symbolic* symbolic = nullptr;
  klu_numeric* numeric = nullptr;
  int n = 0;

  Impl() { klu_defaults(&common); }
  ~Impl() { release(); }
  Impl(const Impl&) = delete;
  Impl& operator=(const Impl&) = delete;
  void release() {
    if (numeric != nullptr) klu_free_numeric(&numeric, &common);
    if (symbolic != nullptr) klu_free_symbolic(&symbolic, &common);
  }
};

KktLu::KktLu() : impl_(std::make_unique<Impl>()) {}
KktLu::KktLu(const Eigen::SparseMatrix<double>& matrix) : KktLu() { compute(matrix); }
KktLu::~KktLu() = default;
KktLu::KktLu(KktLu&&) noexcept = default;
KktLu& KktLu::operator=(KktLu&&) noexcept = default;

void KktLu::compute(const Eigen::SparseMatrix<double>& matrix) {
  if (matrix.rows() != matrix.cols()) throw std::invalid_argument("KktLu: a square matrix");
  Impl& k = *impl_;
  k.release();
  k.n = static_cast<int>(matrix.rows());
  if (k.n == 0) return;
  Eigen::SparseMatrix<double> a = matrix;  // compressed, and arrays KLU may take as non-const
  a.makeCompressed();
  k.symbolic = klu_analyze(k.n, a.outerIndexPtr(), a.innerIndexPtr(), &k.common);
  if (k.symbolic == nullptr) return;
  k.numeric = klu_factor(a.outerIndexPtr(), a.innerIndexPtr(), a.valuePtr(), k.symbolic, &k.common);
  if (k.numeric != nullptr && k.common.status != KLU_OK) klu_free_numeric(&k.numeric, &k.common);
}

Eigen::ComputationInfo KktLu::info() const {
  const Impl& k = *impl_;
  return k.n == 0 || k.numeric != nullptr ? Eigen::Success : Eigen::NumericalIssue;
}

Eigen::VectorXd KktLu::solve(const Eigen::VectorXd& rhs) const {
  Impl& k = *impl_;
  if (rhs.size() != k.n) throw std::invalid_argument("KktLu: right-hand side of wrong size");
  Eigen::VectorXd x = rhs;
  if (k.n == 0) return x;
  if (k.numeric == nullptr) throw std::logic_error("KktLu: solve without a factorization");
  if (klu_solve(k.symbolic, k.numeric, k.n, 1, x.data(), &k.common) == 0) {
    throw std::runtime_error("KLU solve failed (status " + std::to_string(k.common.status) + ")");
  }
  return x;
}

long KktLu::factor_entries() const {
  const Impl& k = *impl_;
  return k.numeric == nullptr ? 0 : k.numeric->lnz + k.numeric->unz + k.numeric->nzoff;
}

}  // namespace condyn
