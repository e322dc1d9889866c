// The least-change step of the initial projection (least_change.hpp), dense or sparse.

#include "models/assembly/least_change.hpp"

#include <Eigen/SparseCholesky>
#include <stdexcept>

#include "models/core/eigen_decompositions.hpp"

namespace condyn {

namespace {

// Rank threshold of the weighted, row-normalised free-column block (as build_model's rank check).
constexpr double kStepRankTolerance = 1e-10;
// A least-change step whose block (rows x free DOFs) has more entries than this is solved
// sparse, by the normal equations of the minimum-norm problem (below); smaller ones keep the
// dense complete orthogonal decomposition, which also treats rank-deficient rows (32 MB, and
// seconds of factorization).
constexpr double kMaxDenseStepEntries = 4e6;

using SparseRowMajor = Eigen::SparseMatrix<double, Eigen::RowMajor>;

/// B⁺ rhs by a complete orthogonal decomposition: rank-deficient rows are treated as well.
Eigen::VectorXd dense_min_norm(const SparseRowMajor& B, const Eigen::VectorXd& rhs) {
  const Eigen::MatrixXd b(B);
  Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(b.rows(), b.cols());
  cod.setThreshold(kStepRankTolerance);
  cod.compute(b);
  return cod.solve(rhs);
}

/// z = Bᵀ (B Bᵀ)⁻¹ rhs by a sparse LDLᵀ of B Bᵀ: the minimum-norm solution when the rows are
/// independent (build_model's rank check has made them so). Its error grows with cond(B)²,
/// not cond(B): the Gauss-Newton loop iterates on the residual, and violated() judges the
/// result, so a step that lost digits is corrected or refused, never kept silently.
Eigen::VectorXd sparse_min_norm(const SparseRowMajor& B, const Eigen::VectorXd& rhs) {
  const Eigen::SparseMatrix<double> Bt = B.transpose();
  const Eigen::SparseMatrix<double> BBt = B * Bt;
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(BBt);
  if (ldlt.info() != Eigen::Success) {
    throw std::runtime_error(
        "cannot project the initial state: the constraints are dependent at the projected "
        "configuration (singular B Bt in the sparse least-change step)");
  }
  return Bt * ldlt.solve(rhs);
}

}  // namespace

Eigen::VectorXd least_change_step(const Eigen::SparseMatrix<double>& A,
                                  const std::vector<int>& rows, const std::vector<int>& free,
                                  const Eigen::VectorXd& r, const Eigen::VectorXd& row_weight,
                                  const Eigen::VectorXd& w_inv_sqrt) {
  const auto n = w_inv_sqrt.size();
  Eigen::VectorXd dx = Eigen::VectorXd::Zero(n);
  if (free.empty() || rows.empty()) return dx;
  const auto nr = static_cast<Eigen::Index>(rows.size());
  const auto nf = static_cast<Eigen::Index>(free.size());
  // B from A's entries on (rows, free): local indices, -1 outside.
  std::vector<int> row_at(static_cast<std::size_t>(row_weight.size()), -1),
      col_at(static_cast<std::size_t>(n), -1);
  for (Eigen::Index k = 0; k < nr; ++k)
    row_at[static_cast<std::size_t>(rows[static_cast<std::size_t>(k)])] = static_cast<int>(k);
  for (Eigen::Index c = 0; c < nf; ++c)
    col_at[static_cast<std::size_t>(free[static_cast<std::size_t>(c)])] = static_cast<int>(c);
  std::vector<Eigen::Triplet<double>> entries;
  for (Eigen::Index j = 0; j < A.outerSize(); ++j) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, j); it; ++it) {
      const int k = row_at[static_cast<std::size_t>(it.row())],
                c = col_at[static_cast<std::size_t>(it.col())];
      if (k >= 0 && c >= 0) entries.emplace_back(k, c, it.value() * w_inv_sqrt[it.col()]);
    }
  }
  SparseRowMajor B(nr, nf);
  B.setFromTriplets(entries.begin(), entries.end());
  Eigen::VectorXd rhs(nr);
  for (Eigen::Index k = 0; k < nr; ++k) {
    const int i = rows[static_cast<std::size_t>(k)];
    const double norm = B.row(k).blueNorm();  // no overflow of the squares of large rows
    if (norm > 0.0) {  // a row on given DOFs only: nothing free can change its residual
      B.row(k) *= row_weight[i] / norm;
      rhs[k] = -r[i] * row_weight[i] / norm;
    } else {
      rhs[k] = 0.0;
    }
  }
  const Eigen::VectorXd z =
      static_cast<double>(nr) * static_cast<double>(nf) <= kMaxDenseStepEntries
          ? dense_min_norm(B, rhs)
          : sparse_min_norm(B, rhs);
  for (Eigen::Index c = 0; c < nf; ++c) {
    const int d = free[static_cast<std::size_t>(c)];
    dx[d] = w_inv_sqrt[d] * z[c];
  }
  return dx;
}

}  // namespace condyn
