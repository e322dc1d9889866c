#include "dae/integrators/step_driver.hpp"

#include "dae/interface/interrupt.hpp"
#include "dae/interface/recoverable_error.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>

namespace condyn {

const char* to_string(FailureKind kind) {
  switch (kind) {
    case FailureKind::unknown:
      return "integrator failure";
    case FailureKind::non_finite:
      return "non-finite solution";
    case FailureKind::residual_non_finite:
      return "repeated residual failures";
    case FailureKind::step_budget:
      return "step budget exhausted";
    case FailureKind::wall_time_budget:
      return "wall-time budget exhausted";
    case FailureKind::steps_per_output:
      return "too many steps between two outputs";
    case FailureKind::step_size_collapsed:
      return "step size collapsed";
    case FailureKind::convergence:
      return "Newton convergence failures";
    case FailureKind::error_test:
      return "error-test failures";
    case FailureKind::tolerance_too_tight:
      return "tolerances too tight";
    case FailureKind::linear_solver:
      return "linear solver failure";
    case FailureKind::first_step:
      return "failure before the first step";
    case FailureKind::bad_input:
      return "integrator input refused";
    case FailureKind::interrupted:
      return "interrupted";
  }
  return "integrator failure";
}

TimeGrid make_time_grid(const std::vector<double>& output_times,
                        const std::vector<double>& breakpoints) {
  TimeGrid grid;
  const double t0 = output_times.front(), t_end = output_times.back();
  const double tol = time_merge_tolerance(t0, t_end);
  grid.tolerance = tol;

  // Load steps: a cluster within tol of the last kept time (t0 or a stop) joins it, and stands
  // for its last member, so every step of the cluster is on in the segment after it.
  double last = t0;
  bool at_t0 = true;
  for (double b : breakpoints) {
    if (b <= t0) continue;
    if (b >= t_end - tol) break;  // switches on within roundoff of the end: changes nothing
    if (b - last <= tol) {
      if (at_t0) {
        grid.initial_stop = b;
      } else {
        grid.stops.back() = b;
      }
    } else {
      grid.stops.push_back(b);
      at_t0 = false;
    }
    last = b;
  }

  // Outputs: each one within tol of a stop is that stop; ones within tol of t0, t_end or the
  // output kept before them are the same time and dropped.
  const auto& marks = grid.stops;
  grid.outputs.push_back(t0);
  for (std::size_t k = 1; k + 1 < output_times.size(); ++k) {
    double t = output_times[k];
    if (t - t0 <= tol || t_end - t <= tol) continue;
    // The nearest stop: the first one at or after t, or the one before it.
    const auto after = std::lower_bound(marks.begin(), marks.end(), t);
    if (after != marks.end() && *after - t <= tol) {
      t = *after;
    } else if (after != marks.begin() && t - *(after - 1) <= tol) {
      t = *(after - 1);
    }
    if (t - grid.outputs.back() <= tol) continue;
    grid.outputs.push_back(t);
  }
  grid.outputs.push_back(t_end);
  return grid;
}

namespace {

using Clock = std::chrono::steady_clock;

constexpr double kCollapsedStep = 1e-12;  // a step size relative to |t|: a few thousand ulps

/// One run of the integration loop: the time grid, where the integrator stands, the budgets
/// spent, the outputs so far and the integrand's integrals.
class StepLoop {
 public:
  StepLoop(Stepper& stepper, const IntegratorOptions& options, SolveSummary& summary)
      : stepper_(stepper),
        options_(options),
        summary_(summary),
        start_(Clock::now()),
        grid_(make_time_grid(options.output_times, options.breakpoints)),
        t0_(grid_.outputs.front()),
        t_end_(grid_.outputs.back()),
        done_(Eigen::VectorXd::Zero(options.integrand ? options.integrand_size : 0)),
        from_(t0_),
        reached_(t0_),
        next_progress_(options.progress_after_seconds) {}

  /// From (y0, yp0) at t0 to t_end, one internal step at a time: every step is seen exactly
  /// (drift, μ), outputs are interpolated. Throws IntegrationError.
  void run(const Eigen::VectorXd& y0, const Eigen::VectorXd& yp0) {
    const auto& times = grid_.outputs;
    record(t0_, y0, yp0, done_);
    // A load step within roundoff after t0 switches on before the first step.
    if (grid_.initial_stop) restart_at(*grid_.initial_stop);
    stepper_.set_stop_time(stop_ahead());
    while (k_ < times.size()) {
      // Never a first output within roundoff of where the integrator stands (SUNDIALS refuses
      // it after a (re)initialisation; the grid keeps outputs and stops apart, this is the guard).
      const double tout = times[k_] - reached_ > grid_.tolerance ? times[k_] : stop_ahead();
      const double t = stepper_.step(tout);
      ++total_steps_;
      check_stall(t - reached_, t);
      reached_ = t;  // the step succeeded: a budget that ends the run here ends it at t
      check_step_budgets(t);
      const auto& stops = grid_.stops;
      const bool at_stop = next_stop_ < stops.size() && t >= stops[next_stop_];
      if (options_.on_step && !at_stop) options_.on_step(t, stepper_.y());
      record_outputs_in_step(t, at_stop);
      if (done_.size() > 0) done_ += integral_to(t);
      from_ = t;
      if (at_stop) {
        const double b = stops[next_stop_++];
        restart_at(b);
        // A step that ends at a stop is seen as the restart leaves it: a drive's table changes
        // its rate there, and the state before the jump met the rows at the old rate (a drift
        // of the jump's size, where the run holds them).
        if (options_.on_step) options_.on_step(b, stepper_.y());
        steps_since_output_ = 0;
      } else if (stepper_.wants_restart(t)) {
        // The state is re-expressed, the motion goes on: no load switches, no work jumps.
        stepper_.restart(t);
        stepper_.set_stop_time(stop_ahead());
      }
      check_interrupt();
      if (const int signal = stop_requested(); signal != 0) {
        std::ostringstream s;
        s << "stopped by " << signal_name(signal) << " at t = " << t;
        throw IntegrationError(FailureKind::interrupted, s.str());
      }
      report_progress_and_check_wall_time(t);
    }
  }

  /// Keeps what was computed in the failure `e`: the rows so far, where the run stopped and its
  /// last step; and refines the integrator's word by the facts (refine_failure_kind).
  void keep_partial(IntegrationError& e) {
    e.in_loop = true;
    e.t_reached = reached_;
    e.t0 = t0_;
    e.t_end = t_end_;
    e.steps = total_steps_;
    e.elapsed_seconds = elapsed();
    try {
      stepper_.fill_summary(summary_);
      e.last_step = summary_.last_step;
    } catch (const IntegrationError&) {
      // The counters are lost with the integrator's state; the failure itself is what matters.
    }
    refine_failure_kind(e);
    e.raw_partial = std::make_shared<const RawTrajectory>(std::move(out_));
  }

  [[nodiscard]] RawTrajectory take() { return std::move(out_); }

 private:
  /// A failure before any step is a failure to start; failures (or a stall) with the last step
  /// at roundoff of the time reached are a collapse. A residual that stays non-finite
  /// (IDA_REP_RES_ERR) at a step cut to roundoff is the collapse's consequence
  /// (y' = cj (y − y_pred) overflows), not a blow-up of the solution.
  void refine_failure_kind(IntegrationError& e) const {
    const bool residual_failure = e.kind == FailureKind::residual_non_finite;
    const bool solver_failure =
        e.kind == FailureKind::convergence || e.kind == FailureKind::error_test ||
        e.kind == FailureKind::linear_solver || e.kind == FailureKind::unknown;
    if (solver_failure && total_steps_ == 0) {
      e.kind = FailureKind::first_step;
    } else if ((e.kind == FailureKind::convergence || e.kind == FailureKind::error_test ||
                e.kind == FailureKind::steps_per_output || residual_failure) &&
               total_steps_ > 0 &&
               std::abs(e.last_step) <= kCollapsedStep * std::abs(e.t_reached)) {
      e.kind = FailureKind::step_size_collapsed;
    }
  }

  /// ∫ from `from_` (the start of the last internal step) to b over the step's interpolant:
  /// 3-point Gauss-Legendre.
  Eigen::VectorXd integral_to(double b) {
    Eigen::VectorXd sum = Eigen::VectorXd::Zero(done_.size());
    if (done_.size() == 0 || b <= from_) return sum;
    static constexpr double kNode = 0.7745966692414833770;  // sqrt(3/5)
    static constexpr std::array<std::pair<double, double>, 3> kRule{
        {{-kNode, 5.0 / 9.0}, {0.0, 8.0 / 9.0}, {kNode, 5.0 / 9.0}}};
    const double mid = 0.5 * (from_ + b), half = 0.5 * (b - from_);
    for (const auto& [x, w] : kRule) {
      const double tq = mid + half * x;
      stepper_.interpolate(tq, yq_, ypq_);
      sum += (half * w) * options_.integrand(tq, yq_, ypq_);
    }
    return sum;
  }

  void record(double t, const Eigen::VectorXd& y, const Eigen::VectorXd& yp,
              const Eigen::VectorXd& integrals) {
    if (!y.allFinite() || !yp.allFinite()) {
      std::ostringstream s;
      s << "the solution became non-finite (NaN or inf) at t = " << t;
      throw IntegrationError(FailureKind::non_finite, s.str());
    }
    if (!integrals.allFinite()) {
      // The solution is finite; what it feeds (the energy balance's work integrals) is not.
      std::ostringstream s;
      s << "the energy balance's integrals (the work of the loads, constraints and damping) "
           "overflow the double range at t = "
        << t << ", while the solution is finite: the energy quantity cannot be reported "
        << "for this run (leave it out of [output] quantities)";
      throw IntegrationError(FailureKind::non_finite, s.str());
    }
    if (options_.on_output) {
      options_.on_output(t, y, yp, integrals);
    } else {
      out_.y.push_back(y);
      out_.yp.push_back(yp);
      if (integrals.size() > 0) out_.integrals.push_back(integrals);
    }
    // After the row is taken: a sink that fails on it (a state the problem cannot complete)
    // leaves the times and the rows of a partial result the same length.
    out_.t.push_back(t);
  }

  /// Outputs inside the step that ended at t; one at a load step's time waits for the state
  /// after the step.
  void record_outputs_in_step(double t, bool at_stop) {
    const auto& times = grid_.outputs;
    while (k_ < times.size() && (times[k_] < t || (times[k_] == t && !at_stop))) {
      const Eigen::VectorXd integrals = done_ + integral_to(times[k_]);
      if (times[k_] == t) {
        record(t, stepper_.y(), stepper_.yp(), integrals);
      } else {
        stepper_.interpolate(times[k_], yo_, ypo_);
        record(times[k_], yo_, ypo_, integrals);
      }
      ++k_;
      steps_since_output_ = 0;
    }
  }

  /// Restarts at a load step's time: the state after it, and the outputs merged into it.
  void restart_at(double b) {
    const auto& times = grid_.outputs;
    const Eigen::VectorXd before = options_.integrand_jump ? stepper_.y() : Eigen::VectorXd();
    stepper_.restart(b);
    if (options_.integrand_jump && done_.size() > 0) {
      done_ += options_.integrand_jump(b, before, stepper_.y());
    }
    stepper_.set_stop_time(stop_ahead());
    ++summary_.restarts;
    reached_ = b;
    from_ = b;
    while (k_ < times.size() && times[k_] <= b) {
      record(times[k_], stepper_.y(), stepper_.yp(), done_);
      ++k_;
    }
  }

  [[nodiscard]] double stop_ahead() const {
    return next_stop_ < grid_.stops.size() ? grid_.stops[next_stop_] : t_end_;
  }

  /// A step size that stays at roundoff of t can never reach the next output: steps below
  /// kCollapsedStep |t|, kStalledSteps of them in a row (a cut at a discontinuity grows back in
  /// a few dozen), end the run as a collapse at once, not after the budget of steps per output
  /// (100,000 by default, minutes of a run that had already stopped advancing).
  void check_stall(double advanced, double t) {
    constexpr std::size_t kStalledSteps = 1000;
    steps_at_roundoff_ =
        std::abs(advanced) <= kCollapsedStep * std::abs(t) ? steps_at_roundoff_ + 1 : 0;
    if (steps_at_roundoff_ < kStalledSteps) return;
    std::ostringstream s;
    s << "the step size stayed below " << kCollapsedStep << " |t| for " << kStalledSteps
      << " steps in a row (at t = " << t << "): the run cannot advance";
    throw IntegrationError(FailureKind::step_size_collapsed, s.str());
  }

  /// The budgets of steps between two outputs and in all, after a step that ended at t.
  void check_step_budgets(double t) {
    if (++steps_since_output_ > options_.max_steps_per_output) {
      std::ostringstream s;
      s << "took " << options_.max_steps_per_output << " steps without reaching the output time "
        << grid_.outputs[k_] << " (at t = " << t
        << "; the budget of steps between two outputs, [solve] max_steps_per_output)";
      throw IntegrationError(FailureKind::steps_per_output, s.str());
    }
    if (options_.max_steps > 0 && total_steps_ > options_.max_steps) {
      std::ostringstream s;
      s << "took more than " << options_.max_steps << " steps in all (at t = " << t
        << ", the step budget of this run)";
      throw IntegrationError(FailureKind::step_budget, s.str());
    }
  }

  /// The progress callback when it is due, and the wall-time budget, after a step that ended at t.
  void report_progress_and_check_wall_time(double t) {
    if (!(options_.max_wall_seconds > 0.0 || options_.on_progress)) return;
    const std::size_t outputs = grid_.outputs.size();
    const double seconds = elapsed();
    if (options_.on_progress && seconds >= next_progress_ && k_ < outputs) {
      options_.on_progress({t0_, reached_, t_end_, total_steps_, seconds});
      next_progress_ = seconds + options_.progress_every_seconds;
    }
    if (options_.max_wall_seconds > 0.0 && seconds > options_.max_wall_seconds && k_ < outputs) {
      std::ostringstream s;
      s << "ran longer than " << options_.max_wall_seconds << " s of wall time (at t = " << t
        << ", the wall-time budget of this run)";
      throw IntegrationError(FailureKind::wall_time_budget, s.str());
    }
  }

  [[nodiscard]] double elapsed() const {
    return std::chrono::duration<double>(Clock::now() - start_).count();
  }

  Stepper& stepper_;
  const IntegratorOptions& options_;
  SolveSummary& summary_;
  const Clock::time_point start_;
  const TimeGrid grid_;
  const double t0_, t_end_;
  RawTrajectory out_;
  /// The integrand's integrals from t0 to `from_`, the start of the current internal step.
  Eigen::VectorXd done_;
  double from_;
  Eigen::VectorXd yq_, ypq_, yo_, ypo_;  // interpolated states (quadrature nodes, outputs)
  std::size_t next_stop_ = 0;
  std::size_t k_ = 1;  // next output
  long steps_since_output_ = 0, total_steps_ = 0;
  std::size_t steps_at_roundoff_ = 0;  // consecutive steps below kCollapsedStep |t|
  double reached_;
  double next_progress_;
};

}  // namespace

RawTrajectory drive(Stepper& stepper, const Eigen::VectorXd& y0, const Eigen::VectorXd& yp0,
                    const IntegratorOptions& options, SolveSummary& summary) {
  StepLoop loop(stepper, options, summary);
  try {
    loop.run(y0, yp0);
  } catch (IntegrationError& e) {
    loop.keep_partial(e);
    throw;
  } catch (const RecoverableError& e) {
    // An evaluation the loop makes itself, outside the integrator's retries (an output's y', an
    // observer's state, a problem's restart test), that the problem could not complete: no step
    // is left to cut, so the run ends here, as data, with the rows before it.
    IntegrationError failure(FailureKind::convergence, e.what());
    loop.keep_partial(failure);
    throw failure;
  }
  stepper.fill_summary(summary);
  return loop.take();
}

}  // namespace condyn
