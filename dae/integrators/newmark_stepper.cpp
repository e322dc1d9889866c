#include "dae/integrators/newmark_stepper.hpp"

#include "dae/linsolve/velocity_jump.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <utility>

#include "dae/integrators/newmark_error_control.hpp"
#include "dae/integrators/stabilized_newmark_newton.hpp"

namespace condyn {

NewmarkStepper::NewmarkStepper(const MechanicalSystem& system, bool linear,
                               const NewmarkSettings& settings, ConsistentAccelerations consistent,
                               double t0, const Eigen::VectorXd& u0, const Eigen::VectorXd& v0)
    : system_(system.clone()),
      settings_(settings),
      consistent_(std::move(consistent)),
      linear_(linear),
      n_(system.dofs()),
      m_(system.constraints()),
      newton_(make_step_newton(*system_, linear, settings.constraints)),
      grid_(t0, settings.step),
      stop_(t0),
      t_(t0),
      t_prev_(t0) {
  system_->begin_segment(t0);
  if (!(settings.step > 0.0)) newton_->set_stale_ratio(NewmarkStepRules::kStaleRatio);
  x_.u = u0;
  x_.v = v0;
  consistent_accelerations();
  x_prev_ = x_;
}

void NewmarkStepper::consistent_accelerations() {
  auto solved = consistent_(t_, x_.u, x_.v);
  if (!solved) {
    std::ostringstream s;
    s << "the accelerations and multipliers at t = " << t_
      << " cannot be solved from the constraints at acceleration level ([M A^T; A 0] singular)";
    throw IntegrationError(FailureKind::linear_solver, s.str());
  }
  x_.acc = std::move(solved->first);
  x_.lambda = std::move(solved->second);
  x_.mu = Eigen::VectorXd::Zero(newton_->mu_size());
  a_ = x_.acc;
}

double NewmarkStepper::step(double tout) {
  return settings_.step > 0.0 ? fixed_step(tout) : controlled_step(tout);
}

double NewmarkStepper::fixed_step(double tout) {
  const double t_next = grid_.next_time(t_, stop_, tout);
  const double h = grid_.step_length(t_, t_next);
  StepState x;
  Eigen::VectorXd a;
  if (const auto failure = attempt(t_next, h, x, a)) {
    std::ostringstream s;
    s << failure->what << " at t = " << t_next << " (fixed step " << settings_.step
      << settings_.step_advice << ")";
    throw IntegrationError(failure->kind, s.str());
  }
  accept(t_next, h, std::move(x), std::move(a));
  return t_;
}

std::optional<NewmarkStepper::StepFailure> NewmarkStepper::attempt(double t_next, double h,
                                                                   StepState& x,
                                                                   Eigen::VectorXd& a) {
  const AlphaParameters& p = settings_.parameters;
  const StepCoefficients c{(1.0 - p.alpha_m) / (h * h * p.beta * (1.0 - p.alpha_f)),
                           p.gamma / (h * p.beta)};
  // The predictor: ü and λ kept, a, v and u from the step's formulas (consistent with them, so
  // Newton's increments keep the formulas exact).
  const auto algorithmic = [&](const Eigen::VectorXd& acc) -> Eigen::VectorXd {
    return (p.alpha_f * x_.acc - p.alpha_m * a_ + (1.0 - p.alpha_f) * acc) / (1.0 - p.alpha_m);
  };
  x = x_;
  const Eigen::VectorXd a_pred = algorithmic(x.acc);
  x.u = x_.u + h * x_.v + (h * h) * ((0.5 - p.beta) * a_ + p.beta * a_pred);
  x.v = x_.v + h * ((1.0 - p.gamma) * a_ + p.gamma * a_pred);
  if (auto failure = solve_step(t_next, c, x)) return failure;
  a = algorithmic(x.acc);
  return std::nullopt;
}

void NewmarkStepper::accept(double t_next, double h, StepState x, Eigen::VectorXd a) {
  a_ = std::move(a);
  x_prev_ = std::move(x_);
  x_ = std::move(x);
  t_prev_ = t_;
  t_ = t_next;
  last_step_ = h;
  ++steps_;
}

std::optional<NewmarkStepper::StepFailure> NewmarkStepper::solve_step(double t_next,
                                                                      const StepCoefficients& c,
                                                                      StepState& x) {
  Eigen::VectorXd r, d, trial;
  newton_->begin_step(x);
  newton_->residual(t_next, x, c, r);
  int exact = 0;  // iterations on the factors of this step's own matrix
  for (int k = 0; k < settings_.max_newton_iterations; ++k) {
    if (!r.allFinite())
      return StepFailure{FailureKind::residual_non_finite, "the residual is not finite"};
    if (!newton_->factor(t_next, x, c))
      return StepFailure{FailureKind::linear_solver, "singular Newton matrix"};
    const bool stale = newton_->stale();
    d = -r;
    newton_->solve_in_place(d);
    ++newton_iterations_;
    // The iterate before the correction, for backtracking (nonlinear models only, below).
    StepState start;
    if (!linear_) start = x;
    newton_->apply(t_next, d, c, x);
    const auto du = d.head(n_);
    // A linear model's first Newton step on its own matrix solves its equations up to the
    // roundoff of the factored matrix, eps times its condition times the step (2.5e7 |u| eps on a
    // spring of 1e12 with h ω = 1e4); the second, on the residual it leaves, refines that to the
    // residual's own roundoff at the cost of a solve (the factorization is kept). A first step
    // already within the tolerance below needs no refinement. On stale factors (error control,
    // StepNewton::set_stale_ratio) the iterations converge linearly to the tolerance below.
    if (!stale && linear_ && ++exact == 2) return std::nullopt;
    const double weighted =
        (du.array().abs() / (settings_.rtol * x.u.array().abs() + settings_.atol)).maxCoeff();
    if (!(weighted > settings_.newton_fraction)) {
      if (!std::isfinite(weighted))
        return StepFailure{FailureKind::non_finite, "Newton's update is not finite"};
      return std::nullopt;
    }
    // Backtracking: a correction whose full length raises the scaled residual's norm is halved
    // until it lowers it. Near a singular configuration (the N-four-bar's cranks on the ground
    // line, IFToMM A02) the constraints' quadratic terms outweigh the linear ones that Newton's
    // correction follows: full corrections overshoot and the iteration diverges, halved ones
    // reach the root next to the predictor, on the motion's branch (docs/schemes.md). Away from
    // such configurations the full correction lowers the residual and is taken as before (its
    // residual is the next iteration's). A linear model's residual is linear in the correction:
    // nothing to search.
    newton_->residual(t_next, x, c, trial);
    if (linear_) {
      r.swap(trial);
      continue;
    }
    // Sufficient decrease (Armijo's test): the residual's norm falls by at least a share of the
    // correction's length (a full Newton correction away from a root's roundoff lowers it by far
    // more; near a singular root by about half).
    double length = 1.0;
    const auto lowered = [&] {
      return trial.norm() <= (1.0 - NewmarkStepRules::kSufficientDecrease * length) * r.norm();
    };
    for (int halvings = 0; halvings < NewmarkStepRules::kMaxHalvings && !lowered(); ++halvings) {
      length *= 0.5;
      d *= 0.5;
      x = start;
      newton_->return_to(t_next, x);
      newton_->apply(t_next, d, c, x);
      newton_->residual(t_next, x, c, trial);
    }
    if (!lowered()) {
      // Not even a short step along Newton's correction lowers the residual: it is at its
      // roundoff, and the correction is that roundoff amplified by a nearly singular matrix
      // (at A02's passages, corrections twice the tolerance on residuals of 2e-14). Converged,
      // if what is left of the residual is within the tolerance (backward_error).
      x = start;
      newton_->return_to(t_next, x);
      if (backward_error(t_next, x, c, r) <= settings_.newton_fraction) return std::nullopt;
      return StepFailure{FailureKind::convergence,
                         "the residual does not decrease along Newton's correction"};
    }
    r.swap(trial);
    // Stale factors that have not converged in a few iterations: this step's own from here on.
    if (stale && k + 1 >= NewmarkStepRules::kStaleIterations) newton_->drop_factors();
  }
  // Iterations that crawl (a step that lands on a singular configuration: Newton's iterations
  // converge linearly to a root where the matrix is singular, A02 at h = 1e-4) end converged
  // when the residual left is within the tolerance.
  if (!linear_ && backward_error(t_next, x, c, r) <= settings_.newton_fraction) return std::nullopt;
  return StepFailure{FailureKind::convergence, "Newton's iterations did not converge in " +
                                                   std::to_string(settings_.max_newton_iterations)};
}

double NewmarkStepper::backward_error(double t, const StepState& x, const StepCoefficients& c,
                                      const Eigen::VectorXd& r) const {
  const double tau = settings_.rtol * x.u.lpNorm<Eigen::Infinity>() + settings_.atol;
  const Eigen::VectorXd reach = tau * newton_->row_sensitivities(t, x, c);
  double worst = 0.0;
  for (Eigen::Index i = 0; i < r.size(); ++i) {
    if (r[i] == 0.0) continue;
    if (!(reach[i] > 0.0)) return std::numeric_limits<double>::infinity();
    worst = std::max(worst, std::abs(r[i]) / reach[i]);
  }
  return worst;
}

Eigen::VectorXd NewmarkStepper::pack(const StepState& x, bool derivative) const {
  Eigen::VectorXd out(size());
  if (derivative) {
    out << x.v, x.acc, Eigen::VectorXd::Zero(m_ + x.mu.size());
  } else {
    out << x.u, x.v, x.lambda, x.mu;
  }
  return out;
}

Eigen::VectorXd NewmarkStepper::y() { return pack(x_, false); }
Eigen::VectorXd NewmarkStepper::yp() { return pack(x_, true); }

void NewmarkStepper::interpolate(double t, Eigen::VectorXd& y, Eigen::VectorXd& yp) {
  const double h = t_ - t_prev_;
  if (!(h > 0.0)) {
    y = pack(x_, false);
    yp = pack(x_, true);
    return;
  }
  const double s = (t - t_prev_) / h;
  const StepState& a = x_prev_;
  const StepState& b = x_;
  StepState x;
  hermite(s, h, a.u, a.v, b.u, b.v, x.u, x.v);
  x.acc = (1 - s) * a.acc + s * b.acc;
  x.lambda = (1 - s) * a.lambda + s * b.lambda;
  x.mu = (1 - s) * a.mu + s * b.mu;
  y = pack(x, false);
  yp = pack(x, true);
}

void NewmarkStepper::restart(double t) {
  t_ = t;
  system_->begin_segment(t);
  // A drive's rate may change here (a table's sample): v onto the rows at the new rate, as the
  // multiplier schemes' restart does.
  jump_onto_velocity_rows(*system_, t, x_.u, x_.v);
  consistent_accelerations();
  x_prev_ = x_;
  t_prev_ = t_;
}

void NewmarkStepper::fill_summary(SolveSummary& summary) {
  summary.steps = steps_;
  summary.error_test_failures = rejected_steps_;
  summary.newton_failures = newton_failures_;
  summary.residual_evals = newton_->residuals();
  summary.jacobian_evals = newton_->factorizations();
  summary.newton_iterations = newton_iterations_;
  summary.last_step = last_step_;
}

}  // namespace condyn
