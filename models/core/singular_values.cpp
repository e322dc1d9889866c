// Singular values: small blocks by a symmetric eigenvalue problem, larger ones by LAPACK's dgesdd
// from OpenBLAS, loaded on first use (models/core/singular_values.hpp says why).

#include "models/core/singular_values.hpp"

#include <algorithm>
#include <cstddef>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "models/core/eigen_decompositions.hpp"
#include "models/core/load_library.hpp"

#ifndef CONDYN_OPENBLAS_SONAME
#error "CONDYN_OPENBLAS_SONAME (OpenBLAS's shared library, e.g. libopenblas.so.0) is set by CMake"
#endif

namespace condyn {

namespace {

/// LAPACK's dgesdd (Fortran calling convention: every argument by address, then the hidden length
/// of the character argument jobz, as gfortran passes it).
using Dgesdd = void (*)(const char* jobz, const int* m, const int* n, double* a, const int* lda,
                        double* s, double* u, const int* ldu, double* vt, const int* ldvt,
                        double* work, const int* lwork, int* iwork, int* info,
                        std::size_t jobz_length);

/// Loads OpenBLAS once per process (global, as CHOLMOD wants it: models/core/fixed_pattern_cholmod
/// .cpp); it stays loaded. A failed load throws LibraryUnavailable and is tried again at the next
/// call.
Dgesdd dgesdd() {
  static const Dgesdd f = [] {
    const LoadedLibrary openblas(
        {"OpenBLAS", CONDYN_OPENBLAS_SONAME, "computes the singular values of constraint blocks",
         "libopenblas0-pthread"},
        LoadedLibrary::Scope::global);
    Dgesdd g = nullptr;
    openblas.resolve("dgesdd_", g);
    return g;
  }();
  return f;
}

void require_finite(const Eigen::MatrixXd& a) {
  if (!a.allFinite()) {
    throw std::runtime_error("singular values of a matrix that holds a value that is not finite");
  }
}

/// dgesdd's values of `a` (overwritten), or nothing when OpenBLAS cannot be loaded.
std::optional<Eigen::VectorXd> lapack_singular_values(Eigen::MatrixXd& a) {
  Dgesdd f = nullptr;
  try {
    f = dgesdd();
  } catch (const LibraryUnavailable&) {
    return std::nullopt;
  }
  const int m = static_cast<int>(a.rows()), n = static_cast<int>(a.cols());
  const int k = std::min(m, n);
  Eigen::VectorXd s(k);
  const char jobz = 'N';  // the values only: U and Vᵀ are not referenced
  const int lda = std::max(1, m), one = 1;
  double unused = 0.0;  // U and Vᵀ's place
  std::vector<int> iwork(static_cast<std::size_t>(8 * k));
  int info = 0, query = -1;
  double size = 0.0;
  f(&jobz, &m, &n, a.data(), &lda, s.data(), &unused, &one, &unused, &one, &size, &query,
    iwork.data(), &info, 1);
  if (info == 0) {
    const int lwork = static_cast<int>(size);
    std::vector<double> work(static_cast<std::size_t>(std::max(1, lwork)));
    f(&jobz, &m, &n, a.data(), &lda, s.data(), &unused, &one, &unused, &one, work.data(), &lwork,
      iwork.data(), &info, 1);
  }
  if (info != 0) {
    throw std::runtime_error("LAPACK's dgesdd failed on a " + std::to_string(m) + " x " +
                             std::to_string(n) + " matrix (info " + std::to_string(info) +
                             (info > 0 ? ": the divide and conquer did not converge)" : ")"));
  }
  return s;
}

}  // namespace

Eigen::VectorXd symmetric_singular_values(const Eigen::MatrixXd& a) {
  const Eigen::Index k = std::min(a.rows(), a.cols());
  if (k == 0) return Eigen::VectorXd(0);
  require_finite(a);
  // A rectangular block first to its k x k triangle R (Householder QR of A or Aᵀ, backward
  // stable: σ(R) = σ(A)), so that the work and memory below grow with k, not with the long side.
  Eigen::MatrixXd r;
  if (a.rows() == a.cols()) {
    r = a;
  } else {
    const Eigen::MatrixXd tall = a.rows() > a.cols() ? a : Eigen::MatrixXd(a.transpose());
    const Eigen::HouseholderQR<Eigen::MatrixXd> qr(tall);
    r = qr.matrixQR().topRows(k).triangularView<Eigen::Upper>();
  }
  // [0 R; Rᵀ 0] has the eigenvalues ±σ_i: the k largest are the σ_i, in ascending order (an
  // exact zero σ may come out as −eps σ_max: clamped).
  Eigen::MatrixXd w = Eigen::MatrixXd::Zero(2 * k, 2 * k);
  w.topRightCorner(k, k) = r;
  w.bottomLeftCorner(k, k) = r.transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(w, Eigen::EigenvaluesOnly);
  const Eigen::VectorXd& lambda = eig.eigenvalues();
  Eigen::VectorXd s(k);
  for (Eigen::Index i = 0; i < k; ++i) s[i] = std::max(0.0, lambda[2 * k - 1 - i]);
  return s;
}

Eigen::VectorXd singular_values(Eigen::MatrixXd a) {
  if (std::min(a.rows(), a.cols()) <= kSymmetricSingularValuesMax) {
    return symmetric_singular_values(a);
  }
  require_finite(a);
  if (auto s = lapack_singular_values(a)) return *s;
  return symmetric_singular_values(a);  // without OpenBLAS: the same values, more slowly
}

}  // namespace condyn
