// The lowest modes of a symmetric pencil (K, M), dense or by shift-invert Lanczos
// (pencil_modes.hpp). Spectra, as for the largest frequency (largest_frequency.cpp): restarts,
// convergence tests and Ritz extraction are what a kept library does better than a few lines here.

#include "models/core/pencil_modes.hpp"

#include <Spectra/SymGEigsShiftSolver.h>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <memory>
#include <numeric>
#include <string>

#include "models/core/eigen_decompositions.hpp"
#include "models/core/massless_dofs.hpp"
#include "models/core/symmetric_factor.hpp"

namespace condyn {

namespace {

/// The DOFs with mass, ascending: the complement of massless_columns.
std::vector<int> massive_columns(const Eigen::SparseMatrix<double>& M) {
  const std::vector<int> h = massless_columns(M);
  std::vector<int> r;
  r.reserve(static_cast<std::size_t>(M.cols()) - h.size());
  std::size_t k = 0;
  for (int j = 0; j < M.cols(); ++j) {
    if (k < h.size() && h[k] == j) {
      ++k;
    } else {
      r.push_back(j);
    }
  }
  return r;
}

/// The scale of ω²: the largest K_jj / M_jj over the DOFs with mass (K's diagonal bounds its
/// largest eigenvalue from below, and its ratio to M's sets the units).
double eigenvalue_scale(const Eigen::SparseMatrix<double>& K, const Eigen::SparseMatrix<double>& M,
                        const std::vector<int>& r) {
  const Eigen::VectorXd k = K.diagonal(), m = M.diagonal();
  double scale = 0.0;
  for (const int j : r) {
    if (m[j] > 0.0) scale = std::max(scale, std::abs(k[j]) / m[j]);
  }
  return scale > 0.0 ? scale : 1.0;
}

[[noreturn]] void unstable(double lambda) {
  throw ModesUnavailable(
      ModesUnavailable::Why::stiffness,
      "the stiffness is not positive semi-definite on the motions allowed: a mode "
      "with omega^2 = " +
          std::to_string(lambda) +
          " < 0 (an unstable model: buckled or "
          "pre-stressed beyond its limit)");
}

/// Mass-normalizes each column (φᵀMφ = 1) and makes its entry of largest magnitude positive, so
/// that both paths give the same shapes.
void normalize(const Eigen::SparseMatrix<double>& M, Eigen::MatrixXd& shapes) {
  for (Eigen::Index j = 0; j < shapes.cols(); ++j) {
    auto phi = shapes.col(j);
    const double mass = phi.dot(M * phi);
    if (mass > 0.0) phi /= std::sqrt(mass);
    Eigen::Index at = 0;
    phi.cwiseAbs().maxCoeff(&at);
    if (phi[at] < 0.0) phi = -phi;
  }
}

/// ω² below −(a tolerance of the scale) is an instability; above it, roundoff of a zero-frequency
/// mode, set to 0. The tolerance: a rigid motion's ω² comes out within a few eps of the scale
/// (dense) or kModeTolerance times the shift (Lanczos), far below 1e-6 of the scale.
void check_and_clamp(Eigen::VectorXd& omega2, double scale) {
  constexpr double kRoundoff = 1e-6;
  for (double& l : omega2) {
    if (l < -kRoundoff * scale) unstable(l);
    l = std::max(l, 0.0);
  }
}

PencilModes dense_modes(const Eigen::SparseMatrix<double>& K, const Eigen::SparseMatrix<double>& M,
                        int count, const std::vector<int>& r, const std::vector<int>& h) {
  const Eigen::MatrixXd Kd(K), Md(M);
  Eigen::MatrixXd Kc = Kd(r, r);
  Eigen::LLT<Eigen::MatrixXd> hold;
  if (!h.empty()) {
    const Eigen::MatrixXd Khh = Kd(h, h);  // a MatrixXd: the instance compiled once
    hold.compute(Khh);
    if (hold.info() != Eigen::Success) {
      throw ModesUnavailable(ModesUnavailable::Why::stiffness,
                             "massless DOFs that no stiffness holds: K on the " +
                                 std::to_string(h.size()) +
                                 " DOFs without mass is not positive definite");
    }
    Kc -= Kd(r, h) * hold.solve(Kd(h, r));
  }
  const Eigen::MatrixXd Mr = Md(r, r);
  if (Eigen::LLT<Eigen::MatrixXd>(Mr).info() != Eigen::Success) {
    throw ModesUnavailable(ModesUnavailable::Why::no_mass,
                           "the mass matrix is not positive definite on the DOFs with mass");
  }
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(
      Kc, Mr, Eigen::ComputeEigenvectors | Eigen::Ax_lBx);
  if (eig.info() != Eigen::Success)
    throw ModesUnavailable(ModesUnavailable::Why::not_converged,
                           "the dense eigensolver did not converge");
  PencilModes out;
  out.dense = true;
  out.omega2 = eig.eigenvalues().head(count);
  out.shapes = Eigen::MatrixXd::Zero(K.rows(), count);
  const Eigen::MatrixXd phi_r = eig.eigenvectors().leftCols(count);
  out.shapes(r, Eigen::all) = phi_r;
  if (!h.empty()) out.shapes(h, Eigen::all) = -hold.solve(Kd(h, r) * phi_r);
  return out;
}

/// Whether `factor` holds a positive definite matrix with room to spare: every pivot above
/// kPivotFloor of the largest (a singular K, a rigid motion, leaves one at roundoff of the largest;
/// a held structure's pivots stay of the order of its stiffnesses, however flexible it is).
bool positive_definite(const SymmetricFactor& factor) {
  constexpr double kPivotFloor = 1e-9;
  return factor.positive_definite() && factor.pivot_ratio() > kPivotFloor;
}

/// (K_c − σ M_RR)⁻¹ on the DOFs with mass, through the factor of the whole K − σM: the right-hand
/// side is zero on the massless DOFs, so their rows are the static condensation (Spectra's
/// shift-solve interface; the factor is made at σ once, before).
class CondensedShiftSolve {
 public:
  using Scalar = double;
  CondensedShiftSolve(const SymmetricFactor& factor, const std::vector<int>& r, Eigen::Index n)
      : factor_(factor), r_(r), full_(n) {}
  [[nodiscard]] Eigen::Index rows() const { return static_cast<Eigen::Index>(r_.size()); }
  [[nodiscard]] Eigen::Index cols() const { return rows(); }
  void set_shift(double /*sigma*/) {}  // factored at σ already
  void perform_op(const double* x, double* y) const {
    full_.setZero();
    for (std::size_t i = 0; i < r_.size(); ++i) full_[r_[i]] = x[i];
    const Eigen::VectorXd z = factor_.solve(full_);
    for (std::size_t i = 0; i < r_.size(); ++i) y[i] = z[r_[i]];
  }

 private:
  const SymmetricFactor& factor_;
  const std::vector<int>& r_;
  mutable Eigen::VectorXd full_;
};

/// y = M_RR x (Spectra's B operator).
class MassProduct {
 public:
  using Scalar = double;
  explicit MassProduct(const Eigen::SparseMatrix<double>& m) : m_(m) {}
  [[nodiscard]] Eigen::Index rows() const { return m_.rows(); }
  [[nodiscard]] Eigen::Index cols() const { return m_.cols(); }
  void perform_op(const double* x, double* y) const {
    Eigen::Map<Eigen::VectorXd>(y, m_.rows()) =
        m_ * Eigen::Map<const Eigen::VectorXd>(x, m_.cols());
  }

 private:
  const Eigen::SparseMatrix<double>& m_;
};

PencilModes sparse_modes(const Eigen::SparseMatrix<double>& K, const Eigen::SparseMatrix<double>& M,
                         int count, const std::vector<int>& r, double scale) {
  // σ = 0 when K is positive definite (a structure its supports hold): a flexible one's lowest
  // ω², 1e-15 of its largest on a strip of 10⁴ columns, keeps its relative accuracy. A singular K
  // (zero-frequency modes) takes σ = −s, s a small fraction of ω²'s scale: K + sM is positive
  // definite, and ω² far below s lose relative accuracy (about kModeTolerance s / ω²).
  constexpr double kShift = 1e-8;
  // The factorization: CHOLMOD's supernodal Cholesky above kCholmodAbove DOFs (on a 3D mesh
  // Eigen's simplicial one takes minutes at 10⁵).
  double sigma = 0.0;
  auto factor = std::make_unique<SymmetricFactor>(K);
  if (!positive_definite(*factor)) {
    sigma = -kShift * scale;
    const Eigen::SparseMatrix<double> shifted = K - sigma * M;
    factor.reset();  // one factor held at a time
    factor = std::make_unique<SymmetricFactor>(shifted);
    if (!factor->positive_definite()) {
      throw ModesUnavailable(ModesUnavailable::Why::stiffness,
                             "K + s M (s = " + std::to_string(-sigma) +
                                 ") is not positive definite: the stiffness is not positive "
                                 "semi-definite on the motions allowed (an unstable model), or "
                                 "massless DOFs are held by no stiffness");
    }
  }
  const Eigen::SparseMatrix<double> Mr = principal_block(M, r);
  CondensedShiftSolve op(*factor, r, K.rows());
  MassProduct bop(Mr);
  const auto nr = static_cast<Eigen::Index>(r.size());
  // A Krylov space of twice the modes asked and at least 20 more: Spectra's advice (ncv >= 2 nev)
  // with room for clustered frequencies.
  const Eigen::Index ncv =
      std::min<Eigen::Index>(nr, std::max<Eigen::Index>(2 * count + 1, count + 20));
  Spectra::SymGEigsShiftSolver<CondensedShiftSolve, MassProduct, Spectra::GEigsMode::ShiftInvert>
      eigs(op, bop, count, ncv, sigma);
  eigs.init();
  constexpr Eigen::Index kMaxRestarts = 1000;
  try {
    eigs.compute(Spectra::SortRule::LargestMagn, kMaxRestarts, kModeTolerance,
                 Spectra::SortRule::SmallestAlge);
  } catch (const std::runtime_error& e) {
    throw ModesUnavailable(ModesUnavailable::Why::not_converged,
                           std::string("Lanczos failed: ") + e.what());
  }
  if (eigs.info() != Spectra::CompInfo::Successful) {
    throw ModesUnavailable(ModesUnavailable::Why::not_converged,
                           "Lanczos did not converge to " + std::to_string(count) +
                               " modes within " + std::to_string(kMaxRestarts) + " restarts");
  }
  const Eigen::VectorXd lambda = eigs.eigenvalues();
  const Eigen::MatrixXd phi_r = eigs.eigenvectors();
  std::vector<Eigen::Index> order(static_cast<std::size_t>(lambda.size()));
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](auto a, auto b) { return lambda[a] < lambda[b]; });
  PencilModes out;
  out.omega2.resize(count);
  out.shapes.resize(K.rows(), count);
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(K.rows());
  for (int j = 0; j < count; ++j) {
    const auto k = order[static_cast<std::size_t>(j)];
    out.omega2[j] = lambda[k];
    // φ = (λ − σ)(K − σM)⁻¹ M φ: the massless DOFs' entries (their static rows), and one step of
    // inverse iteration on the others.
    const Eigen::VectorXd m_phi = Mr * phi_r.col(k);
    for (std::size_t i = 0; i < r.size(); ++i) rhs[r[i]] = m_phi[static_cast<Eigen::Index>(i)];
    out.shapes.col(j) = (lambda[k] - sigma) * factor->solve(rhs);
  }
  return out;
}

}  // namespace

std::vector<int> massless_columns(const Eigen::SparseMatrix<double>& M) {
  std::vector<int> h;
  for (int j = 0; j < M.outerSize(); ++j) {
    bool zero = true;
    for (Eigen::SparseMatrix<double>::InnerIterator it(M, j); it && zero; ++it)
      zero = it.value() == 0.0;
    if (zero) h.push_back(j);
  }
  return h;
}

int mode_count(const Eigen::SparseMatrix<double>& M) {
  return static_cast<int>(M.cols()) - static_cast<int>(massless_columns(M).size());
}

PencilModes lowest_modes(const Eigen::SparseMatrix<double>& K, const Eigen::SparseMatrix<double>& M,
                         int count, ModeSolver solver) {
  const std::vector<int> r = massive_columns(M);
  const auto nr = static_cast<int>(r.size());
  if (nr == 0)
    throw ModesUnavailable(ModesUnavailable::Why::no_mass,
                           "the model has no mass: it has no natural modes");
  if (count < 1 || count > nr) {
    throw std::invalid_argument("asked for " + std::to_string(count) + " modes of a pencil with " +
                                std::to_string(nr));
  }
  const double n = static_cast<double>(K.rows());
  const bool dense_fits = n * n <= kMaxDenseModeEntries;
  const bool lanczos_fits = count < nr - 1;
  if (solver == ModeSolver::automatic) {
    solver = (K.rows() <= kDenseModeDofs || !lanczos_fits) ? ModeSolver::dense : ModeSolver::sparse;
  }
  if (solver == ModeSolver::dense && !dense_fits) {
    throw std::invalid_argument(
        std::to_string(count) + " of " + std::to_string(nr) +
        " modes need the dense eigensolver, and " + std::to_string(K.rows()) +
        " DOFs is beyond its limit: ask for fewer than " + std::to_string(nr - 1));
  }
  if (solver == ModeSolver::sparse && !lanczos_fits) {
    throw std::invalid_argument("Lanczos gives at most " + std::to_string(nr - 2) + " of the " +
                                std::to_string(nr) + " modes");
  }
  const double scale = eigenvalue_scale(K, M, r);
  PencilModes out = solver == ModeSolver::dense ? dense_modes(K, M, count, r, massless_columns(M))
                                                : sparse_modes(K, M, count, r, scale);
  check_and_clamp(out.omega2, scale);
  normalize(M, out.shapes);
  return out;
}

double mass_along(const Eigen::SparseMatrix<double>& M, const Eigen::VectorXd& L) {
  const std::vector<int> r = massive_columns(M);
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> factor(principal_block(M, r));
  if (factor.info() != Eigen::Success) {
    throw ModesUnavailable(ModesUnavailable::Why::no_mass,
                           "the mass matrix is not positive definite on the DOFs with mass");
  }
  const Eigen::VectorXd lr = L(r);
  return lr.dot(factor.solve(lr));
}

}  // namespace condyn
