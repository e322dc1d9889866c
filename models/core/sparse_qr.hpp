#pragma once
// SuiteSparseQR for the rank check of large constraint groups (models/assembly/rank_check.cpp),
// through its C interface and loaded when first needed.
//
// Only groups above kDenseBlockEntries need it. Linking it would load SuiteSparseQR with CHOLMOD,
// METIS, LAPACK, BLAS and the gfortran, quadmath and OpenMP runtimes into every process, used or
// not: resident memory and start-up time (docs/benchmarks.md) for scenes that never factor a
// large group. Loaded on first use, a scene pays for it only when it needs it.

#include <Eigen/SparseCore>
#include <memory>
#include <vector>

namespace condyn {

/// Rank of `a` (rows x columns) by SuiteSparseQR's rank-revealing QR with threshold `tol`, and its
/// column order: order[0..rank) are independent, the rest are dependent on them (SuiteSparseQR
/// moves them last). Throws std::runtime_error when SuiteSparseQR cannot be loaded or fails.
struct SparseQrRank {
  int rank = 0;
  std::vector<int> order;
};
SparseQrRank sparse_qr_rank(const Eigen::SparseMatrix<double>& a, double tol);

/// Least-squares solutions of basis * y = b (basis of full column rank), factored once by
/// SuiteSparseQR: y = E (R \ (Q' b)).
class SparseLeastSquares {
 public:
  SparseLeastSquares(const Eigen::SparseMatrix<double>& basis, double tol);
  ~SparseLeastSquares();
  SparseLeastSquares(const SparseLeastSquares&) = delete;
  SparseLeastSquares& operator=(const SparseLeastSquares&) = delete;

  [[nodiscard]] Eigen::VectorXd solve(const Eigen::VectorXd& b) const;

 private:
  struct Factor;
  std::unique_ptr<Factor> factor_;
};

/// True once SuiteSparseQR has been loaded into this process (for the tests).
bool sparse_qr_loaded();

}  // namespace condyn
