#include "dae/cvode_integrator.hpp"

#include "dae/recoverable_error.hpp"

#include "dae/sundials_raii.hpp"

#include <cvode/cvode.h>
#include <cvode/cvode_proj.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include <chrono>
#include <exception>
#include <memory>
#include <sstream>

namespace condyn {

namespace {

using sundials::ContextPtr;
using sundials::MatrixPtr;
using sundials::SolverPtr;
using sundials::VectorPtr;
using sundials::view;

// The integrator memory's owner; the others come from dae/sundials_raii.hpp.
struct CvodeDeleter {
  void operator()(void* mem) const { CVodeFree(&mem); }
};
using CvodePtr = std::unique_ptr<void, CvodeDeleter>;

/// What the C callbacks need; exceptions are parked here, never propagated through CVODE.
struct CallbackData {
  const OdeProblem* problem = nullptr;
  double step_reference = 0.0;
  std::exception_ptr error;
  std::string recoverable;  ///< the last RecoverableError a callback met (CVODE then cut its step)
  std::string message;
};

int rhs_trampoline(double t, N_Vector y, N_Vector ydot, void* user) {
  auto* data = static_cast<CallbackData*>(user);
  try {
    auto out = view(ydot);
    data->problem->rhs(t, data->step_reference, view(y), out);
    return out.allFinite() ? 0 : 1;  // recoverable: CVODE retries with a smaller step
  } catch (const RecoverableError& e) {
    data->recoverable = e.what();
    return 1;
  } catch (...) {
    data->error = std::current_exception();
    return -1;
  }
}

int projection_trampoline(double t, N_Vector y, N_Vector corr, double /*eps*/, N_Vector err,
                          void* user) {
  auto* data = static_cast<CallbackData*>(user);
  try {
    auto c = view(corr);
    if (!data->problem->project(t, view(y), c)) return 1;  // recoverable: smaller step
    if (err != nullptr) {
      auto e = view(err);
      data->problem->project_error(e);
    }
    return c.allFinite() ? 0 : 1;
  } catch (const RecoverableError& e) {
    data->recoverable = e.what();
    return 1;
  } catch (...) {
    data->error = std::current_exception();
    return -1;
  }
}

/// What a CVODE return flag says happened (by its code, never its text).
FailureKind failure_kind(int flag) {
  switch (flag) {
    case CV_TOO_MUCH_WORK:
      return FailureKind::steps_per_output;
    case CV_TOO_MUCH_ACC:
      return FailureKind::tolerance_too_tight;
    case CV_ERR_FAILURE:
      return FailureKind::error_test;
    case CV_CONV_FAILURE:
    case CV_NLS_FAIL:
    case CV_NLS_SETUP_FAIL:
    case CV_PROJFUNC_FAIL:
    case CV_REPTD_PROJFUNC_ERR:
      return FailureKind::convergence;
    case CV_LINIT_FAIL:
    case CV_LSETUP_FAIL:
    case CV_LSOLVE_FAIL:
      return FailureKind::linear_solver;
    case CV_FIRST_RHSFUNC_ERR:  // the right-hand side stayed non-finite
    case CV_REPTD_RHSFUNC_ERR:
      return FailureKind::residual_non_finite;
    case CV_ILL_INPUT:
    case CV_TOO_CLOSE:
    case CV_BAD_T:
    case CV_BAD_K:
    case CV_BAD_DKY:
      return FailureKind::bad_input;
    default:
      return FailureKind::unknown;
  }
}

void error_handler(int /*code*/, const char* /*module*/, const char* function, char* msg,
                   void* user) {
  static_cast<CallbackData*>(user)->message = std::string(function) + ": " + msg;
}

class Cvode final : public Stepper {
 public:
  Cvode(const OdeProblem& problem, const Eigen::VectorXd& y0, double t0,
        const IntegratorOptions& options)
      : n_(problem.size()) {
    data_.problem = &problem;
    data_.step_reference = t0;
    SUNContext raw = nullptr;
    if (SUNContext_Create(nullptr, &raw) != 0) throw IntegrationError("SUNContext_Create failed");
    ctx_.reset(raw);
    y_.reset(N_VNew_Serial(n_, ctx_.get()));
    work_.reset(N_VNew_Serial(n_, ctx_.get()));
    if (!y_ || !work_) throw IntegrationError("N_VNew_Serial failed (out of memory?)");
    view(y_.get()) = y0;
    matrix_.reset(SUNDenseMatrix(n_, n_, ctx_.get()));
    if (matrix_) solver_.reset(SUNLinSol_Dense(y_.get(), matrix_.get(), ctx_.get()));
    if (!matrix_ || !solver_) throw IntegrationError("could not create the dense linear solver");
    mem_.reset(CVodeCreate(CV_BDF, ctx_.get()));
    if (!mem_) throw IntegrationError("CVodeCreate failed");
    check(CVodeSetErrHandlerFn(mem_.get(), error_handler, &data_), "CVodeSetErrHandlerFn");
    check(CVodeInit(mem_.get(), rhs_trampoline, t0, y_.get()), "CVodeInit");
    check(CVodeSetUserData(mem_.get(), &data_), "CVodeSetUserData");
    view(work_.get()) = options.atol_vector(problem.unknown_kinds(), static_cast<int>(n_));
    check(CVodeSVtolerances(mem_.get(), options.rtol, work_.get()),
          "CVodeSVtolerances");  // copies the vector
    check(CVodeSetLinearSolver(mem_.get(), solver_.get(), matrix_.get()), "CVodeSetLinearSolver");
    if (problem.has_projection()) {
      check(CVodeSetProjFn(mem_.get(), projection_trampoline), "CVodeSetProjFn");
      check(CVodeSetProjErrEst(mem_.get(), SUNTRUE), "CVodeSetProjErrEst");
    }
  }

  double step(double tout) override {
    double tret = 0.0;
    const int flag = CVode(mem_.get(), tout, y_.get(), &tret, CV_ONE_STEP);
    if (data_.error) std::rethrow_exception(data_.error);
    if (flag < 0) {
      double tcur = 0.0, hlast = 0.0;
      CVodeGetCurrentTime(mem_.get(), &tcur);
      CVodeGetLastStep(mem_.get(), &hlast);
      std::ostringstream s;
      s << "CVode failed with " << sundials::flag_name(CVodeGetReturnFlagName, flag)
        << " at t = " << tcur << " (last step " << hlast << ")";
      if (!data_.message.empty()) s << ": " << data_.message;
      if (!data_.recoverable.empty())
        s << " (the equations' last complaint: " << data_.recoverable << ")";
      throw IntegrationError(failure_kind(flag), s.str());
    }
    return tret;
  }

  void interpolate(double t, Eigen::VectorXd& y, Eigen::VectorXd& yp) override {
    check(CVodeGetDky(mem_.get(), t, 0, work_.get()), "CVodeGetDky");
    y = view(work_.get());
    check(CVodeGetDky(mem_.get(), t, 1, work_.get()), "CVodeGetDky");
    yp = view(work_.get());
  }
  [[nodiscard]] Eigen::VectorXd y() override { return view(y_.get()); }
  [[nodiscard]] Eigen::VectorXd yp() override {
    double t = 0.0;
    check(CVodeGetCurrentTime(mem_.get(), &t), "CVodeGetCurrentTime");
    Eigen::VectorXd out(n_);
    data_.problem->rhs(t, data_.step_reference, view(y_.get()), out);
    return out;
  }
  void restart(double t) override {
    collect();  // CVodeReInit may reset the counters: keep what this segment did
    data_.step_reference = t;
    check(CVodeReInit(mem_.get(), t, y_.get()), "CVodeReInit");
    baseline_ = read_counters();
  }
  void set_stop_time(double t) override {
    check(CVodeSetStopTime(mem_.get(), t), "CVodeSetStopTime");
  }
  void fill_summary(SolveSummary& summary) override {
    collect();
    summary.steps = totals_.steps;
    summary.residual_evals = totals_.rhs;
    summary.jacobian_evals = totals_.jac;
    summary.newton_iterations = totals_.newton;
    summary.newton_failures = totals_.newton_failures;
    summary.error_test_failures = totals_.error_tests;
    double h = 0.0;
    check(CVodeGetLastStep(mem_.get(), &h), "CVodeGetLastStep");
    summary.last_step = h;
    summary.notes = std::to_string(totals_.projections) + " projections onto the constraints";
  }

 private:
  struct Counters {
    long steps = 0, rhs = 0, jac = 0, newton = 0, newton_failures = 0, error_tests = 0,
         projections = 0;
  };
  [[nodiscard]] Counters read_counters() const {
    Counters c;
    check(CVodeGetNumSteps(mem_.get(), &c.steps), "CVodeGetNumSteps");
    check(CVodeGetNumRhsEvals(mem_.get(), &c.rhs), "CVodeGetNumRhsEvals");
    check(CVodeGetNumJacEvals(mem_.get(), &c.jac), "CVodeGetNumJacEvals");
    check(CVodeGetNumNonlinSolvIters(mem_.get(), &c.newton), "CVodeGetNumNonlinSolvIters");
    check(CVodeGetNumNonlinSolvConvFails(mem_.get(), &c.newton_failures),
          "CVodeGetNumNonlinSolvConvFails");
    check(CVodeGetNumErrTestFails(mem_.get(), &c.error_tests), "CVodeGetNumErrTestFails");
    if (data_.problem->has_projection()) {
      check(CVodeGetNumProjEvals(mem_.get(), &c.projections), "CVodeGetNumProjEvals");
    }
    return c;
  }
  void collect() {
    const Counters now = read_counters();
    totals_.steps += now.steps - baseline_.steps;
    totals_.rhs += now.rhs - baseline_.rhs;
    totals_.jac += now.jac - baseline_.jac;
    totals_.newton += now.newton - baseline_.newton;
    totals_.newton_failures += now.newton_failures - baseline_.newton_failures;
    totals_.error_tests += now.error_tests - baseline_.error_tests;
    totals_.projections += now.projections - baseline_.projections;
    baseline_ = now;
  }
  void check(int flag, const char* call) const {
    if (flag < 0) {
      throw IntegrationError(failure_kind(flag),
                             std::string(call) + " failed with " +
                                 sundials::flag_name(CVodeGetReturnFlagName, flag) +
                                 (data_.message.empty() ? "" : ": " + data_.message));
    }
  }

  sunindextype n_;
  CallbackData data_;
  Counters totals_, baseline_;
  // Declared in creation order: destroyed in reverse (CVODE memory first, context last).
  ContextPtr ctx_;
  VectorPtr y_, work_;
  MatrixPtr matrix_;
  SolverPtr solver_;
  CvodePtr mem_;
};

}  // namespace

RawTrajectory integrate_ode(const OdeProblem& problem, const Eigen::VectorXd& y0,
                            const IntegratorOptions& options, SolveSummary& summary) {
  options.validate();
  if (y0.size() != problem.size()) throw std::invalid_argument("integrator: y0 has the wrong size");
  const auto start = std::chrono::steady_clock::now();
  const double t0 = options.output_times.front();
  Cvode cvode(problem, y0, t0, options);
  Eigen::VectorXd yp0(problem.size());
  problem.rhs(t0, t0, y0, yp0);
  RawTrajectory out = drive(cvode, y0, yp0, options, summary);
  summary.unknowns = problem.size();
  summary.jacobian_nonzeros = problem.size() * problem.size();  // dense
  summary.termination = "reached t = " + std::to_string(options.output_times.back());
  summary.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace condyn
