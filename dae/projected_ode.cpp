#include "dae/projected_ode.hpp"

#include "dae/kkt.hpp"

#include <stdexcept>

namespace condyn {

ProjectedOde::ProjectedOde(const MechanicalSystem& system)
    : system_(system), n_(system.dofs()), m_(system.constraints()) {
  if (system.has_curvature()) {
    throw std::invalid_argument("projection does not yet support nonlinear constraints");
  }
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(n_);
  const auto& M = system.mass(0.0, zero);
  A_ = system.constraint_jacobian(0.0, zero);
  mass_.compute(M);
  if (mass_.info() != Eigen::Success) {
    throw std::invalid_argument(
        "projection needs mass on every DOF: the mass matrix is not positive definite");
  }
  kkt_.compute(kkt_matrix(M, A_));
  if (kkt_.info() != Eigen::Success)
    throw std::invalid_argument("the KKT system [M Aᵀ; A 0] is singular");

  for (int i = 0; i < m_; ++i) {
    if (system.position_rows()[static_cast<std::size_t>(i)]) position_rows_.push_back(i);
  }
  Eigen::SparseMatrix<double> select(static_cast<Eigen::Index>(position_rows_.size()), m_);
  for (std::size_t k = 0; k < position_rows_.size(); ++k) {
    select.insert(static_cast<Eigen::Index>(k), position_rows_[k]) = 1.0;
  }
  Ap_ = select * A_;
  if (m_ > 0) {
    minv_at_ = mass_.solve(Eigen::MatrixXd(A_.transpose()));
    gram_.compute(A_ * minv_at_);
  }
  if (!position_rows_.empty()) {
    minv_apt_ = mass_.solve(Eigen::MatrixXd(Ap_.transpose()));
    gram_p_.compute(Ap_ * minv_apt_);
  }
  force_.resize(n_);
  rows_.resize(m_);
}

Eigen::VectorXd ProjectedOde::accelerations(double t, double step_reference, const ConstRef& u,
                                            const ConstRef& v) const {
  system_.force(t, step_reference, u, v, force_);
  Eigen::VectorXd rhs(n_ + m_);
  rhs.head(n_) = force_;
  if (m_ > 0) {
    system_.acceleration_bias(t, u, v, rows_);
    rhs.tail(m_) = rows_;
  }
  return kkt_.solve(rhs);
}

void ProjectedOde::rhs(double t, double step_reference, ConstRef y, Ref ydot) const {
  ydot.head(n_) = y.tail(n_);
  ydot.tail(n_) = accelerations(t, step_reference, y.head(n_), y.tail(n_)).head(n_);
}

Eigen::VectorXd ProjectedOde::multipliers(double t, const Eigen::VectorXd& y) const {
  return accelerations(t, t, y.head(n_), y.tail(n_)).tail(m_);
}

void ProjectedOde::project(double t, ConstRef y, Ref corr) const {
  corr.setZero();
  if (!position_rows_.empty()) {
    system_.position_residual(t, y.head(n_), rows_);
    Eigen::VectorXd phi_p(static_cast<Eigen::Index>(position_rows_.size()));
    for (std::size_t k = 0; k < position_rows_.size(); ++k) {
      phi_p[static_cast<Eigen::Index>(k)] = rows_[position_rows_[k]];
    }
    corr.head(n_) = -minv_apt_ * gram_p_.solve(phi_p);
  }
  const Eigen::VectorXd u = y.head(n_) + corr.head(n_);
  system_.velocity_residual(t, u, y.tail(n_), rows_);
  corr.tail(n_) = -minv_at_ * gram_.solve(rows_);
}

void ProjectedOde::project_error(Ref err) const {
  if (!position_rows_.empty()) {
    err.head(n_) -= minv_apt_ * gram_p_.solve(Ap_ * err.head(n_));
  }
  err.tail(n_) -= minv_at_ * gram_.solve(A_ * err.tail(n_));
}

}  // namespace condyn
