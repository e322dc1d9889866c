#pragma once
// Symmetric test matrices with a 2D or 3D mesh's pattern, and the residual test of a solve with
// them (tests of CHOLMOD and of SymmetricFactor).

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <limits>
#include <vector>

namespace condyn::test {

/// K + s M on an nx × ny (× nz) grid: the five-point (seven-point) Laplacian, a 2D (3D) mesh's
/// pattern, plus s times the identity; symmetric, positive definite for s > 0 and indefinite for
/// s below −12.
inline Eigen::SparseMatrix<double> grid_matrix(int nx, int ny, double s, int nz = 1) {
  const int n = nx * ny * nz;
  std::vector<Eigen::Triplet<double>> t;
  const auto couple = [&t](int a, int b) {
    t.emplace_back(a, b, -1.0);
    t.emplace_back(b, a, -1.0);
  };
  for (int k = 0; k < nz; ++k) {
    for (int j = 0; j < ny; ++j) {
      for (int i = 0; i < nx; ++i) {
        const int p = (k * ny + j) * nx + i;
        t.emplace_back(p, p, (nz > 1 ? 6.0 : 4.0) + s);
        if (i + 1 < nx) couple(p, p + 1);
        if (j + 1 < ny) couple(p, p + nx);
        if (k + 1 < nz) couple(p, p + nx * ny);
      }
    }
  }
  Eigen::SparseMatrix<double> a(n, n);
  a.setFromTriplets(t.begin(), t.end());
  a.makeCompressed();
  return a;
}

/// ‖A x − b‖∞ relative to ‖A‖∞ ‖x‖∞ + ‖b‖∞: a backward-stable solve leaves a modest multiple of
/// machine epsilon (Cholesky's bound grows with n only through the entries per row).
inline double relative_residual(const Eigen::SparseMatrix<double>& a, const Eigen::VectorXd& x,
                                const Eigen::VectorXd& b) {
  const Eigen::VectorXd row_sums = a.cwiseAbs() * Eigen::VectorXd::Ones(a.cols());
  const double norm_a = row_sums.maxCoeff();
  return (a * x - b).lpNorm<Eigen::Infinity>() /
         (norm_a * x.lpNorm<Eigen::Infinity>() + b.lpNorm<Eigen::Infinity>());
}

/// Roundoff bound of the relative residual above: 100 ε (observed 1e-17 to 1e-16 here).
inline constexpr double kSolveRoundoff = 100 * std::numeric_limits<double>::epsilon();

}  // namespace condyn::test
