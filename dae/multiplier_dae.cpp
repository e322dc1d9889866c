#include "dae/multiplier_dae.hpp"

#include "dae/kkt.hpp"

#include <algorithm>
#include <sstream>
#include <stdexcept>

namespace condyn {

MultiplierDae::MultiplierDae(const MechanicalSystem& system, MultiplierScheme scheme, double alpha,
                             double beta)
    : system_(system),
      scheme_(scheme),
      alpha_(alpha),
      beta_(beta),
      n_(system.dofs()),
      m_(system.constraints()),
      p_(0) {
  if (system.has_curvature()) {
    throw std::invalid_argument("multiplier formulations do not yet support nonlinear constraints");
  }
  if (scheme == MultiplierScheme::ggl) {
    for (int i = 0; i < m_; ++i) {
      if (system.position_rows()[static_cast<std::size_t>(i)]) position_row_.push_back(i);
    }
    p_ = static_cast<int>(position_row_.size());
  }
  select_p_.resize(p_, m_);
  for (int k = 0; k < p_; ++k)
    select_p_.insert(k, position_row_[static_cast<std::size_t>(k)]) = 1.0;
  position_mask_.resize(m_, m_);
  velocity_mask_.resize(m_, m_);
  for (int i = 0; i < m_; ++i) {
    if (system.position_rows()[static_cast<std::size_t>(i)]) {
      position_mask_.insert(i, i) = 1.0;
    } else {
      velocity_mask_.insert(i, i) = 1.0;
    }
  }

  force_.resize(n_);
  rows_.resize(m_);
  // Patterns at the initial state: fixed for the run (constant for linear systems).
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(n_);
  const auto& M = system.mass(0.0, zero);
  const auto& A = system.constraint_jacobian(0.0, zero);
  const auto& f_u = system.force_jacobian_u(0.0, zero, zero);
  const auto& f_v = system.force_jacobian_v(0.0, zero, zero);
  const Eigen::SparseMatrix<double> Ap = select_p_ * A;
  const int iu = 0, iv = n_, il = lambda_at(), im = mu_at();
  jacobian_ = BlockJacobian(size());
  jacobian_.declare_identity(iu, iu, n_);  // d(u')
  jacobian_.declare_identity(iu, iv, n_);  // −I
  jacobian_.declare(iu, im, Eigen::SparseMatrix<double>(Ap.transpose()));
  jacobian_.declare(iv, iu, f_u);
  jacobian_.declare(iv, iv, f_v);
  jacobian_.declare(iv, iv, M);
  jacobian_.declare(iv, il, Eigen::SparseMatrix<double>(A.transpose()));
  // λ rows: cj A (index1, baumgarte), A (ggl, index2, and 2α A), or under index3 A on position
  // rows (d/du) and on velocity rows (d/dv).
  jacobian_.declare(il, iv, A);
  if (scheme == MultiplierScheme::index3) {
    jacobian_.declare(il, iu, Eigen::SparseMatrix<double>(position_mask_ * A));
  }
  if (scheme == MultiplierScheme::baumgarte) {
    jacobian_.declare(il, iu, Eigen::SparseMatrix<double>(position_mask_ * A));  // β² φ_u
  }
  jacobian_.declare(im, iu, Ap);
  jacobian_.finish();
}

Eigen::VectorXd MultiplierDae::differential_id() const {
  Eigen::VectorXd id = Eigen::VectorXd::Zero(size());
  id.head(lambda_at()).setOnes();
  return id;
}

Eigen::VectorXd MultiplierDae::variable_index() const {
  Eigen::VectorXd index = Eigen::VectorXd::Ones(size());
  switch (scheme_) {
    case MultiplierScheme::index1:
    case MultiplierScheme::baumgarte:
      break;
    case MultiplierScheme::ggl:
    case MultiplierScheme::index2:
      index.tail(size() - lambda_at()).setConstant(2.0);  // λ (and μ)
      break;
    case MultiplierScheme::index3:
      index.segment(n_, n_).setConstant(2.0);  // velocities
      for (int i = 0; i < m_; ++i) {
        index[lambda_at() + i] = system_.position_rows()[static_cast<std::size_t>(i)] ? 3.0 : 2.0;
      }
      break;
  }
  return index;
}

Eigen::VectorXd MultiplierDae::pack(const Eigen::VectorXd& u0, const Eigen::VectorXd& v0) const {
  Eigen::VectorXd y = Eigen::VectorXd::Zero(size());
  y.segment(0, n_) = u0;
  y.segment(n_, n_) = v0;
  return y;
}

void MultiplierDae::residual(double t, double step_reference, ConstRef y, ConstRef yp,
                             Ref r) const {
  const auto uu = y.segment(0, n_), vv = y.segment(n_, n_), lam = y.segment(lambda_at(), m_);
  const auto up = yp.segment(0, n_), vp = yp.segment(n_, n_);
  auto& f = force_;
  system_.force(t, step_reference, uu, vv, f);
  const auto& M = system_.mass(t, uu);
  r.segment(0, n_) = up - vv;
  r.segment(n_, n_) = M * vp - f;
  if (m_ == 0) return;  // unconstrained: a plain second-order ODE
  const auto& A = system_.constraint_jacobian(t, uu);
  r.segment(n_, n_) += A.transpose() * lam;
  auto rl = r.segment(lambda_at(), m_);
  auto& work = rows_;
  switch (scheme_) {
    case MultiplierScheme::index1:
      system_.acceleration_bias(t, uu, vv, work);
      rl = A * vp - work;
      break;
    case MultiplierScheme::baumgarte: {
      system_.acceleration_bias(t, uu, vv, work);
      rl = A * vp - work;
      system_.velocity_residual(t, uu, vv, work);
      rl += 2.0 * alpha_ * work;
      system_.position_residual(t, uu, work);
      rl += beta_ * beta_ * work;
      break;
    }
    case MultiplierScheme::index2:
      system_.velocity_residual(t, uu, vv, rl);
      break;
    case MultiplierScheme::index3: {
      system_.position_residual(t, uu, work);  // zero on velocity rows
      rl = work;
      system_.velocity_residual(t, uu, vv, work);
      rl += velocity_mask_ * work;
      break;
    }
    case MultiplierScheme::ggl: {
      system_.velocity_residual(t, uu, vv, rl);
      const auto mu = y.segment(mu_at(), p_);
      r.segment(0, n_) += A.transpose() * (select_p_.transpose() * mu);
      system_.position_residual(t, uu, work);
      r.segment(mu_at(), p_) = select_p_ * work;
      break;
    }
  }
}

void MultiplierDae::jacobian(double t, double /*step_reference*/, ConstRef y, ConstRef yp,
                             double cj, Eigen::SparseMatrix<double>& J) const {
  (void)yp;
  const auto uu = y.segment(0, n_), vv = y.segment(n_, n_);
  const auto& M = system_.mass(t, uu);
  const auto& A = system_.constraint_jacobian(t, uu);
  const auto& f_u = system_.force_jacobian_u(t, uu, vv);
  const auto& f_v = system_.force_jacobian_v(t, uu, vv);
  const Eigen::SparseMatrix<double> Ap = select_p_ * A;
  const int iu = 0, iv = n_, il = lambda_at(), im = mu_at();
  std::fill_n(J.valuePtr(), J.nonZeros(), 0.0);
  BlockJacobian::add_identity(J, iu, iu, n_, cj);
  BlockJacobian::add_identity(J, iu, iv, n_, -1.0);
  BlockJacobian::add(J, iv, iu, f_u, -1.0);
  BlockJacobian::add(J, iv, iv, f_v, -1.0);
  BlockJacobian::add(J, iv, iv, M, cj);
  if (m_ == 0) return;
  BlockJacobian::add(J, iv, il, Eigen::SparseMatrix<double>(A.transpose()));
  switch (scheme_) {
    case MultiplierScheme::index1:
      BlockJacobian::add(J, il, iv, A, cj);
      break;
    case MultiplierScheme::baumgarte: {
      BlockJacobian::add(J, il, iv, A, cj + 2.0 * alpha_);
      BlockJacobian::add(J, il, iu, Eigen::SparseMatrix<double>(position_mask_ * A), beta_ * beta_);
      break;
    }
    case MultiplierScheme::index2:
      BlockJacobian::add(J, il, iv, A);
      break;
    case MultiplierScheme::index3:
      BlockJacobian::add(J, il, iu, Eigen::SparseMatrix<double>(position_mask_ * A));
      BlockJacobian::add(J, il, iv, Eigen::SparseMatrix<double>(velocity_mask_ * A));
      break;
    case MultiplierScheme::ggl:
      BlockJacobian::add(J, il, iv, A);
      BlockJacobian::add(J, iu, im, Eigen::SparseMatrix<double>(Ap.transpose()));
      BlockJacobian::add(J, im, iu, Ap);
      break;
  }
}

void MultiplierDae::make_consistent(double t, Eigen::VectorXd& y, Eigen::VectorXd& yp) const {
  const Eigen::VectorXd uu = y.segment(0, n_), vv = y.segment(n_, n_);
  auto& f = force_;
  system_.force(t, t, uu, vv, f);
  const auto& M = system_.mass(t, uu);
  yp = Eigen::VectorXd::Zero(size());
  yp.segment(0, n_) = vv;
  if (m_ == 0) {
    Eigen::SparseLU<Eigen::SparseMatrix<double>> lu(M);
    if (lu.info() != Eigen::Success) {
      throw std::runtime_error("the mass matrix is singular: accelerations are undefined");
    }
    yp.segment(n_, n_) = lu.solve(f);
    return;
  }
  const auto& A = system_.constraint_jacobian(t, uu);
  Eigen::VectorXd rhs_l(m_), work(m_);
  system_.acceleration_bias(t, uu, vv, rhs_l);
  if (scheme_ == MultiplierScheme::baumgarte) {
    system_.velocity_residual(t, uu, vv, work);
    rhs_l -= 2.0 * alpha_ * work;
    system_.position_residual(t, uu, work);
    rhs_l -= beta_ * beta_ * work;
  }
  // [M Aᵀ; A 0] [v'; λ] = [f; γ]
  const Eigen::SparseMatrix<double> kkt = kkt_matrix(M, A);
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu;
  lu.compute(kkt);
  if (lu.info() != Eigen::Success) {
    std::ostringstream s;
    s << "the consistency system [M Aᵀ; A 0] is singular at t = " << t
      << ": some DOF has neither mass nor a constraint that fixes its acceleration";
    throw std::runtime_error(s.str());
  }
  Eigen::VectorXd rhs(n_ + m_);
  rhs << f, rhs_l;
  const Eigen::VectorXd sol = lu.solve(rhs);
  yp.segment(n_, n_) = sol.head(n_);
  y.segment(lambda_at(), m_) = sol.tail(m_);
  y.segment(mu_at(), p_).setZero();
}

}  // namespace condyn
