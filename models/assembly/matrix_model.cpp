// The matrix model: M, K and C as the scene writes them (rows or Matrix Market files), each
// positive semi-definite; and Rayleigh damping C = a0 M + a1 K for any linear model.

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <string_view>
#include <unordered_set>

#include "models/assembly/model_builder.hpp"
#include "models/core/eigen_decompositions.hpp"
#include "models/core/symmetric_factor.hpp"

namespace condyn {

namespace {

// Above this size a file-given matrix is not made dense for its eigenvalues (n^2 memory, n^3
// time); 500 keeps the dense check at 2 MB and a few tens of ms, as for rows a scene writes.
constexpr Eigen::Index kDensePsdCheck = 500;
// Larger ones: the inertia of A + δ D (D = diag(A), δ relative) by a sparse LDLᵀ. Cholesky-type
// factorizations of a positive definite matrix are backward stable, with a backward error of a
// small multiple of eps ‖A‖ per entry: 1e-8 keeps a margin of several decades over it at a
// million DOFs, and still refuses an eigenvalue below −1e-8 of the diagonal, where the 2 x 2
// minors alone let an indefinite tridiagonal matrix pass.
constexpr double kSparsePsdShift = 1e-8;

}  // namespace

Eigen::SparseMatrix<double> ModelBuilder::sparse_psd(const std::vector<std::vector<double>>& rows,
                                                     const std::string& key,
                                                     const SourcePoint& where) const {
  const int n = static_cast<int>(rows.size());
  Eigen::MatrixXd dense(n, n);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j)
      dense(i, j) = rows[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)];
  }
  // The key's own line where the scene wrote the rows, else the model table's.
  check_psd(dense,
            where.path.empty() ? SourcePoint{"model." + key, spec_.model.where.line} : where);
  return dense.sparseView();
}

void ModelBuilder::check_psd(const Eigen::MatrixXd& dense, const SourcePoint& where,
                             const std::string& file) const {
  const std::string name = file.empty() ? "" : file + " ";
  // Positive semi-definite up to roundoff of the largest eigenvalue.
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(dense, Eigen::EigenvaluesOnly);
  const double lo = eig.eigenvalues().minCoeff();
  const double hi = eig.eigenvalues().cwiseAbs().maxCoeff();
  if (!std::isfinite(lo) || !std::isfinite(hi)) {
    fail(where, name + "has eigenvalues beyond the double range: the entries are too large");
  }
  if (lo < -1e-12 * std::max(hi, 1e-300)) {
    fail(where, name + "is not positive semi-definite (smallest eigenvalue " + fmt(lo) + ")");
  }
}

/// A file's matrix (already square and symmetric: read_matrix_files.cpp) stays sparse. Small ones
/// get the eigenvalue check of written rows; larger ones the necessary conditions that cost
/// O(nnz), a_ii >= 0 and every 2 x 2 principal minor >= 0 (|a_ij| <= sqrt(a_ii a_jj)), which
/// name the entry of a sign slip or a misplaced value, then the inertia of a sparse LDLᵀ
/// (kSparsePsdShift), which catches the indefinite matrices they let pass.
Eigen::SparseMatrix<double> ModelBuilder::file_psd(const FileMatrix& m,
                                                   const std::string& key) const {
  const SourcePoint where{m.where.path, m.where.line};
  const Eigen::SparseMatrix<double>& a = m.matrix;
  if (a.rows() <= kDensePsdCheck) {
    check_psd(Eigen::MatrixXd(a), where, m.file);
    return a;
  }
  const Eigen::VectorXd d = a.diagonal();
  for (Eigen::Index i = 0; i < d.size(); ++i) {
    if (d[i] < 0.0) {
      fail(where, m.file + " is not positive semi-definite: its diagonal entry (" +
                      std::to_string(i + 1) + "," + std::to_string(i + 1) + ") = " + fmt(d[i]) +
                      " < 0 (" + key + ")");
    }
  }
  for (Eigen::Index k = 0; k < a.outerSize(); ++k) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(a, k); it; ++it) {
      const double bound = std::sqrt(d[it.row()] * d[it.col()]);
      // Roundoff of the product's square root.
      if (std::abs(it.value()) > bound * (1.0 + 1e-12) && it.row() != it.col()) {
        fail(where, m.file + " is not positive semi-definite: |entry (" +
                        std::to_string(it.row() + 1) + "," + std::to_string(it.col() + 1) +
                        ")| = " + fmt(std::abs(it.value())) +
                        " exceeds the square root of its two diagonal entries' product (" +
                        fmt(bound) + ")");
      }
    }
  }
  check_sparse_inertia(m, key);
  return a;
}

/// A + δ D positive definite (kSparsePsdShift; zero diagonal entries, whose rows are zero after
/// the minor check, get δ max(D)): by Sylvester's law of inertia, a pivot that is not positive
/// is an eigenvalue of A + δ D that is not, below −δ max(D) in A.
void ModelBuilder::check_sparse_inertia(const FileMatrix& m, const std::string& key) const {
  const Eigen::SparseMatrix<double>& a = m.matrix;
  const Eigen::VectorXd d = a.diagonal();
  const double top = d.size() > 0 ? d.maxCoeff() : 0.0;
  if (!(top > 0.0)) return;  // the zero matrix (the minors have checked every entry against D)
  Eigen::SparseMatrix<double> shifted = a;
  for (Eigen::Index i = 0; i < d.size(); ++i)
    shifted.coeffRef(i, i) += kSparsePsdShift * (d[i] > 0.0 ? d[i] : top);
  shifted.makeCompressed();
  const SymmetricFactor factor(shifted);
  if (factor.positive_definite()) return;
  fail({m.where.path, m.where.line}, m.file + " is not positive semi-definite (" + key +
                                         "): " + factor.method() + " of it, shifted by " +
                                         fmt(kSparsePsdShift) + " of its diagonal, " +
                                         factor.finding() + ": it has an eigenvalue below -" +
                                         fmt(kSparsePsdShift) + " of its largest diagonal entry");
}

/// check_degenerate_dofs' test on what the scene wrote, before the work that grows with n (the
/// names' index, the definiteness checks): O(nnz + n). A size line that declares far more DOFs
/// than the files fill (whose later checks would take time and memory that grow with the
/// declared size before refusing it) is refused here, after reading.
void ModelBuilder::check_unreached_dofs() const {
  const auto& m = spec_.model;
  std::vector<bool> reached(m.dofs.size(), false);
  const auto reach = [&](const Eigen::SparseMatrix<double>& a) {
    for (int k = 0; k < a.outerSize(); ++k) {
      for (Eigen::SparseMatrix<double>::InnerIterator it(a, k); it; ++it) {
        const auto j = static_cast<std::size_t>(it.col());
        if (it.value() != 0.0 && j < reached.size()) reached[j] = true;
      }
    }
  };
  const auto reach_rows = [&](const std::vector<std::vector<double>>& rows) {
    for (const auto& row : rows) {
      for (std::size_t j = 0; j < row.size() && j < reached.size(); ++j) {
        if (row[j] != 0.0) reached[j] = true;
      }
    }
  };
  for (const auto* file : {&m.mass_file, &m.stiffness_file, &m.damping_file}) reach(file->matrix);
  for (const auto* rows : {&m.mass, &m.stiffness, &m.damping}) reach_rows(*rows);
  for (const auto& block : spec_.constraint_blocks) reach(block.A.matrix);
  std::unordered_set<std::string_view> named;  // the DOFs written constraints name
  for (const auto& c : spec_.constraints) {
    for (const auto& [dof, coefficient] : c.terms) {
      if (coefficient != 0.0) named.insert(dof);
    }
  }
  for (std::size_t i = 0; i < reached.size(); ++i) {
    if (!reached[i] && named.count(m.dofs[i]) == 0) fail_undefined_motion(m.dofs[i]);
  }
}

void ModelBuilder::build_matrix() {
  const auto& m = spec_.model;
  check_unreached_dofs();
  set_dofs(m.dofs);
  model_.M = m.mass_file.given() ? file_psd(m.mass_file, "mass")
                                 : sparse_psd(m.mass, "mass", m.mass_where);
  model_.K.edit() = m.stiffness_file.given()
                        ? file_psd(m.stiffness_file, "stiffness")
                        : sparse_psd(m.stiffness, "stiffness", m.stiffness_where);
  model_.C.resize(model_.dofs(), model_.dofs());
  if (m.damping_file.given()) {
    model_.C = file_psd(m.damping_file, "damping");
  } else if (!m.damping.empty()) {
    model_.C = sparse_psd(m.damping, "damping", m.damping_where);
  }
  model_.M.makeCompressed();
  model_.K.edit().makeCompressed();
  model_.C.makeCompressed();
}

void ModelBuilder::apply_rayleigh() {
  if (!spec_.model.rayleigh) return;
  if (model_.is_nonlinear()) {
    fail(spec_.model.rayleigh_where,
         "Rayleigh damping needs a linear model or a truss: this model's system has no damping "
         "matrix");
  }
  const auto [a0, a1] = *spec_.model.rayleigh;
  report_.damping = spec_.model.rayleigh_rule;
  if (nonlinear_truss_) return rayleigh_on_members(a0, a1);
  // M and K are positive semi-definite, a0 and a1 >= 0: so is C. A truss's member dampers are
  // already in C.
  if (model_.C.nonZeros() == 0) model_.rayleigh = RayleighCoefficients{a0, a1};
  model_.C = (a0 * model_.M + a1 * *model_.K + model_.C).pruned();
  model_.C.makeCompressed();
}

void ModelBuilder::rayleigh_on_members(double a0, double a1) {
  // a0 M as it is (constant, and it dissipates a0 vᵀMv >= 0 in any configuration); a1 K as the
  // dashpot c = a1 EA/L along each bar's current axis: the material part of a1 times the bar's
  // tangent, equal to a1 K at the unloaded reference configuration and, unlike a1 K(u(0)) frozen,
  // following the bar as it turns. Rigid members get none (they keep their length).
  layout_.mass_damping = a0;
  for (auto& b : layout_.bars) {
    const double added = a1 * b.EA / b.length;
    if (!std::isfinite(b.c + added)) {
      fail(spec_.model.rayleigh_where, "a1 EA / L of the bar joining nodes " +
                                           std::to_string(b.i + 1) + " and " +
                                           std::to_string(b.j + 1) + " overflows the double range");
    }
    b.c += added;
  }
  const std::string rule =
      "on a truss with rigid members or large displacements: a0 M, and a1 K as dashpots of "
      "a1 EA/L along the bars";
  report_.damping = report_.damping.empty() ? rule : report_.damping + " (" + rule + ")";
}

}  // namespace condyn
