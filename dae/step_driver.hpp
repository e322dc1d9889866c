#pragma once
/// The integration loop shared by every SUNDIALS integrator condyn drives (IDA for the DAE
/// formulations, CVODE for the projected ODE): one internal step at a time, so every step is
/// observed exactly; outputs interpolated at the exact output times; load steps crossed with a
/// stop time and a restart from a consistent state.

#include <Eigen/Dense>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "dae/solve_summary.hpp"

namespace condyn {

/// y and y' at the output times.
struct RawTrajectory {
  std::vector<double> t;
  std::vector<Eigen::VectorXd> y, yp;
};

struct Trajectory;

/// The integrator failed (or refused an input). The message names the SUNDIALS call, its flag
/// name, the time reached and the integrator's own explanation. When the failure happens inside
/// the integration loop, the exception also says how far the run got and carries what it had
/// computed: the output rows before the failure (t0 included), raw from the loop and, once the
/// solve layer has assembled them, as a trajectory.
class IntegrationError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
  double t_reached = 0.0;  ///< the last time the integrator reached successfully
  double last_step = 0.0;  ///< the last step size it took (0: none)
  bool in_loop = false;    ///< the fields below and above are set
  std::shared_ptr<const RawTrajectory> raw_partial;
  std::shared_ptr<const Trajectory> partial;  ///< set by solve(); rows up to t_reached
  std::string scheme;                         ///< set by solve()
  std::string suggestion;                     ///< set by solve(): what to try instead
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
  /// SUNDIALS 6.4 cannot clear a stop time and keeps it across re-initialisation, so the loop
  /// always sets one ahead: the next load step, else the end of the run.
  virtual void set_stop_time(double t) = 0;
  /// Adds the integrator's counters to the summary (steps, evaluations, failures, last step).
  virtual void fill_summary(SolveSummary& summary) = 0;
};

/// Runs the loop from the stepper's initialised state at output_times.front() (which is recorded
/// as given: y0, yp0). Fills the summary's counters, restarts, unknowns-independent fields and wall
/// time is left to the caller. Throws IntegrationError when more than max_steps_per_output steps
/// pass between two outputs or the solution becomes non-finite; every IntegrationError leaving the
/// loop carries the time reached, the last step and the rows recorded so far.
[[nodiscard]] RawTrajectory drive(Stepper& stepper, const Eigen::VectorXd& y0,
                                  const Eigen::VectorXd& yp0, const IntegratorOptions& options,
                                  SolveSummary& summary);

}  // namespace condyn
