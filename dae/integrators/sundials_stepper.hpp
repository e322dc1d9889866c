#pragma once
/// The part of a SUNDIALS stepper that IDA (the DAE formulations) and CVODE (the projected ODE)
/// share: what the C callbacks report back, return codes turned into IntegrationErrors with
/// their failure kind, one step's failure message, interpolation, and the counters summed across
/// re-initialisations. Each integrator supplies its C functions (Api) and its counters.

#include <exception>
#include <string>

#include "dae/integrators/step_driver.hpp"
#include "dae/integrators/sundials_raii.hpp"
#include "dae/interface/recoverable_error.hpp"

namespace condyn::sundials {

/// What the C callbacks report back to the stepper; exceptions never cross C frames.
struct CallbackReport {
  std::exception_ptr error;  ///< a fatal exception from a callback, rethrown after the call
  std::string recoverable;   ///< the last RecoverableError (the integrator then cut its step)
  std::string message;       ///< the integrator's own last error message
};

/// Runs a callback's body and returns what SUNDIALS expects: the body's 0 or +1; +1 for a
/// RecoverableError (noted in the report: the integrator retries with a smaller step); −1 for
/// any other exception, parked in the report and rethrown by the stepper after the call.
template <class Body>
int guarded(CallbackReport& report, const Body& body) noexcept {
  try {
    return body();
  } catch (const RecoverableError& e) {
    report.recoverable = e.what();
    return 1;
  } catch (...) {
    report.error = std::current_exception();
    return -1;
  }
}

/// The error handler of both integrators: keeps the message in the CallbackReport passed as
/// the handler's data.
void record_message(int code, const char* module, const char* function, char* msg, void* report);

/// One integrator's C API as the skeleton calls it (IDA and CVODE share these signatures).
struct Api {
  const char* step_call;  ///< "IDASolve" or "CVode", for messages
  char* (*flag_name)(long int);
  int (*current_time)(void*, sunrealtype*);
  int (*last_step)(void*, sunrealtype*);
  int (*dky)(void*, sunrealtype, int, N_Vector);
  int (*last_order)(void*, int*);
  FailureKind (*failure_kind)(int);
};

/// What an integrator counts; `evaluations` are residual (IDA) or right-hand side (CVODE)
/// evaluations, `projections` CVODE's projections onto the constraints.
struct Counters {
  long steps = 0, evaluations = 0, jacobians = 0, newton = 0, newton_failures = 0, error_tests = 0,
       projections = 0;
};

class SundialsStepper : public Stepper {
 public:
  /// y and y' at t inside the last step, from the integrator's interpolating polynomial.
  void interpolate(double t, Eigen::VectorXd& y, Eigen::VectorXd& yp) override;
  /// The counters summed over every segment, and the last step size.
  void fill_summary(SolveSummary& summary) override;

 protected:
  explicit SundialsStepper(const Api& api) : api_(api) {}
  /// The integrator's memory and a work vector of the state's size, once created.
  void attach(void* mem, N_Vector work) {
    mem_ = mem;
    work_ = work;
  }
  /// Throws an IntegrationError naming `call`, the flag and its kind, when flag < 0.
  void check(int flag, const char* call) const;
  /// After one step call: rethrows a callback's exception; for flag < 0 throws an
  /// IntegrationError with the time and last step reached and what the integrator and the
  /// equations last said.
  void after_step(int flag) const;
  /// Adds what the integrator counted since the last call to the totals. Differencing against a
  /// baseline keeps the totals right whether or not re-initialisation resets the counters.
  void collect();
  /// The counters as they stand (a re-initialisation calls this after reinit: the new baseline).
  void rebase() { baseline_ = read_counters(); }
  [[nodiscard]] virtual Counters read_counters() const = 0;
  /// Words for the summary's notes (CVODE: its projections); none by default.
  [[nodiscard]] virtual std::string notes(const Counters& /*totals*/) const { return {}; }

  CallbackReport report_;

 private:
  const Api& api_;
  void* mem_ = nullptr;
  N_Vector work_ = nullptr;
  Counters totals_, baseline_;
  double last_step_ = 0.0;
  mutable int max_order_used_ = 0;  ///< the highest BDF order of any step
};

}  // namespace condyn::sundials
