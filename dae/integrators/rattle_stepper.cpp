#include "dae/integrators/rattle_stepper.hpp"

namespace condyn {

RattleStepper::RattleStepper(const MechanicalSystem& system, const RattleSettings& settings,
                             double step, double t0, const Eigen::VectorXd& u0,
                             const Eigen::VectorXd& v0)
    : system_(system.clone()),
      n_(system.dofs()),
      m_(system.constraints()),
      step_(*system_, settings),
      grid_(t0, step),
      stop_(t0),
      t_(t0),
      t_prev_(t0),
      u_(u0),
      v_(v0),
      mu_(Eigen::VectorXd::Zero(system.constraints())),
      u_prev_(u0),
      v_prev_(v0),
      mu_prev_(mu_) {
  system_->begin_segment(t0);
}

double RattleStepper::step(double tout) {
  const double t_next = grid_.next_time(t_, stop_, tout);
  const double h = grid_.step_length(t_, t_next);
  Eigen::VectorXd u = u_, v = v_, mu;
  step_.advance(t_, h, u, v, mu);
  u_prev_ = std::move(u_);
  v_prev_ = std::move(v_);
  mu_prev_ = std::move(mu_);
  u_ = std::move(u);
  v_ = std::move(v);
  mu_ = std::move(mu);
  t_prev_ = t_;
  t_ = t_next;
  last_step_ = h;
  ++steps_;
  return t_;
}

Eigen::VectorXd RattleStepper::pack(const Eigen::VectorXd& u, const Eigen::VectorXd& v,
                                    const Eigen::VectorXd& mu) const {
  Eigen::VectorXd out(2 * n_ + m_);
  out << u, v, mu;
  return out;
}

Eigen::VectorXd RattleStepper::y() { return pack(u_, v_, mu_); }

Eigen::VectorXd RattleStepper::yp() {
  Eigen::VectorXd y, yp;
  interpolate(t_, y, yp);
  return yp;
}

void RattleStepper::interpolate(double t, Eigen::VectorXd& y, Eigen::VectorXd& yp) {
  const double h = t_ - t_prev_;
  if (!(h > 0.0)) {  // before the first step, or at a restart
    y = pack(u_, v_, mu_);
    yp = pack(v_, Eigen::VectorXd::Zero(n_), Eigen::VectorXd::Zero(m_));
    return;
  }
  const double s = (t - t_prev_) / h;
  Eigen::VectorXd u, v, acc;
  hermite(s, h, u_prev_, v_prev_, u_, v_, u, v, &acc);
  y = pack(u, v, (1 - s) * mu_prev_ + s * mu_);
  yp = pack(v, acc, Eigen::VectorXd::Zero(m_));
}

void RattleStepper::restart(double t) {
  t_ = t;
  system_->begin_segment(t);
  u_prev_ = u_;
  v_prev_ = v_;
  mu_prev_ = mu_;
  t_prev_ = t_;
}

void RattleStepper::fill_summary(SolveSummary& summary) {
  summary.steps = steps_;
  summary.residual_evals = step_.force_evaluations();
  summary.jacobian_evals = step_.factorizations();
  summary.newton_iterations = step_.newton_iterations();
  summary.last_step = last_step_;
}

}  // namespace condyn
