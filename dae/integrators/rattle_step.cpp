#include "dae/integrators/rattle_step.hpp"

#include <cmath>
#include <sstream>
#include <string>

#include "dae/integrators/step_driver.hpp"
#include "dae/linsolve/kkt.hpp"

namespace condyn {

namespace {

using Sparse = Eigen::SparseMatrix<double>;

[[noreturn]] void fail(FailureKind kind, const std::string& what, double t) {
  std::ostringstream s;
  s << "rattle: " << what << " at t = " << t << " (a smaller [solve] step may converge)";
  throw IntegrationError(kind, s.str());
}

}  // namespace

RattleStep::RattleStep(MechanicalSystem& system, const RattleSettings& settings)
    : system_(system),
      settings_(settings),
      n_(system.dofs()),
      m_(system.constraints()),
      constant_rows_(system.constraints() == 0 || !system.has_curvature()),
      lambda_scaled_(Eigen::VectorXd::Zero(system.constraints())) {
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(n_);
  M_ = system.mass(0.0, zero);
  M_.makeCompressed();
}

void RattleStep::factor(double t, const Sparse& U, const Sparse& L) {
  if (constant_rows_ && factored_) return;
  matrix_ = m_ > 0 ? kkt_matrix(M_, U, L) : M_;
  nonzeros_ = matrix_.nonZeros();
  ++factorizations_;
  factored_ = klu_.factor(matrix_);
  if (!factored_) fail(FailureKind::linear_solver, "singular matrix [M A^T; A 0]", t);
}

void RattleStep::solve_positions(double t_next, const Sparse& A_n, const Eigen::VectorXd& c,
                                 Eigen::VectorXd& u) {
  Eigen::VectorXd lambda = lambda_scaled_;
  for (int k = 0; k < settings_.max_newton_iterations; ++k) {
    d_.resize(n_ + m_);
    d_.head(n_) = M_ * u - c;
    if (m_ > 0) {
      d_.head(n_) += A_n.transpose() * lambda;
      phi_.resize(m_);
      system_.position_residual(t_next, u, phi_);
      d_.tail(m_) = phi_;
    }
    if (!d_.allFinite())
      fail(FailureKind::residual_non_finite, "the residual is not finite", t_next);
    if (m_ > 0) {
      const Sparse A_k = system_.constraint_jacobian(t_next, u);
      factor(t_next, A_n, A_k);
    } else {
      factor(t_next, A_n, A_n);
    }
    d_ = -d_;
    klu_.solve_in_place(d_);
    ++newton_iterations_;
    const auto du = d_.head(n_);
    u += du;
    lambda += d_.tail(m_);
    // Constant rows make both blocks linear: the first iteration is exact up to roundoff.
    if (constant_rows_) break;
    const double weighted =
        (du.array().abs() / (settings_.rtol * u.array().abs() + settings_.atol)).maxCoeff();
    if (!std::isfinite(weighted))
      fail(FailureKind::non_finite, "Newton's update is not finite", t_next);
    if (weighted <= 1.0) {
      lambda_scaled_ = lambda;
      return;
    }
  }
  if (constant_rows_) {
    lambda_scaled_ = lambda;
    return;
  }
  fail(FailureKind::convergence,
       "Newton's iterations on the position constraints did not converge in " +
           std::to_string(settings_.max_newton_iterations),
       t_next);
}

void RattleStep::advance(double t, double h, Eigen::VectorXd& u, Eigen::VectorXd& v,
                         Eigen::VectorXd& mu) {
  const double t_next = t + h;
  // The first half kick and the drift: the position stage.
  f_.resize(n_);
  system_.force(t, u, v, f_);
  ++forces_;
  const Sparse A_n = m_ > 0 ? system_.constraint_jacobian(t, u) : Sparse(0, n_);
  Eigen::VectorXd u_next = u + h * v;
  const Eigen::VectorXd c = M_ * u_next + (0.5 * h * h) * f_;
  solve_positions(t_next, A_n, c, u_next);
  const Eigen::VectorXd v_half = (u_next - u) / h;
  // The second half kick, projected on the velocity constraints.
  system_.force(t_next, u_next, v_half, f_);
  ++forces_;
  d_.resize(n_ + m_);
  d_.head(n_) = M_ * v_half + (0.5 * h) * f_;
  if (m_ > 0) {
    const Sparse A_next = system_.constraint_jacobian(t_next, u_next);
    phi_.resize(m_);
    system_.velocity_residual(t_next, u_next, Eigen::VectorXd::Zero(n_), phi_);
    d_.tail(m_) = -phi_;
    factor(t_next, A_next, A_next);
  }
  if (!d_.allFinite()) fail(FailureKind::residual_non_finite, "the force is not finite", t_next);
  const Eigen::VectorXd rhs = d_;
  klu_.solve_in_place(d_);
  Eigen::VectorXd correction = rhs - matrix_ * d_;  // one step of iterative refinement
  klu_.solve_in_place(correction);
  d_ += correction;
  u = std::move(u_next);
  v = d_.head(n_);
  mu = (2.0 / h) * d_.tail(m_);
}

}  // namespace condyn
