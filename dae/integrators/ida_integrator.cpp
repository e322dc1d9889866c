#include "dae/integrators/ida_integrator.hpp"

#include "dae/integrators/ida_failure_kind.hpp"
#include "dae/integrators/klu_linear_solver.hpp"
#include "dae/integrators/newton_linear_solver.hpp"
#include "dae/integrators/no_unknowns.hpp"
#include "dae/integrators/stale_correction.hpp"
#include "dae/integrators/step_driver.hpp"
#include "dae/integrators/sundials_raii.hpp"
#include "dae/integrators/sundials_stepper.hpp"
#include "dae/integrators/trap_watch.hpp"
#include "dae/integrators/vector_ops.hpp"

#include <ida/ida.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <memory>
#include <sstream>
#include <vector>

namespace condyn {

namespace {

using sundials::ContextPtr;
using sundials::MatrixPtr;
using sundials::SolverPtr;
using sundials::VectorPtr;
using sundials::view;

// The integrator memory's owner; the others come from dae/integrators/sundials_raii.hpp.
struct IdaDeleter {
  void operator()(void* mem) const { IDAFree(&mem); }
};
using IdaPtr = std::unique_ptr<void, IdaDeleter>;

/// What the C callbacks need; exceptions thrown by the problem go to `report`, never through IDA's
/// C frames.
struct IdaCallbackData {
  DaeProblem* problem = nullptr;
  double rtol = 0.0;
  Eigen::VectorXd atol;     ///< per component (IntegratorOptions::atol_vector)
  double time_scale = 1.0;  ///< IntegratorOptions::time_scale
  void* mem = nullptr;      ///< IDA memory, for the step size in the weight function
  /// The step the weights assume before IDA has taken one (at t0 and after each restart, where
  /// IDA computes the weights once for the first step and all its retries). With h = 1 there,
  /// the higher-index components' weights were 1/h larger than in later steps and the first
  /// step failed to converge at every size (GGL on Andrews, the four-bar, the hanging chain).
  /// The multipliers are consistent at t0 (make_consistent), so weights this lax for one step
  /// cost nothing. Also passed to IDASetInitStep.
  double first_step = 1.0;
  /// Differentiation index less one per component (DaeProblem::variable_index): the power of
  /// h/T in its weight.
  Eigen::VectorXi order;
  std::vector<double> scale;  ///< (h/T)^order for each order, recomputed at each call
  /// Floors under |y_i| in the weights, engaged by a trapped run (dae/integrators/trap_watch.hpp).
  TrapWatch watch;
  Eigen::VectorXd floor;
  /// The dense solver's staging matrix with the problem's pattern (empty for KLU, whose matrix
  /// takes the values directly: a copy of the Newton matrix less, issue 12).
  Eigen::SparseMatrix<double> jac;
  /// Corrections from a stale matrix for problems with algebraic equations, or null: takes W
  /// from each Jacobian (dae/integrators/stale_correction.hpp).
  StaleCorrection* stale = nullptr;
  sundials::CallbackReport* report = nullptr;
};

int residual_trampoline(double t, N_Vector y, N_Vector yp, N_Vector r, void* user) {
  auto* data = static_cast<IdaCallbackData*>(user);
  return sundials::guarded(*data->report, [&] {
    auto rv = view(r);
    data->problem->residual(t, view(y), view(yp), rv);
    // A non-finite residual is recoverable: IDA retries with a smaller step.
    return rv.allFinite() ? 0 : 1;
  });
}

int jacobian_trampoline(double t, double cj, N_Vector y, N_Vector yp, N_Vector /*r*/, SUNMatrix J,
                        void* user, N_Vector /*t1*/, N_Vector /*t2*/, N_Vector /*t3*/) {
  auto* data = static_cast<IdaCallbackData*>(user);
  return sundials::guarded(*data->report, [&] {
    if (double* values = sundials::pattern_matrix_values(J)) {
      // The KLU solver's matrix: the values in the problem's fixed pattern, zeroed by IDA.
      const JacobianMap map = data->problem->jacobian_pattern().map(values);
      data->problem->fill_jacobian(t, view(y), view(yp), cj, map);
      if (data->stale) data->stale->update(map, cj);
    } else {
      data->problem->jacobian(t, view(y), view(yp), cj, data->jac);
      if (data->stale) data->stale->update(data->jac, cj);
      for (int k = 0; k < data->jac.outerSize(); ++k) {
        for (Eigen::SparseMatrix<double>::InnerIterator it(data->jac, k); it; ++it) {
          SM_ELEMENT_D(J, it.row(), it.col()) = it.value();
        }
      }
    }
    return 0;
  });
}

/// Higher-index problems: the first step, as a fraction of the first output interval (the
/// BDF start at order 1 ramps up from there within a few steps), when no guess is given.
constexpr double kFirstStepFraction = 1e-8;

/// IDA's bound on cj's change before its linear solver is set up again (IDASetDeltaCjLSetup):
/// a matrix factored at cj serves while cj / cj_setup stays within [(1 − d) / (1 + d),
/// (1 + d) / (1 − d)]. IDA's default d = 0.25 ([0.6, 1.67]) below kLargeSystem unknowns; 0.5
/// ([1/3, 3]: the doubling steps of the start and a doubled step later share a matrix) from it,
/// for the problems that reuse their Newton matrices (DaeProblem::reuses_newton_matrix). A stale
/// matrix costs steps; a factorization costs about what a step does on small systems and tens of
/// steps' solves on large ones. Measured in docs/benchmarks.md ("The start of a stiff run"): 0.5
/// paid on braced walls of 4e4 and 2e5 unknowns, not on a shear frame of 10; 0.7 did not pay.
constexpr double kDeltaCj = 0.25;
constexpr double kLargeDeltaCj = 0.5;
constexpr long kLargeSystem = 10000;

/// The condensed Newton solve's bound on |cj / cj_setup − 1| (make_newton_solver's max_change)
/// from IDA's d above: 2d / (1 + d), IDA's lower bound (a doubled step halves cj), its upper
/// one tighter (1 + 2d / (1 + d) instead of (1 + d) / (1 − d)).
constexpr double condensed_cj_change(double d) { return 2.0 * d / (1.0 + d); }

/// Called by the weight function after each step (IDA evaluates the weights once per step).
void watch_for_trap(IdaCallbackData& data, double t) {
  long steps = 0, fails = 0;
  IDAGetNumSteps(data.mem, &steps);
  IDAGetNumErrTestFails(data.mem, &fails);
  data.watch.observe(steps, fails, t);
}

/// Error weights (h/T)^(k_i − 1) / (rtol |y_i| + atol_i), k_i the component's index (DaeProblem),
/// T the model's time scale (IntegratorOptions::time_scale): h/T is a pure number, so the
/// weights do not change with the units (with the default atol of λ,
/// dae/formulations/model_scales.hpp, an index-2 correction δλ ≤ atol_λ T/h moves v by h a δλ / m ≤
/// atol / T).
int weight_trampoline(N_Vector y, N_Vector ewt, void* user) {
  auto* data = static_cast<IdaCallbackData*>(user);
  double h = 0.0;
  if (data->mem != nullptr) IDAGetCurrentStep(data->mem, &h);
  h = std::abs(h);
  if (!(h > 0.0)) h = data->first_step;
  // One power per index, not per component: std::pow per unknown is a visible part of a large
  // GGL step (issue 12).
  for (std::size_t k = 0; k < data->scale.size(); ++k) {
    data->scale[k] = std::pow(h / data->time_scale, static_cast<double>(k));
  }
  const double* yv = N_VGetArrayPointer(y);
  double* w = N_VGetArrayPointer(ewt);
  const double* atol = data->atol.data();
  const int* order = data->order.data();
  const Eigen::Index n = data->order.size();
  bool floored = false;
  if (data->mem != nullptr) {
    double t = 0.0;
    IDAGetCurrentTime(data->mem, &t);
    if (!data->watch.engaged) watch_for_trap(*data, t);
    if (data->watch.engaged) {
      const bool ok = sundials::guarded(*data->report, [&] {
                        floored = data->problem->error_scale_floors(t, view(y), data->floor);
                        data->watch.applied = data->watch.applied || floored;
                        return 0;
                      }) == 0;
      if (!ok) return -1;
    }
  }
  const double* floor = data->floor.data();
  for (Eigen::Index i = 0; i < n; ++i) {
    const double magnitude = floored ? std::max(std::abs(yv[i]), floor[i]) : std::abs(yv[i]);
    w[i] = data->scale[static_cast<std::size_t>(order[i])] / (data->rtol * magnitude + atol[i]);
  }
  return 0;
}

const sundials::Api kIdaApi{"IDASolve", IDAGetReturnFlagName, IDAGetCurrentTime, IDAGetLastStep,
                            IDAGetDky,  IDAGetLastOrder,      ida_failure_kind};

class Ida final : public sundials::SundialsStepper {
 public:
  Ida(DaeProblem& problem, const IntegratorOptions& options)
      : SundialsStepper(kIdaApi), n_(problem.size()) {
    data_.problem = &problem;
    data_.report = &report_;
    // The problem's own Newton solve (condensed, no Jacobian formed) when it has one and KLU is
    // asked for; else IDA factors the Jacobian jacobian() fills, KLU or dense. The condensed
    // matrix is refactored when cj leaves the band IDA keeps its own matrices in, or, unless the
    // problem reuses its Newton matrices (DaeProblem::reuses_newton_matrix), whenever cj changes.
    if (options.condensed_newton && !options.dense_linear_solver) {
      newton_ = problem.newton_system();
      max_cj_change_ = problem.reuses_newton_matrix() ? condensed_cj_change(delta_cj()) : 0.0;
      // The plan asks for CHOLMOD only where the matrix is symmetric positive definite.
      if (options.cholmod && (!newton_ || !newton_->use_cholmod(options.cholmod_ordering))) {
        throw IntegrationError("CHOLMOD asked for a Newton matrix that is not symmetric");
      }
    }
    if (!newton_ && options.dense_linear_solver) {
      data_.jac = problem.jacobian_pattern().matrix();
    }
    SUNContext raw_ctx = nullptr;
    check_raw(SUNContext_Create(nullptr, &raw_ctx), "SUNContext_Create");
    ctx_.reset(raw_ctx);
    y_.reset(sundials::new_vector(n_, ctx_.get()));
    yp_.reset(sundials::new_vector(n_, ctx_.get()));
    id_.reset(sundials::new_vector(n_, ctx_.get()));
    work_.reset(sundials::new_vector(n_, ctx_.get()));
    if (!y_ || !yp_ || !id_ || !work_)
      throw IntegrationError("N_VNew_Serial failed (out of memory?)");
    mem_.reset(IDACreate(ctx_.get()));
    if (!mem_) throw IntegrationError("IDACreate failed");
    if (newton_) {
      void* mem = mem_.get();
      solver_.reset(sundials::make_newton_solver(
          *newton_, [mem](double& cj) { return IDAGetCurrentCj(mem, &cj) == IDA_SUCCESS; },
          max_cj_change_, ctx_.get()));
    } else if (options.dense_linear_solver) {
      matrix_.reset(SUNDenseMatrix(n_, n_, ctx_.get()));
      if (matrix_) solver_.reset(SUNLinSol_Dense(y_.get(), matrix_.get(), ctx_.get()));
    } else {
      matrix_.reset(sundials::make_pattern_matrix(problem.jacobian_pattern(), ctx_.get()));
      if (matrix_) solver_.reset(sundials::make_klu_solver(problem.jacobian_pattern(), ctx_.get()));
    }
    if ((!newton_ && !matrix_) || !solver_) {
      throw IntegrationError("could not create the linear solver");
    }
    // Equations without y' (GGL's ψ and φ rows, DaeProblem::algebraic_equations): corrections
    // from a stale matrix keep them exact (dae/integrators/stale_correction.hpp) and IDA's own
    // scaling goes off below. The condensed solve refactors at every cj and needs none.
    const std::vector<bool> algebraic = problem.algebraic_equations();
    if (!newton_ && std::find(algebraic.begin(), algebraic.end(), true) != algebraic.end()) {
      stale_ = std::make_unique<StaleCorrection>(algebraic, problem.differential_id());
      void* mem = mem_.get();
      solver_.reset(sundials::make_stale_corrected_solver(
          solver_.release(), *stale_,
          [mem](double& cj) { return IDAGetCurrentCj(mem, &cj) == IDA_SUCCESS; }, ctx_.get()));
      if (!solver_) throw IntegrationError("could not create the linear solver");
      data_.stale = stale_.get();
    }
    attach(mem_.get(), work_.get());
    check(IDASetErrHandlerFn(mem_.get(), sundials::record_message, &report_), "IDASetErrHandlerFn");
  }

  void init(double t0, const Eigen::VectorXd& y0, const Eigen::VectorXd& yp0,
            const IntegratorOptions& options) {
    view(y_.get()) = y0;
    view(yp_.get()) = yp0;
    // IDA reads the id vector for one purpose here: IDASetSuppressAlg leaves out of the error test
    // the components marked 0. So higher-index components are marked 0 too (index3's velocities
    // are differential but index 2).
    const Eigen::VectorXd index = data_.problem->variable_index();
    const bool higher_index = index.size() > 0 && index.maxCoeff() > 1.0;
    view(id_.get()) = data_.problem->differential_id();
    if (higher_index) {
      view(id_.get()) = (index.array() > 1.0).select(0.0, view(id_.get()).array());
    }
    check(IDAInit(mem_.get(), residual_trampoline, t0, y_.get(), yp_.get()), "IDAInit");
    // IDA's own first step, min(1e-3 of the way to the first output, 0.5 / ‖y'(0)‖), is the
    // step that changes y by half its tolerance: from rest under a load, a velocity change of
    // atol_v / 2 (6e-7 s on a braced wall whose first steps pass the error test at 4e-6 s). The
    // guess replaces it where every unknown is in the error test (reuses_newton_matrix); index1
    // and Baumgarte keep it (their errors on IFToMM A01 and A03 and their convergence in rtol on
    // the chapter's 5.6.2 depended on it).
    const bool guess =
        higher_index || (options.first_step && data_.problem->reuses_newton_matrix());
    if (options.output_times.size() > 1) {
      const double interval = options.output_times[1] - options.output_times[0];
      data_.first_step = options.first_step ? std::min(*options.first_step, 0.5 * interval)
                                            : kFirstStepFraction * interval;
    }
    check(IDASetUserData(mem_.get(), &data_), "IDASetUserData");
    check(IDASetMaxOrd(mem_.get(), options.max_order), "IDASetMaxOrd");
    check(IDASetId(mem_.get(), id_.get()), "IDASetId");
    data_.atol = options.atol_vector(data_.problem->unknown_kinds(), static_cast<int>(n_),
                                     data_.problem->multiplier_row_scales(t0, y0),
                                     data_.problem->multiplier_row_masses(t0, y0));
    if (higher_index) {
      data_.rtol = options.rtol;
      data_.time_scale = options.time_scale;
      data_.order = (index.array() - 1.0).round().cast<int>().max(0);
      data_.scale.assign(static_cast<std::size_t>(data_.order.maxCoeff()) + 1, 1.0);
      data_.mem = mem_.get();
      check(IDAWFtolerances(mem_.get(), weight_trampoline), "IDAWFtolerances");
      check(IDASetSuppressAlg(mem_.get(), SUNTRUE), "IDASetSuppressAlg");
    } else {
      view(work_.get()) = data_.atol;  // IDASVtolerances copies it
      check(IDASVtolerances(mem_.get(), options.rtol, work_.get()), "IDASVtolerances");
      if (data_.problem->suppress_algebraic_error()) {
        check(IDASetSuppressAlg(mem_.get(), SUNTRUE), "IDASetSuppressAlg");
      }
    }
    check(IDASetLinearSolver(mem_.get(), solver_.get(), matrix_.get()), "IDASetLinearSolver");
    if (!newton_) check(IDASetJacFn(mem_.get(), jacobian_trampoline), "IDASetJacFn");
    if (stale_) {
      check(IDASetLinearSolutionScaling(mem_.get(), SUNFALSE), "IDASetLinearSolutionScaling");
    }
    if (data_.problem->reuses_newton_matrix()) {
      check(IDASetDeltaCjLSetup(mem_.get(), delta_cj()), "IDASetDeltaCjLSetup");
    }
    // A table's first kink caps the first step (IntegratorOptions::first_kink): the guess, or
    // IDA's own, which is at most 1e-3 of the way to the first output.
    if (options.output_times.size() > 1) {
      const double kink_step = 0.5 * (options.first_kink - t0);
      const double own = guess ? data_.first_step : 1e-3 * (options.output_times[1] - t0);
      if (kink_step > 0.0 && kink_step < own) {
        data_.first_step = kink_step;
      } else if (!guess) {
        return;  // IDA's own
      }
      check(IDASetInitStep(mem_.get(), data_.first_step), "IDASetInitStep");
    }
  }

  /// IDA's bound on cj's change before a new factorization, by the size of the system.
  [[nodiscard]] double delta_cj() const { return n_ >= kLargeSystem ? kLargeDeltaCj : kDeltaCj; }

  /// Entries of the matrix the Newton iterations factor: the condensed one, else the Jacobian.
  [[nodiscard]] long jacobian_nonzeros() const {
    return newton_ ? newton_->nonzeros()
                   : static_cast<long>(data_.problem->jacobian_pattern().nonZeros());
  }

  void reinit(double t0, const Eigen::VectorXd& y0, const Eigen::VectorXd& yp0) {
    collect();  // IDAReInit resets IDA's counters: keep what this segment did
    view(y_.get()) = y0;
    view(yp_.get()) = yp0;
    check(IDAReInit(mem_.get(), t0, y_.get(), yp_.get()), "IDAReInit");
    if (data_.order.size() > 0)
      check(IDASetInitStep(mem_.get(), data_.first_step), "IDASetInitStep");
    rebase();
  }

  void set_stop_time(double t) override { check(IDASetStopTime(mem_.get(), t), "IDASetStopTime"); }
  /// Takes one internal step (bounded by the stop time that is set); returns the time reached,
  /// the stop time exactly when the step lands on it. IDA sizes its first step after a
  /// (re)initialisation from the distance to `tout`, so callers pass the next output time.
  double step(double tout) override {
    double tret = 0.0;
    after_step(IDASolve(mem_.get(), tout, &tret, y_.get(), yp_.get(), IDA_ONE_STEP));
    return tret;
  }

  [[nodiscard]] Eigen::VectorXd y() override { return view(y_.get()); }
  [[nodiscard]] Eigen::VectorXd yp() override { return view(yp_.get()); }

  void restart(double t) override {
    data_.problem->begin_segment(t);
    Eigen::VectorXd yb = view(y_.get()), ypb;
    data_.problem->jump_velocities(t, yb);
    data_.problem->make_consistent(t, yb, ypb);
    reinit(t, yb, ypb);
  }
  /// restart(t) from the state y instead of its own (the end of a passage's bridge).
  void restart_from(double t, const Eigen::VectorXd& y) {
    view(y_.get()) = y;
    restart(t);
  }

 private:
  [[nodiscard]] sundials::Counters read_counters() const override {
    sundials::Counters c;
    check(IDAGetNumSteps(mem_.get(), &c.steps), "IDAGetNumSteps");
    check(IDAGetNumResEvals(mem_.get(), &c.evaluations), "IDAGetNumResEvals");
    if (newton_) {
      c.jacobians = sundials::newton_solver_setups(solver_.get());  // one matrix per setup
    } else {
      check(IDAGetNumJacEvals(mem_.get(), &c.jacobians), "IDAGetNumJacEvals");
    }
    check(IDAGetNumNonlinSolvIters(mem_.get(), &c.newton), "IDAGetNumNonlinSolvIters");
    check(IDAGetNumNonlinSolvConvFails(mem_.get(), &c.newton_failures),
          "IDAGetNumNonlinSolvConvFails");
    check(IDAGetNumErrTestFails(mem_.get(), &c.error_tests), "IDAGetNumErrTestFails");
    return c;
  }
  [[nodiscard]] std::string notes(const sundials::Counters& /*totals*/) const override {
    if (!data_.watch.applied) return {};
    std::ostringstream s;
    s.precision(6);
    s << "error weights of the DOFs on constraint rows floored by their rows from t = "
      << data_.watch.since << ", after " << kTrappedSteps
      << " steps in a row each failed the error test (docs/schemes.md; on a long run, compare "
         "with index2 or projection)";
    return s.str();
  }
  static void check_raw(int flag, const char* call) {
    if (flag != 0)
      throw IntegrationError(std::string(call) + " failed (" + std::to_string(flag) + ")");
  }

  sunindextype n_;
  IdaCallbackData data_;
  // Declared in creation order: destroyed in reverse (IDA memory first, context last).
  ContextPtr ctx_;
  VectorPtr y_, yp_, id_, work_;
  std::unique_ptr<NewtonSystem> newton_;  ///< outlives solver_, which points to it
  double max_cj_change_ = 0.0;            ///< of newton_'s factorization (make_newton_solver)
  MatrixPtr matrix_;
  std::unique_ptr<StaleCorrection> stale_;  ///< outlives solver_, which points to it
  SolverPtr solver_;
  IdaPtr mem_;  ///< destroyed first
};

}  // namespace

RawTrajectory integrate(DaeProblem& problem, const Eigen::VectorXd& y0,
                        const IntegratorOptions& options, SolveSummary& summary,
                        const PassageBridge* bridge) {
  options.validate();
  if (y0.size() != problem.size()) throw std::invalid_argument("integrator: y0 has the wrong size");
  const WallTimer timer(summary);
  const double t0 = options.output_times.front();
  if (problem.size() == 0) {
    NoUnknowns none([&problem](double t) { problem.begin_segment(t); }, options.output_times);
    problem.begin_segment(t0);
    RawTrajectory out = drive(none, y0, y0, options, summary);
    summary.unknowns = 0;
    summary.set_reached(options.output_times.back());
    return out;
  }
  Ida ida(problem, options);
  problem.begin_segment(t0);
  Eigen::VectorXd y_init = y0, yp0;
  problem.make_consistent(t0, y_init, yp0);
  ida.init(t0, y_init, yp0, options);
  summary.unknowns = problem.size();  // before the loop: a failed run's summary has them too
  summary.jacobian_nonzeros = ida.jacobian_nonzeros();
  RawTrajectory out = drive_bridged(ida, bridge, problem.size(), t0, y_init, yp0, options, summary);
  summary.set_reached(options.output_times.back());
  return out;
}

}  // namespace condyn
