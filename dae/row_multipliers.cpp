#include "dae/row_multipliers.hpp"

#include <algorithm>
#include <cmath>

#include "dae/kkt.hpp"

namespace condyn {

AccelerationLevelMultipliers::AccelerationLevelMultipliers(const MechanicalSystem& system,
                                                           bool constant)
    : system_(system.clone()), constant_(constant) {
  if (system.constraints() == 0) {
    usable_ = false;
    return;
  }
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
  const Eigen::SparseMatrix<double> scaled = scale_.asDiagonal() * A;
  Eigen::SparseMatrix<double> M = system_->mass(t, u);
  for (int i : decoupled_) M.coeffRef(i, i) = 1.0;
  M.makeCompressed();
  return klu_.factor(kkt_matrix(M, scaled));
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
  Eigen::VectorXd x(n + m);
  x << f, scale_.cwiseProduct(gamma);
  klu_.solve_in_place(x);
  // [u''; μ] with μ = D⁻¹λ: λ = D μ.
  Eigen::VectorXd a = x.head(n), lambda = scale_.cwiseProduct(x.tail(m));
  // The solution is used only when it satisfies both blocks: a matrix singular to roundoff (a
  // massless DOF its rows do not quite fix) gives a huge or non-finite one, and the scheme's λ,
  // which holds the state, is kept for that row.
  const Eigen::SparseMatrix<double>& A = system_->constraint_jacobian(t, u);
  const Eigen::VectorXd force = A.transpose() * lambda;
  const Eigen::VectorXd inertia = system_->mass(t, u) * a;
  const double scale = std::max(
      {f.cwiseAbs().maxCoeff(), force.cwiseAbs().maxCoeff(), inertia.cwiseAbs().maxCoeff()});
  const Eigen::VectorXd dynamic = inertia + force - f;
  Eigen::VectorXd kinematic = A * a - gamma;
  const double kinematic_scale =
      std::max(gamma.cwiseAbs().maxCoeff(), (A.cwiseAbs() * a.cwiseAbs()).maxCoeff());
  constexpr double kResidual = 1e-8;
  const auto within = [](double r, double s) { return std::isfinite(r) && r <= kResidual * s; };
  for (int i : decoupled_) a[i] = 0.0;
  if (!within(dynamic.cwiseAbs().maxCoeff(), scale) ||
      !within(kinematic.cwiseAbs().maxCoeff(), kinematic_scale)) {
    return std::nullopt;
  }
  return std::make_pair(std::move(a), std::move(lambda));
}

}  // namespace condyn
