#include "dae/integrators/cvode_integrator.hpp"

#include "dae/integrators/newton_linear_solver.hpp"
#include "dae/integrators/no_unknowns.hpp"
#include "dae/integrators/sundials_raii.hpp"
#include "dae/integrators/sundials_stepper.hpp"
#include "dae/integrators/vector_ops.hpp"

#include <cvode/cvode.h>
#include <cvode/cvode_proj.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunlinsol/sunlinsol_spgmr.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunnonlinsol/sunnonlinsol_fixedpoint.h>

#include <exception>
#include <memory>
#include <sstream>

namespace condyn {

namespace {

using sundials::ContextPtr;
using sundials::MatrixPtr;
using sundials::NonlinearSolverPtr;
using sundials::SolverPtr;
using sundials::VectorPtr;
using sundials::view;

// The integrator memory's owner; the others come from dae/integrators/sundials_raii.hpp.
struct CvodeDeleter {
  void operator()(void* mem) const { CVodeFree(&mem); }
};
using CvodePtr = std::unique_ptr<void, CvodeDeleter>;

/// What the C callbacks need; exceptions go to `report`, never through CVODE's C frames.
struct CvodeCallbackData {
  OdeProblem* problem = nullptr;
  sundials::CallbackReport* report = nullptr;
  /// Calls of the projection, never reset: CVODE's own count (CVodeGetNumProjEvals) restarts
  /// at the first step after CVodeReInit, after the segment's baseline was read, so a run with a
  /// load step lost the projections before it.
  long projections = 0;
  double rtol = 0.0;
  Eigen::VectorXd atol;     ///< per component, as CVODE has it
  Eigen::VectorXd settled;  ///< kProjectionSettled (rtol |y_i| + atol_i), per projection
};

/// The fraction of the error test's tolerance at which a projection that no longer shrinks its
/// corrections counts as converged (OdeProblem::project): CVODE's own default for the
/// projection's stopping test (epsProj, 0.1).
constexpr double kProjectionSettled = 0.1;

/// kProjectionSettled (rtol |y_i| + atol_i) at y, into data.settled.
const Eigen::VectorXd& settled_at(CvodeCallbackData& data,
                                  const Eigen::Ref<const Eigen::VectorXd>& y) {
  data.settled = kProjectionSettled * (data.rtol * y.array().abs() + data.atol.array()).matrix();
  return data.settled;
}

int rhs_trampoline(double t, N_Vector y, N_Vector ydot, void* user) {
  auto* data = static_cast<CvodeCallbackData*>(user);
  return sundials::guarded(*data->report, [&] {
    auto out = view(ydot);
    data->problem->rhs(t, view(y), out);
    return out.allFinite() ? 0 : 1;  // recoverable: CVODE retries with a smaller step
  });
}

int projection_trampoline(double t, N_Vector y, N_Vector corr, double /*eps*/, N_Vector err,
                          void* user) {
  auto* data = static_cast<CvodeCallbackData*>(user);
  ++data->projections;
  return sundials::guarded(*data->report, [&] {
    auto c = view(corr);
    if (!data->problem->project(t, view(y), c, settled_at(*data, view(y)))) {
      return 1;  // recoverable: smaller step
    }
    if (err != nullptr) {
      auto e = view(err);
      data->problem->project_error(e);
    }
    return c.allFinite() ? 0 : 1;
  });
}

/// z = P⁻¹ r for GMRES (OdeProblem::precondition); CVODE's γ, the Newton matrix's I − γJ.
int precondition_trampoline(double /*t*/, N_Vector /*y*/, N_Vector /*fy*/, N_Vector r, N_Vector z,
                            double gamma, double /*delta*/, int /*lr*/, void* user) {
  auto* data = static_cast<CvodeCallbackData*>(user);
  return sundials::guarded(*data->report, [&] {
    auto out = view(z);
    data->problem->precondition(gamma, view(r), out);
    return out.allFinite() ? 0 : 1;
  });
}

/// GMRES's Krylov dimension for a matrix-free problem: twice SUNDIALS' default of 5, so that a
/// Newton system the kinematic preconditioner leaves a few forces' modes in converges without
/// restarts (GMRES restarts are not enabled).
constexpr int kKrylovDimension = 10;

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

const sundials::Api kCvodeApi{
    "CVode",     CVodeGetReturnFlagName, CVodeGetCurrentTime, CVodeGetLastStep,
    CVodeGetDky, CVodeGetLastOrder,      failure_kind};

// CVODE's γ = h β changes with nearly every step: the projection scheme's saddle point is
// refactored when γ moves by more than CVODE's own threshold for a new matrix (dgmax_lsetup), and
// solves in between are scaled as CVODE scales them (validated: condyn validate, the stress
// suite).
constexpr double kNewtonGammaChange = 0.3;

class Cvode final : public sundials::SundialsStepper {
 public:
  Cvode(OdeProblem& problem, const Eigen::VectorXd& y0, double t0, const IntegratorOptions& options)
      : SundialsStepper(kCvodeApi), n_(problem.size()) {
    data_.problem = &problem;
    data_.report = &report_;
    SUNContext raw = nullptr;
    if (SUNContext_Create(nullptr, &raw) != 0) throw IntegrationError("SUNContext_Create failed");
    ctx_.reset(raw);
    y_.reset(sundials::new_vector(n_, ctx_.get()));
    work_.reset(sundials::new_vector(n_, ctx_.get()));
    if (!y_ || !work_) throw IntegrationError("N_VNew_Serial failed (out of memory?)");
    view(y_.get()) = y0;
    non_stiff_ = problem.non_stiff();
    mem_.reset(CVodeCreate(non_stiff_ ? CV_ADAMS : CV_BDF, ctx_.get()));
    if (!mem_) throw IntegrationError("CVodeCreate failed");
    if (non_stiff_) {
      // Functional iteration, without acceleration (Anderson's would keep m vectors of size n).
      fixed_point_.reset(SUNNonlinSol_FixedPoint(y_.get(), 0, ctx_.get()));
      if (!fixed_point_) throw IntegrationError("could not create the fixed-point iteration");
    } else {
      create_linear_solver(problem);
    }
    attach(mem_.get(), work_.get());
    check(CVodeSetErrHandlerFn(mem_.get(), sundials::record_message, &report_),
          "CVodeSetErrHandlerFn");
    check(CVodeInit(mem_.get(), rhs_trampoline, t0, y_.get()), "CVodeInit");
    check(CVodeSetUserData(mem_.get(), &data_), "CVodeSetUserData");
    // Adams' orders go to 12, BDF's to 5: the option caps both.
    check(CVodeSetMaxOrd(mem_.get(), options.max_order), "CVodeSetMaxOrd");
    data_.rtol = options.rtol;
    data_.atol = options.atol_vector(problem.unknown_kinds(), static_cast<int>(n_));
    view(work_.get()) = data_.atol;
    check(CVodeSVtolerances(mem_.get(), options.rtol, work_.get()),
          "CVodeSVtolerances");  // copies the vector
    if (non_stiff_) {
      check(CVodeSetNonlinearSolver(mem_.get(), fixed_point_.get()), "CVodeSetNonlinearSolver");
    } else {
      check(CVodeSetLinearSolver(mem_.get(), solver_.get(), matrix_.get()), "CVodeSetLinearSolver");
      if (!newton_ && !matrix_) {  // GMRES: J v by CVODE's difference quotients, our P
        check(CVodeSetPreconditioner(mem_.get(), nullptr, precondition_trampoline),
              "CVodeSetPreconditioner");
      }
    }
    if (problem.has_projection()) {
      check(CVodeSetProjFn(mem_.get(), projection_trampoline), "CVodeSetProjFn");
      check(CVodeSetProjErrEst(mem_.get(), SUNTRUE), "CVodeSetProjErrEst");
    }
  }

  /// The Newton iterations' linear solver: the problem's own sparse Newton solve when it has
  /// one, else GMRES on difference-quotient products (matrix_free()), else a dense
  /// difference-quotient Jacobian ((n_)² entries).
  void create_linear_solver(const OdeProblem& problem) {
    // A state-dependent one linearises at the predicted state, where CVODE's own matrix-based
    // solvers evaluate their Jacobians.
    newton_ = problem.newton_system();
    if (newton_) {
      void* mem = mem_.get();
      solver_.reset(sundials::make_newton_solver(
          *newton_,
          [mem](double& gamma) { return CVodeGetCurrentGamma(mem, &gamma) == CV_SUCCESS; },
          kNewtonGammaChange, ctx_.get(),
          [mem](double& t, N_Vector& y, long& steps) {
            N_Vector yn = nullptr, fn = nullptr, zn1 = nullptr;
            double gamma = 0.0, rl1 = 0.0;
            void* user = nullptr;
            return CVodeGetNonlinearSystemData(mem, &t, &y, &yn, &fn, &gamma, &rl1, &zn1, &user) ==
                       CV_SUCCESS &&
                   CVodeGetNumSteps(mem, &steps) == CV_SUCCESS;
          }));
      if (!solver_) throw IntegrationError("could not create the sparse Newton solver");
    } else if (problem.matrix_free()) {
      solver_.reset(SUNLinSol_SPGMR(y_.get(), SUN_PREC_LEFT, kKrylovDimension, ctx_.get()));
      if (!solver_) throw IntegrationError("could not create the GMRES linear solver");
    } else {
      matrix_.reset(SUNDenseMatrix(n_, n_, ctx_.get()));
      if (matrix_) solver_.reset(SUNLinSol_Dense(y_.get(), matrix_.get(), ctx_.get()));
      if (!matrix_ || !solver_) throw IntegrationError("could not create the dense linear solver");
    }
  }

  double step(double tout) override {
    double tret = 0.0;
    after_step(CVode(mem_.get(), tout, y_.get(), &tret, CV_ONE_STEP));
    return tret;
  }

  /// Between steps CVODE's interpolant leaves the constraints by the local error (1e-3 on the
  /// period-2 pendulum at rtol 1e-4, where the steps are on them to roundoff): an output or a
  /// quadrature point is projected as the steps are, and its y' is the right-hand side there.
  /// A projection that fails (a singular configuration) leaves the interpolated state.
  void interpolate(double t, Eigen::VectorXd& y, Eigen::VectorXd& yp) override {
    SundialsStepper::interpolate(t, y, yp);
    if (!data_.problem->has_projection()) return;
    correction_.resize(n_);
    try {
      if (!data_.problem->project(t, y, correction_, settled_at(data_, y))) return;
    } catch (const RecoverableError&) {
      return;
    }
    y += correction_;
    data_.problem->rhs(t, y, yp);
  }

  [[nodiscard]] Eigen::VectorXd y() override { return view(y_.get()); }
  [[nodiscard]] Eigen::VectorXd yp() override {
    double t = 0.0;
    check(CVodeGetCurrentTime(mem_.get(), &t), "CVodeGetCurrentTime");
    Eigen::VectorXd out(n_);
    data_.problem->rhs(t, view(y_.get()), out);
    return out;
  }
  void restart(double t) override {
    collect();  // CVodeReInit may reset the counters: keep what this segment did
    data_.problem->begin_segment(t);
    Eigen::VectorXd y = view(y_.get());
    data_.problem->settle(t, y);  // a load step may move what the rows fix
    view(y_.get()) = y;
    check(CVodeReInit(mem_.get(), t, y_.get()), "CVodeReInit");
    rebase();
  }
  /// restart(t) from the state y instead of its own (the end of a passage's bridge).
  void restart_from(double t, const Eigen::VectorXd& y) {
    view(y_.get()) = y;
    restart(t);
  }
  [[nodiscard]] bool wants_restart(double t) override {
    return data_.problem->wants_restart(t, view(y_.get()));
  }
  void set_stop_time(double t) override {
    check(CVodeSetStopTime(mem_.get(), t), "CVodeSetStopTime");
  }
  /// Entries of the matrix the Newton iterations factor: the problem's sparse one, the dense one,
  /// or none (GMRES on products).
  [[nodiscard]] long jacobian_nonzeros() const {
    if (non_stiff_) return 0;
    if (newton_) return newton_->nonzeros();
    return matrix_ ? static_cast<long>(n_) * static_cast<long>(n_) : 0;
  }

 private:
  [[nodiscard]] sundials::Counters read_counters() const override {
    sundials::Counters c;
    check(CVodeGetNumSteps(mem_.get(), &c.steps), "CVodeGetNumSteps");
    check(CVodeGetNumRhsEvals(mem_.get(), &c.evaluations), "CVodeGetNumRhsEvals");
    if (newton_) {
      c.jacobians = sundials::newton_solver_setups(solver_.get());  // one matrix per setup
    } else if (!non_stiff_) {  // functional iteration: no Jacobian
      check(CVodeGetNumJacEvals(mem_.get(), &c.jacobians), "CVodeGetNumJacEvals");
    }
    check(CVodeGetNumNonlinSolvIters(mem_.get(), &c.newton), "CVodeGetNumNonlinSolvIters");
    check(CVodeGetNumNonlinSolvConvFails(mem_.get(), &c.newton_failures),
          "CVodeGetNumNonlinSolvConvFails");
    check(CVodeGetNumErrTestFails(mem_.get(), &c.error_tests), "CVodeGetNumErrTestFails");
    c.projections = data_.projections;
    return c;
  }
  [[nodiscard]] std::string notes(const sundials::Counters& totals) const override {
    if (!data_.problem->has_projection()) return {};
    return std::to_string(totals.projections) + " projections onto the constraints";
  }

  sunindextype n_;
  CvodeCallbackData data_;
  Eigen::VectorXd correction_;  ///< an interpolated state's projection
  // Declared in creation order: destroyed in reverse (CVODE memory first, context last).
  ContextPtr ctx_;
  VectorPtr y_, work_;
  std::unique_ptr<NewtonSystem> newton_;  ///< outlives solver_, which points to it
  MatrixPtr matrix_;
  SolverPtr solver_;
  NonlinearSolverPtr fixed_point_;  ///< a non-stiff problem's functional iteration
  bool non_stiff_ = false;
  CvodePtr mem_;  ///< destroyed first
};

}  // namespace

RawTrajectory integrate_ode(OdeProblem& problem, const Eigen::VectorXd& y0,
                            const IntegratorOptions& options, SolveSummary& summary,
                            const PassageBridge* bridge) {
  options.validate();
  if (y0.size() != problem.size()) throw std::invalid_argument("integrator: y0 has the wrong size");
  const WallTimer timer(summary);
  const double t0 = options.output_times.front();
  problem.begin_segment(t0);
  if (problem.size() == 0) {  // every coordinate fixed: the loop visits the times, nothing else
    NoUnknowns none([&problem](double t) { problem.begin_segment(t); }, options.output_times);
    RawTrajectory out = drive(none, y0, y0, options, summary);
    summary.unknowns = 0;
    summary.set_reached(options.output_times.back());
    return out;
  }
  Eigen::VectorXd y_start = y0;
  problem.settle(t0, y_start);
  Cvode cvode(problem, y_start, t0, options);
  Eigen::VectorXd yp0(problem.size());
  problem.rhs(t0, y_start, yp0);
  summary.unknowns = problem.size();  // before the loop: a failed run's summary has them too
  summary.jacobian_nonzeros = cvode.jacobian_nonzeros();
  RawTrajectory out =
      drive_bridged(cvode, bridge, problem.size(), t0, y_start, yp0, options, summary);
  summary.set_reached(options.output_times.back());
  return out;
}

}  // namespace condyn
