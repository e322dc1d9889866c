#include "dae/formulations/row_multipliers.hpp"

#include <algorithm>
#include <cmath>

#include "dae/linsolve/kkt.hpp"
#include "models/core/row_scales.hpp"

namespace condyn {

AccelerationLevelMultipliers::AccelerationLevelMultipliers(const MechanicalSystem& system,
                                                           bool constant)
    : system_(system.clone()), constant_(constant) {
  // A massless DOF that no row touches (held by stiffness alone) has an empty row and column in
  // [M Aᵀ; A 0]: a unit on its diagonal decouples it (its u'' is not wanted here, and no other
  // equation holds it: a zero diagonal entry of a positive semi-definite M is a zero row and
  // column). A massless DOF in some row keeps its empty diagonal: the rows must fix it, or the
  // matrix is singular and the scheme's own λ is kept.
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(system.dofs());
  const Eigen::SparseMatrix<double>& M = system_->mass(0.0, zero);
  const Eigen::SparseMatrix<double>& A = system_->constraint_jacobian(0.0, zero);
  for (Eigen::Index i = 0; i < M.rows(); ++i) {
    if (M.coeff(i, i) == 0.0 && A.col(i).nonZeros() == 0) decoupled_.push_back(static_cast<int>(i));
  }
}

bool AccelerationLevelMultipliers::factor(double t, const Eigen::VectorXd& u) {
  const Eigen::SparseMatrix<double>& A = system_->constraint_jacobian(t, u);
  scale_ = row_scales(A);  // exact: rows of 1e-150 or 1e150 beside a unit mass
  scaled_ = scale_.asDiagonal() * A;
  Eigen::SparseMatrix<double> M = system_->mass(t, u);
  for (int i : decoupled_) M.coeffRef(i, i) = 1.0;
  M.makeCompressed();
  return klu_.factor(kkt_matrix(M, scaled_));
}

std::optional<std::pair<Eigen::VectorXd, Eigen::VectorXd>> AccelerationLevelMultipliers::operator()(
    double t, const Eigen::VectorXd& u, const Eigen::VectorXd& v) {
  if (!usable_) return std::nullopt;
  if (!factored_ || !constant_) {
    if (!factor(t, u)) {
      usable_ = false;
      return std::nullopt;
    }
    factored_ = true;
  }
  const Eigen::Index n = u.size(), m = scale_.size();
  Eigen::VectorXd f(n), gamma(m);
  system_->force(t, u, v, f);
  system_->acceleration_bias(t, u, v, gamma);
  for (int i : decoupled_) f[i] = 0.0;
  const Eigen::VectorXd scaled_gamma = scale_.cwiseProduct(gamma);
  Eigen::VectorXd x(n + m);
  x << f, scaled_gamma;
  klu_.solve_in_place(x);
  // [u''; μ] with μ = D⁻¹λ: λ = D μ.
  Eigen::VectorXd a = x.head(n);
  const Eigen::VectorXd mu = x.tail(m);
  // The solution is used only when it satisfies both blocks: a matrix singular to roundoff (a
  // massless DOF its rows do not quite fix) gives a huge or non-finite one, and the scheme's λ,
  // which holds the state, is kept for that row. The rows are judged scaled (D A u'' = D γ), so
  // that a row written at 1e-150 counts as much as one written at 1.
  const Eigen::VectorXd force = scaled_.transpose() * mu;
  Eigen::VectorXd inertia = system_->mass(t, u) * a;
  for (int i : decoupled_) inertia[i] = a[i];
  const auto largest = [](const Eigen::VectorXd& y) {
    return y.size() > 0 ? y.cwiseAbs().maxCoeff() : 0.0;
  };
  constexpr double kResidual = 1e-8;
  const auto within = [](double r, double s) { return std::isfinite(r) && r <= kResidual * s; };
  bool solved = within(largest(inertia + force - f),
                       std::max({largest(f), largest(force), largest(inertia)}));
  if (m > 0) {
    solved = solved &&
             within(largest(scaled_ * a - scaled_gamma),
                    std::max(largest(scaled_gamma), largest(scaled_.cwiseAbs() * a.cwiseAbs())));
  }
  if (!solved) return std::nullopt;
  for (int i : decoupled_) a[i] = 0.0;
  return std::make_pair(std::move(a), Eigen::VectorXd(scale_.cwiseProduct(mu)));
}

}  // namespace condyn
