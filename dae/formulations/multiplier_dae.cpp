#include "dae/formulations/multiplier_dae.hpp"

#include "dae/linsolve/condensed_newton.hpp"

#include "dae/linsolve/kkt.hpp"
#include "dae/linsolve/velocity_jump.hpp"
#include "models/core/eigen_decompositions.hpp"

#include <algorithm>
#include <sstream>
#include <stdexcept>
#include <string>

namespace condyn {

namespace {

/// The DOFs whose accelerations a multiplier reaches: the columns of A and, since v' = M⁻¹(f −
/// Aᵀλ), every DOF M's pattern connects to one of them (M⁻¹ is full within a connected block).
std::vector<bool> reached_by_multipliers(const Eigen::SparseMatrix<double>& A,
                                         const Eigen::SparseMatrix<double>& M) {
  const auto n = static_cast<std::size_t>(M.cols());
  std::vector<std::size_t> parent(n);
  for (std::size_t j = 0; j < n; ++j) parent[j] = j;
  const auto root = [&parent](std::size_t j) {
    while (parent[j] != j) j = parent[j] = parent[parent[j]];
    return j;
  };
  for (Eigen::Index k = 0; k < M.outerSize(); ++k) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(M, k); it; ++it) {
      parent[root(static_cast<std::size_t>(it.row()))] = root(static_cast<std::size_t>(it.col()));
    }
  }
  std::vector<bool> constrained_root(n, false), reached(n, false);
  for (Eigen::Index k = 0; k < A.outerSize(); ++k) {
    if (A.col(k).nonZeros() > 0) constrained_root[root(static_cast<std::size_t>(k))] = true;
  }
  for (std::size_t j = 0; j < n; ++j) reached[j] = constrained_root[root(j)];
  return reached;
}

}  // namespace

MultiplierDae::MultiplierDae(const MechanicalSystem& system, Scheme scheme, double alpha,
                             double beta, bool linear)
    : system_(system.clone()),
      scheme_(scheme),
      alpha_(alpha),
      beta_(beta),
      condensed_(linear && (scheme == Scheme::index1 || scheme == Scheme::ggl)),
      n_(system.dofs()),
      m_(system.constraints()),
      p_(0) {
  if (scheme != Scheme::index1 && scheme != Scheme::baumgarte && scheme != Scheme::ggl &&
      scheme != Scheme::index2 && scheme != Scheme::index3) {
    throw std::invalid_argument(std::string("MultiplierDae: ") + to_string(scheme) +
                                " is not a multiplier scheme");
  }
  if (scheme == Scheme::ggl) {
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
  // Patterns at the initial state: every block's pattern is independent of the state
  // (MechanicalSystem's contract), so the Jacobian's pattern is fixed for the run.
  const Eigen::VectorXd zero_n = Eigen::VectorXd::Zero(n_);
  const Eigen::VectorXd y0 = pack(zero_n, zero_n), yp0 = Eigen::VectorXd::Zero(size());
  jacobian_ = BlockJacobian(size());
  for_each_block(0.0, y0, yp0, 1.0,
                 [&](int r, int c, const Eigen::SparseMatrix<double>& S, double /*scale*/) {
                   jacobian_.declare(r, c, S);
                 });
  jacobian_.declare_identity(0, 0, n_);   // d(u')
  jacobian_.declare_identity(0, n_, n_);  // −I
  jacobian_.finish();
  if (linear) held_ = held_massless_of(system);
  if (scheme == Scheme::index3) {
    const Eigen::SparseMatrix<double> A = system_->constraint_jacobian(0.0, zero_n);
    reached_ = reached_by_multipliers(A, system_->mass(0.0, zero_n));
  }
}

void MultiplierDae::for_each_block(double t, ConstRef y, ConstRef yp, double cj,
                                   const BlockVisitor& visit) const {
  using SparseBlock = Eigen::SparseMatrix<double>;
  const auto uu = y.segment(0, n_), vv = y.segment(n_, n_);
  const auto vp = yp.segment(n_, n_);
  const int iu = 0, iv = n_, il = lambda_at(), im = mu_at();
  // Momentum rows: M v' − f + Aᵀλ.
  visit(iv, iv, system_->mass(t, uu), cj);
  visit(iv, iu, system_->stiffness(t, uu, vv), 1.0);
  visit(iv, iv, system_->damping(t, uu, vv), 1.0);
  visit(iv, iu, system_->mass_jacobian(t, uu, vp), 1.0);
  if (m_ == 0) return;
  const auto& A = system_->constraint_jacobian(t, uu);
  visit(iv, il, SparseBlock(A.transpose()), 1.0);
  visit(iv, iu, system_->constraint_force_jacobian(t, uu, y.segment(il, m_)), 1.0);
  const auto acceleration_level = [&](double velocity_scale) {  // A v' − γ
    visit(il, iv, A, cj + velocity_scale);
    visit(il, iu, system_->constraint_product_jacobian(t, uu, vp), 1.0);
    visit(il, iu, system_->acceleration_bias_jacobian_u(t, uu, vv), -1.0);
    visit(il, iv, system_->acceleration_bias_jacobian_v(t, uu, vv), -1.0);
  };
  switch (scheme_) {
    case Scheme::index1:
      acceleration_level(0.0);
      break;
    case Scheme::baumgarte:  // + 2α ψ + β² φ
      acceleration_level(2.0 * alpha_);
      visit(il, iu, system_->velocity_residual_jacobian(t, uu, vv), 2.0 * alpha_);
      visit(il, iu, SparseBlock(position_mask_ * A), beta_ * beta_);
      break;
    case Scheme::index2:
      visit(il, iv, A, 1.0);
      visit(il, iu, system_->velocity_residual_jacobian(t, uu, vv), 1.0);
      break;
    case Scheme::index3: {  // φ on position rows, ψ on velocity rows
      visit(il, iu, SparseBlock(position_mask_ * A), 1.0);
      visit(il, iv, SparseBlock(velocity_mask_ * A), 1.0);
      const auto& psi_u = system_->velocity_residual_jacobian(t, uu, vv);
      if (psi_u.size() > 0) visit(il, iu, SparseBlock(velocity_mask_ * psi_u), 1.0);
      break;
    }
    case Scheme::ggl: {  // ψ = 0, φ_p = 0, and A_pᵀμ in the u rows
      visit(il, iv, A, 1.0);
      visit(il, iu, system_->velocity_residual_jacobian(t, uu, vv), 1.0);
      const SparseBlock Ap = select_p_ * A;
      visit(iu, im, SparseBlock(Ap.transpose()), 1.0);
      visit(im, iu, Ap, 1.0);
      const Eigen::VectorXd w = select_p_.transpose() * y.segment(im, p_);
      visit(iu, iu, system_->constraint_force_jacobian(t, uu, w), 1.0);
      break;
    }
    case Scheme::automatic:
    case Scheme::elimination:
    case Scheme::penalty:
    case Scheme::projection:
    case Scheme::newmark:
    case Scheme::hht:
    case Scheme::generalized_alpha:
    case Scheme::rattle:
      break;  // not multiplier schemes: refused by the constructor
  }
}

Eigen::VectorXd MultiplierDae::differential_id() const {
  Eigen::VectorXd id = Eigen::VectorXd::Zero(size());
  id.head(lambda_at()).setOnes();
  if (held_) {
    Eigen::VectorXd index;
    held_->mark(id, index);
  }
  return id;
}

Eigen::VectorXd MultiplierDae::multiplier_row_scales(double t, const Eigen::VectorXd& y) const {
  if (m_ == 0) return {};
  Eigen::VectorXd scales = Eigen::VectorXd::Zero(size());
  const Eigen::VectorXd uu = u(y);
  const Eigen::SparseMatrix<double>& A = system_->constraint_jacobian(t, uu);
  for (Eigen::Index k = 0; k < A.outerSize(); ++k) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, k); it; ++it) {
      double& c = scales[lambda_at() + it.row()];
      c = std::max(c, std::abs(it.value()));
    }
  }
  for (int k = 0; k < p_; ++k) {
    scales[mu_at() + k] = scales[lambda_at() + position_row_[static_cast<std::size_t>(k)]];
  }
  return scales;
}

Eigen::VectorXd MultiplierDae::multiplier_row_masses(double t, const Eigen::VectorXd& y) const {
  if (m_ == 0) return {};
  Eigen::VectorXd masses = Eigen::VectorXd::Zero(size());
  const Eigen::VectorXd uu = u(y);
  const Eigen::VectorXd diagonal = system_->mass(t, uu).diagonal();
  const Eigen::SparseMatrix<double>& A = system_->constraint_jacobian(t, uu);
  for (Eigen::Index k = 0; k < A.outerSize(); ++k) {
    if (!(diagonal[k] > 0.0)) continue;
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, k); it; ++it) {
      if (it.value() == 0.0) continue;  // a structural zero: the row does not touch the DOF
      double& lightest = masses[lambda_at() + it.row()];
      lightest = lightest > 0.0 ? std::min(lightest, diagonal[k]) : diagonal[k];
    }
  }
  return masses;
}

bool MultiplierDae::error_scale_floors(double t, const ConstRef& y, Eigen::VectorXd& floor) const {
  if (m_ == 0 || (scheme_ != Scheme::ggl && scheme_ != Scheme::index3)) return false;
  const Eigen::VectorXd uu = y.segment(0, n_);
  const Eigen::SparseMatrix<double>& A = system_->constraint_jacobian(t, uu);
  const std::vector<bool>& position = system_->position_rows();
  floor.setZero(size());
  // The rows' shares of the values x (u or v) into floor.segment(at, n): over `rows` (position
  // rows for u; every row for GGL's v, which ψ = 0 holds through λ).
  const auto shares = [&](const Eigen::VectorXd& x, int at, bool all_rows) {
    row_reach_.setZero(m_);
    row_norm2_.setZero(m_);
    for (Eigen::Index k = 0; k < A.outerSize(); ++k) {
      for (Eigen::SparseMatrix<double>::InnerIterator it(A, k); it; ++it) {
        row_reach_[it.row()] += std::abs(it.value() * x[k]);
        row_norm2_[it.row()] += it.value() * it.value();
      }
    }
    for (Eigen::Index k = 0; k < A.outerSize(); ++k) {
      for (Eigen::SparseMatrix<double>::InnerIterator it(A, k); it; ++it) {
        const auto r = it.row();
        if (!(all_rows || position[static_cast<std::size_t>(r)]) || !(row_norm2_[r] > 0.0)) {
          continue;
        }
        double& f = floor[at + k];
        f = std::max(f, std::abs(it.value()) * row_reach_[r] / row_norm2_[r]);
      }
    }
  };
  shares(uu, 0, false);
  // index3's velocities on rows are index 2, out of the error test: no floor.
  if (scheme_ == Scheme::ggl) shares(y.segment(n_, n_), n_, true);
  return true;
}

Eigen::VectorXd MultiplierDae::variable_index() const {
  Eigen::VectorXd index = Eigen::VectorXd::Ones(size());
  switch (scheme_) {
    case Scheme::index1:
    case Scheme::baumgarte:
      break;
    case Scheme::ggl:
    case Scheme::index2:
      index.tail(size() - lambda_at()).setConstant(2.0);  // λ (and μ)
      break;
    case Scheme::index3:
      // The velocities λ reaches (index 2); the others are a plain ODE's, in the error test.
      for (int j = 0; j < n_; ++j) {
        if (reached_[static_cast<std::size_t>(j)]) index[n_ + j] = 2.0;
      }
      for (int i = 0; i < m_; ++i) {
        index[lambda_at() + i] = system_->position_rows()[static_cast<std::size_t>(i)] ? 3.0 : 2.0;
      }
      break;
    case Scheme::automatic:
    case Scheme::elimination:
    case Scheme::penalty:
    case Scheme::projection:
    case Scheme::newmark:
    case Scheme::hht:
    case Scheme::generalized_alpha:
    case Scheme::rattle:
      break;  // not multiplier schemes: refused by the constructor
  }
  if (held_) {
    Eigen::VectorXd id = Eigen::VectorXd::Ones(size());
    held_->mark(id, index);
  }
  return index;
}

Eigen::VectorXd MultiplierDae::pack(const Eigen::VectorXd& u0, const Eigen::VectorXd& v0) const {
  Eigen::VectorXd y = Eigen::VectorXd::Zero(size());
  y.segment(0, n_) = u0;
  y.segment(n_, n_) = v0;
  return y;
}

void MultiplierDae::residual(double t, ConstRef y, ConstRef yp, Ref r) const {
  const auto uu = y.segment(0, n_), vv = y.segment(n_, n_), lam = y.segment(lambda_at(), m_);
  const auto up = yp.segment(0, n_), vp = yp.segment(n_, n_);
  auto& f = force_;
  system_->force(t, uu, vv, f);
  const auto& M = system_->mass(t, uu);
  r.segment(0, n_) = up - vv;
  r.segment(n_, n_) = M * vp - f;
  if (m_ == 0) return;  // unconstrained: a plain second-order ODE
  const auto& A = system_->constraint_jacobian(t, uu);
  r.segment(n_, n_) += A.transpose() * lam;
  auto rl = r.segment(lambda_at(), m_);
  auto& work = rows_;
  switch (scheme_) {
    case Scheme::index1:
      system_->acceleration_bias(t, uu, vv, work);
      rl = A * vp - work;
      break;
    case Scheme::baumgarte: {
      system_->acceleration_bias(t, uu, vv, work);
      rl = A * vp - work;
      system_->velocity_residual(t, uu, vv, work);
      rl += 2.0 * alpha_ * work;
      system_->position_residual(t, uu, work);
      rl += beta_ * beta_ * work;
      break;
    }
    case Scheme::index2:
      system_->velocity_residual(t, uu, vv, rl);
      break;
    case Scheme::index3: {
      system_->position_residual(t, uu, work);  // zero on velocity rows
      rl = work;
      system_->velocity_residual(t, uu, vv, work);
      rl += velocity_mask_ * work;
      break;
    }
    case Scheme::ggl: {
      system_->velocity_residual(t, uu, vv, rl);
      const auto mu = y.segment(mu_at(), p_);
      r.segment(0, n_) += A.transpose() * (select_p_.transpose() * mu);
      system_->position_residual(t, uu, work);
      r.segment(mu_at(), p_) = select_p_ * work;
      break;
    }
    case Scheme::automatic:
    case Scheme::elimination:
    case Scheme::penalty:
    case Scheme::projection:
    case Scheme::newmark:
    case Scheme::hht:
    case Scheme::generalized_alpha:
    case Scheme::rattle:
      break;  // not multiplier schemes: refused by the constructor
  }
}

void MultiplierDae::fill_jacobian(double t, ConstRef y, ConstRef yp, double cj,
                                  JacobianMap J) const {
  std::fill_n(J.valuePtr(), J.nonZeros(), 0.0);
  BlockJacobian::add_identity(J, 0, 0, n_, cj);
  BlockJacobian::add_identity(J, 0, n_, n_, -1.0);
  for_each_block(t, y, yp, cj,
                 [&J](int r, int c, const Eigen::SparseMatrix<double>& S, double scale) {
                   BlockJacobian::add(J, r, c, S, scale);
                 });
}

void MultiplierDae::make_consistent(double t, Eigen::VectorXd& y, Eigen::VectorXd& yp) const {
  if (held_) {
    make_consistent_held(t, y, yp);
    return;
  }
  const Eigen::VectorXd uu = y.segment(0, n_), vv = y.segment(n_, n_);
  auto& f = force_;
  system_->force(t, uu, vv, f);
  const auto& M = system_->mass(t, uu);
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
  const auto& A = system_->constraint_jacobian(t, uu);
  const Eigen::VectorXd rhs_l = constraint_rhs(t, uu, vv);
  // [M Aᵀ; A 0] [v'; λ] = [f; γ]
  const Eigen::SparseMatrix<double> kkt = kkt_matrix(M, A);
  KktLu lu;
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

void MultiplierDae::jump_velocities(double t, Eigen::VectorXd& y) const {
  if (held_) return;
  const Eigen::VectorXd uu = y.segment(0, n_);
  Eigen::VectorXd vv = y.segment(n_, n_);
  jump_onto_velocity_rows(*system_, t, uu, vv);
  y.segment(n_, n_) = vv;
}

Eigen::VectorXd MultiplierDae::constraint_rhs(double t, const Eigen::VectorXd& uu,
                                              const Eigen::VectorXd& vv) const {
  Eigen::VectorXd rhs_l(m_), work(m_);
  system_->acceleration_bias(t, uu, vv, rhs_l);
  if (scheme_ == Scheme::baumgarte) {
    system_->velocity_residual(t, uu, vv, work);
    rhs_l -= 2.0 * alpha_ * work;
    system_->position_residual(t, uu, work);
    rhs_l -= beta_ * beta_ * work;
  }
  return rhs_l;
}

void MultiplierDae::make_consistent_held(double t, Eigen::VectorXd& y, Eigen::VectorXd& yp) const {
  Eigen::VectorXd uu = y.segment(0, n_), vv = y.segment(n_, n_);
  Eigen::VectorXd rhs(n_ + m_);
  system_->force(t, uu, vv, force_);
  rhs.head(n_) = force_;
  if (m_ > 0) rhs.tail(m_) = constraint_rhs(t, uu, vv);
  const Eigen::VectorXd fdot = time_derivative(t, force_, [&](double s) {
    Eigen::VectorXd f(n_);
    system_->force(s, uu, vv, f);
    return f;
  });
  const Eigen::VectorXd sol = held_->consistent(rhs, fdot, uu, vv);
  y.segment(0, n_) = uu;
  y.segment(n_, n_) = vv;
  y.segment(lambda_at(), m_) = sol.tail(m_);
  y.segment(mu_at(), p_).setZero();
  yp = Eigen::VectorXd::Zero(size());
  yp.segment(0, n_) = vv;
  yp.segment(n_, n_) = sol.head(n_);
}

std::vector<bool> MultiplierDae::algebraic_equations() const {
  std::vector<bool> algebraic(static_cast<std::size_t>(size()), false);
  if (scheme_ == Scheme::ggl) std::fill(algebraic.begin() + lambda_at(), algebraic.end(), true);
  return algebraic;
}

std::unique_ptr<NewtonSystem> MultiplierDae::newton_system() const {
  if (!condensed_) return nullptr;
  return std::make_unique<CondensedNewton>(scheme_, linear_matrices(*system_), select_p_);
}

}  // namespace condyn
