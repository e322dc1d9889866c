// The Newmark family's error-controlled step (NewmarkStepper without a fixed step): attempts
// from the proposed step, each judged by the Zienkiewicz-Xie estimate
// (dae/integrators/newmark_error_control.hpp), shorter after a rejection or a failed Newton
// solve, landing on the stop time (a load step, a drive's table sample, the end of the run).

#include <algorithm>
#include <cmath>
#include <sstream>
#include <utility>

#include "dae/integrators/newmark_error_control.hpp"
#include "dae/integrators/newmark_stepper.hpp"

namespace condyn {

double NewmarkStepper::controlled_step(double tout) {
  using R = NewmarkStepRules;
  if (!(next_step_ > 0.0)) {
    double span = std::min(tout - t_, stop_ - t_);
    if (settings_.first_kink > t_) span = std::min(span, 0.5 * (settings_.first_kink - t_));
    next_step_ = first_newmark_step(settings_.parameters.beta, a_, x_.u, settings_.rtol,
                                    settings_.atol, span);
  }
  double h = next_step_;
  // The last failed attempt's kind and words (none yet).
  StepFailure last{FailureKind::error_test, ""};
  for (int failures = 0;; ++failures) {
    const double proposed = h;
    double t_next = t_ + h;
    if (t_next >= stop_ - R::kStretch * h) {
      t_next = stop_;
      h = stop_ - t_;
    }
    const double h_min = R::kMinStepRelative * std::max(std::abs(t_), std::abs(stop_));
    if (failures == R::kMaxFailures || !(h > h_min)) {
      std::ostringstream s;
      s << "the step was cut to " << h << " at t = " << t_ << " after " << failures
        << " failed attempts (the last: " << last.what << ")";
      throw IntegrationError(!(h > h_min) ? FailureKind::step_size_collapsed : last.kind, s.str());
    }
    StepState x;
    Eigen::VectorXd a;
    if (auto failure = attempt(t_next, h, x, a)) {
      ++newton_failures_;
      last = std::move(*failure);
      h *= R::kNewtonCut;
      continue;
    }
    const StepHistory history{h, t_ - t_prev_, &x_prev_.v, &x_.v, &x.v, &a_, &a};
    const double error = zienkiewicz_xie_norm(settings_.parameters.beta, history, x_.u,
                                              settings_.rtol, settings_.atol);
    if (!(error <= 1.0)) {
      ++rejected_steps_;
      std::ostringstream s;
      s << "error estimate " << error << " times the tolerance";
      last = {FailureKind::error_test, s.str()};
      h = std::isfinite(error) ? next_newmark_step(h, error, true) : h * R::kMinShrink;
      continue;
    }
    // A step shortened to land on the stop time keeps the proposal it was cut from.
    next_step_ =
        std::max(next_newmark_step(h, error, failures > 0), t_next == stop_ ? proposed : 0.0);
    accept(t_next, h, std::move(x), std::move(a));
    return t_;
  }
}

}  // namespace condyn
