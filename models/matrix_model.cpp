// The matrix model: M, K and C as the scene writes them, each positive semi-definite.

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "models/model_builder.hpp"

namespace condyn {

Eigen::SparseMatrix<double> ModelBuilder::sparse_psd(const std::vector<std::vector<double>>& rows,
                                                     const std::string& key) const {
  const int n = static_cast<int>(rows.size());
  Eigen::MatrixXd dense(n, n);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j)
      dense(i, j) = rows[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)];
  }
  // Positive semi-definite up to roundoff of the largest eigenvalue.
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(dense, Eigen::EigenvaluesOnly);
  const double lo = eig.eigenvalues().minCoeff();
  const double hi = eig.eigenvalues().cwiseAbs().maxCoeff();
  if (!std::isfinite(lo) || !std::isfinite(hi)) {
    fail(SourcePoint{"model." + key, spec_.model.where.line},
         "has eigenvalues beyond the double range: the entries are too large");
  }
  if (lo < -1e-12 * std::max(hi, 1e-300)) {
    fail(SourcePoint{"model." + key, spec_.model.where.line},
         "is not positive semi-definite (smallest eigenvalue " + fmt(lo) + ")");
  }
  return dense.sparseView();
}

void ModelBuilder::build_matrix() {
  const auto& m = spec_.model;
  set_dofs(m.dofs);
  model_.M = sparse_psd(m.mass, "mass");
  model_.K = sparse_psd(m.stiffness, "stiffness");
  model_.C.resize(model_.dofs(), model_.dofs());
  if (!m.damping.empty()) model_.C = sparse_psd(m.damping, "damping");
  model_.M.makeCompressed();
  model_.K.makeCompressed();
  model_.C.makeCompressed();
}

}  // namespace condyn
