#include "dae/integrators/sundials_stepper.hpp"

#include <algorithm>
#include <sstream>
#include <string>
#include <utility>

namespace condyn::sundials {

void record_message(int /*code*/, const char* /*module*/, const char* function, char* msg,
                    void* report) {
  static_cast<CallbackReport*>(report)->message = std::string(function) + ": " + msg;
}

void SundialsStepper::check(int flag, const char* call) const {
  if (flag < 0) {
    throw IntegrationError(api_.failure_kind(flag),
                           std::string(call) + " failed with " + flag_name(api_.flag_name, flag) +
                               (report_.message.empty() ? "" : ": " + report_.message));
  }
}

void SundialsStepper::after_step(int flag) const {
  if (report_.error) std::rethrow_exception(report_.error);
  if (flag >= 0) {
    int order = 0;
    if (api_.last_order(mem_, &order) == 0) max_order_used_ = std::max(max_order_used_, order);
    return;
  }
  double tcur = 0.0, hlast = 0.0;
  api_.current_time(mem_, &tcur);
  api_.last_step(mem_, &hlast);
  std::ostringstream s;
  s << api_.step_call << " failed with " << flag_name(api_.flag_name, flag) << " at t = " << tcur
    << " (last step " << hlast << ")";
  if (!report_.message.empty()) s << ": " << report_.message;
  if (!report_.recoverable.empty()) {
    s << " (the equations' last complaint: " << report_.recoverable << ")";
  }
  throw IntegrationError(api_.failure_kind(flag), s.str());
}

void SundialsStepper::interpolate(double t, Eigen::VectorXd& y, Eigen::VectorXd& yp) {
  check(api_.dky(mem_, t, 0, work_), "GetDky");
  y = view(work_);
  check(api_.dky(mem_, t, 1, work_), "GetDky");
  yp = view(work_);
}

void SundialsStepper::collect() {
  const Counters now = read_counters();
  totals_.steps += now.steps - baseline_.steps;
  totals_.evaluations += now.evaluations - baseline_.evaluations;
  totals_.jacobians += now.jacobians - baseline_.jacobians;
  totals_.newton += now.newton - baseline_.newton;
  totals_.newton_failures += now.newton_failures - baseline_.newton_failures;
  totals_.error_tests += now.error_tests - baseline_.error_tests;
  totals_.projections += now.projections - baseline_.projections;
  baseline_ = now;
  double h = 0.0;
  check(api_.last_step(mem_, &h), "GetLastStep");
  if (h != 0.0) last_step_ = h;
}

void SundialsStepper::fill_summary(SolveSummary& summary) {
  collect();
  summary.steps = totals_.steps;
  summary.residual_evals = totals_.evaluations;
  summary.jacobian_evals = totals_.jacobians;
  summary.newton_iterations = totals_.newton;
  summary.newton_failures = totals_.newton_failures;
  summary.error_test_failures = totals_.error_tests;
  summary.last_step = last_step_;
  summary.max_order_used = max_order_used_;
  // The integrator's note replaces what the run noted before it (kept as it always was: the
  // scheme's setting notes are not printed beside it).
  if (std::string n = notes(totals_); !n.empty()) {
    summary.notes.assign(1, RunNote{RunNote::Kind::integrator, std::move(n)});
  }
}

}  // namespace condyn::sundials
