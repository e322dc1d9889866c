#pragma once
/// The integration loop shared by every SUNDIALS integrator condyn drives (IDA for the DAE
/// formulations, CVODE for the projected ODE): one internal step at a time, so every step is
/// observed exactly; outputs interpolated at the exact output times; load steps crossed with a
/// stop time and a restart from a consistent state.

#include <Eigen/Dense>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "dae/interface/solve_summary.hpp"
#include "models/core/time_roundoff.hpp"

namespace condyn {

/// y and y' at the output times.
struct RawTrajectory {
  std::vector<double> t;
  std::vector<Eigen::VectorXd> y, yp;
  /// IntegratorOptions::integrand integrated from t0 to each output time (empty without one).
  std::vector<Eigen::VectorXd> integrals;
};

/// How a run failed: set where the failure arises (SUNDIALS flags mapped by their codes, the
/// loop's own checks), refined by the loop from the facts (no step taken, step at roundoff).
enum class FailureKind {
  unknown,
  non_finite,           ///< the solution became NaN or inf
  residual_non_finite,  ///< the residual (right-hand side) was NaN, inf or refused at every retry
  step_budget,          ///< IntegratorOptions::max_steps exhausted
  wall_time_budget,     ///< IntegratorOptions::max_wall_seconds exhausted
  steps_per_output,     ///< max_steps_per_output steps without reaching the next output time
  step_size_collapsed,  ///< solver failures or a stall with the last step at roundoff of t
  convergence,          ///< repeated Newton convergence failures
  error_test,           ///< repeated local error-test failures
  tolerance_too_tight,  ///< the tolerances ask for more than double precision holds
  linear_solver,        ///< the iteration matrix could not be factored or solved
  first_step,           ///< a solver failure at the start, before any step was taken
  bad_input,            ///< the integrator refused an input (a time, a tolerance, a size)
  interrupted,          ///< stopped from outside (request_stop: a signal), not by the model
};

/// A few words naming the kind ("step budget exhausted").
[[nodiscard]] const char* to_string(FailureKind kind);

/// The integrator failed (or refused an input). The message names the SUNDIALS call, its flag
/// name, the time reached and the integrator's own explanation. When the failure happens inside
/// the integration loop, the exception also says how far the run got and carries what it had
/// computed: the output rows before the failure (t0 included), raw from the loop. It travels only
/// from the loop to the observed run (dae/run/observed_run.hpp), which turns it into data
/// (SolveResult::failure and the partial trajectory).
class IntegrationError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
  IntegrationError(FailureKind k, const std::string& what) : std::runtime_error(what), kind(k) {}
  FailureKind kind = FailureKind::unknown;
  double t_reached = 0.0;        ///< the last time the integrator reached successfully
  double last_step = 0.0;        ///< the last step size it took (0: none)
  bool in_loop = false;          ///< the fields below and above are set
  long steps = 0;                ///< internal steps the loop saw before the failure
  double elapsed_seconds = 0.0;  ///< wall time of the loop before the failure
  double t0 = 0.0, t_end = 0.0;  ///< the run's start and end
  std::shared_ptr<const RawTrajectory> raw_partial;
};

/// One integrator, as the loop sees it.
class Stepper {
 public:
  virtual ~Stepper() = default;
  /// One internal step, bounded by the stop time; returns the time reached (the stop time exactly
  /// when the step lands on it). `tout` (the next output time) sizes the first step.
  virtual double step(double tout) = 0;
  /// y and y' at t inside the last step.
  virtual void interpolate(double t, Eigen::VectorXd& y, Eigen::VectorXd& yp) = 0;
  [[nodiscard]] virtual Eigen::VectorXd y() = 0;
  [[nodiscard]] virtual Eigen::VectorXd yp() = 0;
  /// Restarts at a load step t: a consistent state for the segment starting at t, then reinit.
  virtual void restart(double t) = 0;
  /// Whether the problem asks for a restart at t, the end of the step just taken, because it
  /// re-expresses its state there (coordinate partitioning's new partition); restart(t) then
  /// changes the state's meaning. Never at a load step's time. No by default.
  [[nodiscard]] virtual bool wants_restart(double /*t*/) { return false; }
  /// SUNDIALS 6.4 cannot clear a stop time and keeps it across re-initialisation, so the loop
  /// always sets one ahead: the next load step, else the end of the run.
  virtual void set_stop_time(double t) = 0;
  /// Adds the integrator's counters to the summary (steps, evaluations, failures, last step).
  virtual void fill_summary(SolveSummary& summary) = 0;
};

/// The times the loop visits, merged so that no two of them lie within roundoff of each other:
/// SUNDIALS refuses a stop time or a first output within its roundoff of where it stands
/// ("tout too close to t0"), and 3 × 0.1 lies one ulp above 0.3. Times closer than `tolerance`
/// are the same time.
struct TimeGrid {
  double tolerance = 0.0;  ///< kTimeMergeUlps ulps of the time scale (time_merge_tolerance)
  /// The output times: t0 first, t_end last and exact, every time within `tolerance` of a load
  /// step replaced by that load step's time, times within `tolerance` of t0, t_end or the time
  /// before them dropped.
  std::vector<double> outputs;
  /// Load steps in (t0 + tolerance, t_end − tolerance), ascending, more than `tolerance` apart; a
  /// cluster of load steps within `tolerance` of one another is its last member (all of them are
  /// on after it).
  std::vector<double> stops;
  /// Load steps within `tolerance` after t0: the loop restarts there before its first step.
  std::optional<double> initial_stop;
};

/// Merges output times (ascending, t0 first, t_end last) and load steps (ascending) into the
/// grid the loop visits.
[[nodiscard]] TimeGrid make_time_grid(const std::vector<double>& output_times,
                                      const std::vector<double>& breakpoints);

/// Runs the loop from the stepper's initialised state at output_times.front() (which is recorded
/// as given: y0, yp0) over make_time_grid(output_times, breakpoints): the rows are at its outputs.
/// Fills the summary's counters, restarts, unknowns-independent fields and wall time is left to
/// the caller. Reports progress through options.on_progress. Throws IntegrationError when more
/// than max_steps_per_output steps pass between two outputs, a budget (max_steps,
/// max_wall_seconds) is exhausted, the solution becomes non-finite or a stop is requested
/// (request_stop: FailureKind::interrupted); throws Interrupted when the interrupt poll asks to
/// stop (dae/interface/interrupt.hpp); every IntegrationError
/// leaving the loop carries its kind, the time reached, the last step, the steps taken and the
/// rows recorded so far.
[[nodiscard]] RawTrajectory drive(Stepper& stepper, const Eigen::VectorXd& y0,
                                  const Eigen::VectorXd& yp0, const IntegratorOptions& options,
                                  SolveSummary& summary);

}  // namespace condyn
