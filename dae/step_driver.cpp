#include "dae/step_driver.hpp"

#include <sstream>

namespace condyn {

RawTrajectory drive(Stepper& stepper, const Eigen::VectorXd& y0, const Eigen::VectorXd& yp0,
                    const IntegratorOptions& options, SolveSummary& summary) {
  const auto& times = options.output_times;
  const double t0 = times.front();
  RawTrajectory out;
  auto record = [&](double t, const Eigen::VectorXd& y, const Eigen::VectorXd& yp) {
    if (!y.allFinite() || !yp.allFinite()) {
      std::ostringstream s;
      s << "the solution became non-finite (NaN or inf) at t = " << t;
      throw IntegrationError(s.str());
    }
    out.t.push_back(t);
    out.y.push_back(y);
    out.yp.push_back(yp);
  };
  record(t0, y0, yp0);

  // Load steps strictly inside (t0, t_end); each ends a segment.
  std::vector<double> stops;
  for (double b : options.breakpoints) {
    if (b > t0 && b < times.back()) stops.push_back(b);
  }
  std::size_t next_stop = 0;
  auto stop_ahead = [&] { return next_stop < stops.size() ? stops[next_stop] : times.back(); };
  stepper.set_stop_time(stop_ahead());

  // One internal step at a time: every step is seen exactly (drift, μ), outputs are interpolated.
  std::size_t k = 1;  // next output
  long steps_since_output = 0, total_steps = 0;
  double reached = t0;
  Eigen::VectorXd yo, ypo;
  try {
    while (k < times.size()) {
      const double t = stepper.step(times[k]);
      if (++steps_since_output > options.max_steps_per_output) {
        std::ostringstream s;
        s << "took " << options.max_steps_per_output << " steps without reaching the output time "
          << times[k] << " (at t = " << t << ")";
        throw IntegrationError(s.str());
      }
      if (options.max_steps > 0 && ++total_steps > options.max_steps) {
        std::ostringstream s;
        s << "took more than " << options.max_steps << " steps in all (at t = " << t
          << ", the step budget of this run)";
        throw IntegrationError(s.str());
      }
      reached = t;
      if (options.on_step) options.on_step(t, stepper.y());
      const bool at_stop = next_stop < stops.size() && t >= stops[next_stop];
      // Outputs inside the step; one at a load step's time waits for the state after the step.
      while (k < times.size() && (times[k] < t || (times[k] == t && !at_stop))) {
        if (times[k] == t) {
          record(t, stepper.y(), stepper.yp());
        } else {
          stepper.interpolate(times[k], yo, ypo);
          record(times[k], yo, ypo);
        }
        ++k;
        steps_since_output = 0;
      }
      if (at_stop) {
        const double b = stops[next_stop++];
        stepper.restart(b);
        stepper.set_stop_time(stop_ahead());
        ++summary.restarts;
        while (k < times.size() && times[k] <= b) {
          record(times[k], stepper.y(), stepper.yp());
          ++k;
        }
      }
    }
  } catch (IntegrationError& e) {
    // Keep what was computed: the rows so far, where the run stopped and its last step.
    e.in_loop = true;
    e.t_reached = reached;
    try {
      stepper.fill_summary(summary);
      e.last_step = summary.last_step;
    } catch (const IntegrationError&) {
      // The counters are lost with the integrator's state; the failure itself is what matters.
    }
    e.raw_partial = std::make_shared<const RawTrajectory>(std::move(out));
    throw;
  }
  stepper.fill_summary(summary);
  return out;
}

}  // namespace condyn
