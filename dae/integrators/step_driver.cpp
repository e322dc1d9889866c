#include "dae/integrators/step_driver.hpp"

#include "dae/interface/interrupt.hpp"

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

RawTrajectory drive(Stepper& stepper, const Eigen::VectorXd& y0, const Eigen::VectorXd& yp0,
                    const IntegratorOptions& options, SolveSummary& summary) {
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  const TimeGrid grid = make_time_grid(options.output_times, options.breakpoints);
  const auto& times = grid.outputs;
  const auto& stops = grid.stops;
  const double t0 = times.front(), t_end = times.back();
  RawTrajectory out;
  // The integrand's integrals from t0 to `from`, the start of the current internal step.
  Eigen::VectorXd done = Eigen::VectorXd::Zero(options.integrand ? options.integrand_size : 0);
  double from = t0;
  Eigen::VectorXd yq, ypq;
  // ∫ from `from` to b over the last step's interpolant: 3-point Gauss-Legendre.
  auto integral_to = [&](double b) -> Eigen::VectorXd {
    Eigen::VectorXd sum = Eigen::VectorXd::Zero(done.size());
    if (done.size() == 0 || b <= from) return sum;
    static constexpr double kNode = 0.7745966692414833770;  // sqrt(3/5)
    static constexpr std::array<std::pair<double, double>, 3> kRule{
        {{-kNode, 5.0 / 9.0}, {0.0, 8.0 / 9.0}, {kNode, 5.0 / 9.0}}};
    const double mid = 0.5 * (from + b), half = 0.5 * (b - from);
    for (const auto& [x, w] : kRule) {
      const double tq = mid + half * x;
      stepper.interpolate(tq, yq, ypq);
      sum += (half * w) * options.integrand(tq, yq, ypq);
    }
    return sum;
  };
  auto record = [&](double t, const Eigen::VectorXd& y, const Eigen::VectorXd& yp,
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
    out.t.push_back(t);
    if (options.on_output) {
      options.on_output(t, y, yp, integrals);
    } else {
      out.y.push_back(y);
      out.yp.push_back(yp);
      if (integrals.size() > 0) out.integrals.push_back(integrals);
    }
  };
  auto elapsed = [&] { return std::chrono::duration<double>(Clock::now() - start).count(); };

  std::size_t next_stop = 0;
  auto stop_ahead = [&] { return next_stop < stops.size() ? stops[next_stop] : t_end; };
  std::size_t k = 1;  // next output
  long steps_since_output = 0, total_steps = 0;
  double reached = t0;
  double next_progress = options.progress_after_seconds;
  Eigen::VectorXd yo, ypo;
  try {
    record(t0, y0, yp0, done);
    // Restarts at a load step's time: the state after it, and the outputs merged into it.
    auto restart_at = [&](double b) {
      const Eigen::VectorXd before = options.integrand_jump ? stepper.y() : Eigen::VectorXd();
      stepper.restart(b);
      if (options.integrand_jump && done.size() > 0) {
        done += options.integrand_jump(b, before, stepper.y());
      }
      stepper.set_stop_time(stop_ahead());
      ++summary.restarts;
      reached = b;
      from = b;
      while (k < times.size() && times[k] <= b) {
        record(times[k], stepper.y(), stepper.yp(), done);
        ++k;
      }
    };
    // A load step within roundoff after t0 switches on before the first step.
    if (grid.initial_stop) restart_at(*grid.initial_stop);
    stepper.set_stop_time(stop_ahead());

    // One internal step at a time: every step is seen exactly (drift, μ), outputs are interpolated.
    while (k < times.size()) {
      // Never a first output within roundoff of where the integrator stands (SUNDIALS refuses
      // it after a (re)initialisation; the grid keeps outputs and stops apart, this is the guard).
      const double tout = times[k] - reached > grid.tolerance ? times[k] : stop_ahead();
      const double t = stepper.step(tout);
      ++total_steps;
      reached = t;  // the step succeeded: a budget that ends the run here ends it at t
      if (++steps_since_output > options.max_steps_per_output) {
        std::ostringstream s;
        s << "took " << options.max_steps_per_output << " steps without reaching the output time "
          << times[k] << " (at t = " << t
          << "; the budget of steps between two outputs, [solve] max_steps_per_output)";
        throw IntegrationError(FailureKind::steps_per_output, s.str());
      }
      if (options.max_steps > 0 && total_steps > options.max_steps) {
        std::ostringstream s;
        s << "took more than " << options.max_steps << " steps in all (at t = " << t
          << ", the step budget of this run)";
        throw IntegrationError(FailureKind::step_budget, s.str());
      }
      if (options.on_step) options.on_step(t, stepper.y());
      const bool at_stop = next_stop < stops.size() && t >= stops[next_stop];
      // Outputs inside the step; one at a load step's time waits for the state after the step.
      while (k < times.size() && (times[k] < t || (times[k] == t && !at_stop))) {
        const Eigen::VectorXd integrals = done + integral_to(times[k]);
        if (times[k] == t) {
          record(t, stepper.y(), stepper.yp(), integrals);
        } else {
          stepper.interpolate(times[k], yo, ypo);
          record(times[k], yo, ypo, integrals);
        }
        ++k;
        steps_since_output = 0;
      }
      if (done.size() > 0) done += integral_to(t);
      from = t;
      if (at_stop) {
        restart_at(stops[next_stop++]);
        steps_since_output = 0;
      }
      check_interrupt();
      if (const int signal = stop_requested(); signal != 0) {
        std::ostringstream s;
        s << "stopped by " << signal_name(signal) << " at t = " << t;
        throw IntegrationError(FailureKind::interrupted, s.str());
      }
      if (options.max_wall_seconds > 0.0 || options.on_progress) {
        const double seconds = elapsed();
        if (options.on_progress && seconds >= next_progress && k < times.size()) {
          options.on_progress({t0, reached, t_end, total_steps, seconds});
          next_progress = seconds + options.progress_every_seconds;
        }
        if (options.max_wall_seconds > 0.0 && seconds > options.max_wall_seconds &&
            k < times.size()) {
          std::ostringstream s;
          s << "ran longer than " << options.max_wall_seconds << " s of wall time (at t = " << t
            << ", the wall-time budget of this run)";
          throw IntegrationError(FailureKind::wall_time_budget, s.str());
        }
      }
    }
  } catch (IntegrationError& e) {
    // Keep what was computed: the rows so far, where the run stopped and its last step.
    e.in_loop = true;
    e.t_reached = reached;
    e.t0 = t0;
    e.t_end = t_end;
    e.steps = total_steps;
    e.elapsed_seconds = elapsed();
    try {
      stepper.fill_summary(summary);
      e.last_step = summary.last_step;
    } catch (const IntegrationError&) {
      // The counters are lost with the integrator's state; the failure itself is what matters.
    }
    // The facts refine the integrator's word: a failure before any step is a failure to start;
    // failures (or a stall) with the last step at roundoff of the time reached are a collapse.
    // A residual that stays non-finite (IDA_REP_RES_ERR) at a step cut to roundoff is the
    // collapse's consequence (y' = cj (y − y_pred) overflows), not a blow-up of the solution.
    const bool residual_failure = e.kind == FailureKind::residual_non_finite;
    const bool solver_failure =
        e.kind == FailureKind::convergence || e.kind == FailureKind::error_test ||
        e.kind == FailureKind::linear_solver || e.kind == FailureKind::unknown;
    constexpr double kCollapsedStep = 1e-12;  // relative to |t_reached|: a few thousand ulps
    if (solver_failure && total_steps == 0) {
      e.kind = FailureKind::first_step;
    } else if ((e.kind == FailureKind::convergence || e.kind == FailureKind::error_test ||
                e.kind == FailureKind::steps_per_output || residual_failure) &&
               total_steps > 0 && std::abs(e.last_step) <= kCollapsedStep * std::abs(e.t_reached)) {
      e.kind = FailureKind::step_size_collapsed;
    }
    e.raw_partial = std::make_shared<const RawTrajectory>(std::move(out));
    throw;
  }
  stepper.fill_summary(summary);
  return out;
}

}  // namespace condyn
