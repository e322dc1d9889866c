// ω²_max of the pencil (K, M) for models beyond the dense eigensolver
// (dae/formulations/model_scales.cpp). Spectra rather than our own Lanczos: restarts, convergence
// tests and Ritz extraction are what a well-kept library does better than a few lines here.

#include "dae/formulations/largest_frequency.hpp"

#include <Spectra/MatOp/SparseCholesky.h>
#include <Spectra/MatOp/SparseSymMatProd.h>
#include <Spectra/SymGEigsSolver.h>
#include <algorithm>
#include <stdexcept>

namespace condyn {

std::optional<double> largest_eigenvalue(const Eigen::SparseMatrix<double>& K,
                                         const Eigen::SparseMatrix<double>& M) {
  const Eigen::Index n = K.rows();
  if (n < 2) return std::nullopt;
  // Spectra reads one triangle: the symmetric part (a nonlinear model's K_T need not be symmetric).
  const Eigen::SparseMatrix<double> Kt = K.transpose();
  const Eigen::SparseMatrix<double> Ks = 0.5 * (K + Kt);
  using KOp = Spectra::SparseSymMatProd<double>;
  using MOp = Spectra::SparseCholesky<double>;
  KOp k_op(Ks);
  MOp m_op(M);
  if (m_op.info() != Spectra::CompInfo::Successful) return std::nullopt;
  // One eigenvalue, a Krylov space of 20 (at most n): a few hundred products for the slowest
  // spectra tried (the benchmark lattice's clustered top), memory 20 vectors of n.
  const Eigen::Index ncv = std::min<Eigen::Index>(20, n);
  Spectra::SymGEigsSolver<KOp, MOp, Spectra::GEigsMode::Cholesky> eigs(k_op, m_op, 1, ncv);
  eigs.init();
  constexpr Eigen::Index kMaxRestarts = 200;
  try {
    eigs.compute(Spectra::SortRule::LargestMagn, kMaxRestarts, kLargestFrequencyTolerance);
  } catch (const std::runtime_error&) {
    // Spectra throws when its tridiagonal eigensolve fails (non-finite Ritz values): no
    // estimate, as when it does not converge.
    return std::nullopt;
  }
  if (eigs.info() != Spectra::CompInfo::Successful) return std::nullopt;
  return std::abs(eigs.eigenvalues()[0]);
}

}  // namespace condyn
