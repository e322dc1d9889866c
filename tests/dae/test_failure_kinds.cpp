// Failures are data: an explicit kind set where the failure arises (SUNDIALS flags by their codes,
// the loop's budgets and checks), refined by the loop from the facts, and advice chosen from the
// kind and the facts rather than from the message's words. Also the loop's progress callback and
// its whole-run budgets, and in-process IDA and CVODE failures (so that the sanitizer tier's leak
// check sees the flag-name strings SUNDIALS allocates).
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "dae/integrators/cvode_integrator.hpp"
#include "dae/integrators/ida_integrator.hpp"
#include "dae/integrators/step_driver.hpp"
#include "dae/run/failure_advice.hpp"
#include "dae/run/solve.hpp"
#include "models/assembly/build_model.hpp"
#include "models/scene/scene_parser.hpp"
#include "tests/scene_text.hpp"

using namespace condyn;

namespace test_failure_kinds {

namespace {

bool contains(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

/// y' = 1 in steps of h, as the loop sees an integrator; throws `fail_kind` at step `fail_at`
/// (0: never) with its last step set to `last_step` from then on; from step `stall_at` (0: never)
/// `stall_steps` steps of 1e-13 t, at roundoff of t, as a collapsing integrator takes them.
class FakeStepper : public Stepper {
 public:
  explicit FakeStepper(double h) : h_(h) {}
  double step(double /*tout*/) override {
    ++taken_;
    if (fail_at > 0 && taken_ >= fail_at) {
      h_ = last_step;
      throw IntegrationError(fail_kind, "fake failure");
    }
    const bool stalled = stall_at > 0 && taken_ >= stall_at && taken_ < stall_at + stall_steps;
    t_ = std::min(t_ + (stalled ? 1e-13 * t_ : h_), stop_);
    return t_;
  }
  void interpolate(double t, Eigen::VectorXd& y, Eigen::VectorXd& yp) override {
    y = Eigen::VectorXd::Constant(1, t);
    yp = Eigen::VectorXd::Ones(1);
  }
  [[nodiscard]] Eigen::VectorXd y() override { return Eigen::VectorXd::Constant(1, t_); }
  [[nodiscard]] Eigen::VectorXd yp() override { return Eigen::VectorXd::Ones(1); }
  void restart(double t) override { t_ = t; }
  void set_stop_time(double t) override { stop_ = t; }
  void fill_summary(SolveSummary& summary) override { summary.last_step = h_; }

  long fail_at = 0;
  long stall_at = 0, stall_steps = 0;
  FailureKind fail_kind = FailureKind::convergence;
  double last_step = 0.0;

 private:
  double h_, t_ = 0.0, stop_ = 0.0;
  long taken_ = 0;
};

// Binary fractions throughout (steps of 1/64, outputs every 1/4): the fake integrator's times are
// exact, so counts of steps and rows are exact too.
constexpr double kStep = 1.0 / 64.0;

/// Outputs at 0, 1/4, 1/2, 3/4, 1.
IntegratorOptions quarter_outputs() {
  IntegratorOptions o;
  o.output_times = {0.0, 0.25, 0.5, 0.75, 1.0};
  return o;
}

/// The failure a drive() over `stepper` throws (kind unknown when none is thrown).
IntegrationError drive_failure(FakeStepper& stepper, const IntegratorOptions& options) {
  SolveSummary summary;
  try {
    (void)drive(stepper, Eigen::VectorXd::Zero(1), Eigen::VectorXd::Ones(1), options, summary);
  } catch (const IntegrationError& e) {
    return e;
  }
  return IntegrationError("no failure");
}

/// A failure as the loop leaves it: in the loop, from t0 = 0 to t_end.
RunFailure failure(FailureKind kind, double t_reached, double last_step, double t_end, long steps) {
  IntegrationError e(kind, "constructed");
  e.in_loop = true;
  e.t_reached = t_reached;
  e.last_step = last_step;
  e.t_end = t_end;
  e.steps = steps;
  e.elapsed_seconds = 10.0;
  return failure_of(e);
}

}  // namespace

TEST_CASE("each failure kind gets its own advice, worded from the facts") {
  // Before the first step: never "a singular configuration"; the start is what to check.
  const std::string start =
      failure_suggestion(Scheme::ggl, failure(FailureKind::first_step, 0.0, 0.0, 10.0, 0));
  CHECK(contains(start, "before its first step"));
  CHECK(contains(start, "initial state"));
  CHECK(contains(start, "atol"));
  CHECK(contains(start, "another scheme"));
  CHECK_FALSE(contains(start, "singular configuration"));
  CHECK_FALSE(contains(start, "collapsed"));
  // A budget: how much is left, from the last step and the pace; never "collapsed".
  const std::string budget =
      failure_suggestion(Scheme::index1, failure(FailureKind::step_budget, 3.0, 0.01, 1e300, 1000));
  CHECK(contains(budget, "step budget"));
  CHECK(contains(budget, "--max-steps"));
  CHECK(contains(budget, "1e+302 more steps"));  // (1e300 − 3) / 0.01
  CHECK_FALSE(contains(budget, "collapsed"));
  // In IDA's start-up (fewer than 100 steps) the last step says nothing of the rest: no figure.
  const std::string early =
      failure_suggestion(Scheme::index1, failure(FailureKind::step_budget, 1e-6, 1e-7, 1.0, 5));
  CHECK(contains(early, "after 5 steps the step size is still growing"));
  CHECK_FALSE(contains(early, "more steps"));
  const std::string wall = failure_suggestion(
      Scheme::ggl, failure(FailureKind::wall_time_budget, 2.0, 0.01, 100.0, 1000));
  CHECK(contains(wall, "wall-time budget"));
  CHECK(contains(wall, "about 490 s"));  // 10 s for 2 of 100: 490 s for the remaining 98
  const std::string collapsed = failure_suggestion(
      Scheme::index3, failure(FailureKind::step_size_collapsed, 1.0, 1e-200, 2.0, 50));
  CHECK(contains(collapsed, "singular configuration"));
  CHECK(contains(collapsed, "try ggl"));  // index3's own advice
  CHECK(contains(failure_suggestion(
                     Scheme::ggl, failure(FailureKind::steps_per_output, 1e-4, 1e-9, 20.0, 100000)),
                 "very stiff"));
  CHECK(contains(failure_suggestion(Scheme::ggl,
                                    failure(FailureKind::tolerance_too_tight, 1.0, 1e-3, 2.0, 10)),
                 "double precision"));
  CHECK(contains(
      failure_suggestion(Scheme::ggl, failure(FailureKind::linear_solver, 1.0, 1e-3, 2.0, 10)),
      "could not be factored"));
  CHECK(contains(failure_suggestion(Scheme::ggl, failure(FailureKind::bad_input, 0.0, 0.0, 2.0, 0)),
                 "refused an input"));
  {
    // IDA's first step is 0.5 / |y'0|: a load of 1e300 (|y'| / atol beyond the double range)
    // gave a step of 0, refused as a stop time "behind" t = 0. Named for what it is.
    RunFailure zero_step = failure(FailureKind::bad_input, 0.0, 0.0, 1.0, 0);
    zero_step.t0 = 0.0;
    zero_step.message =
        "IDASolve: The value tstop = 1 is behind current t = 0, in the direction of integration.";
    const std::string advice = failure_suggestion(Scheme::elimination, zero_step);
    CHECK(contains(advice, "first step came out as 0"));
    CHECK(contains(advice, "rescale the model or loosen atol"));
  }
  CHECK(contains(
      failure_suggestion(Scheme::ggl, failure(FailureKind::non_finite, 1.0, 1e-3, 2.0, 10)),
      "blew up"));
  const std::string conv =
      failure_suggestion(Scheme::baumgarte, failure(FailureKind::convergence, 1.0, 1e-3, 2.0, 10));
  CHECK(contains(conv, "near the time reached"));
  CHECK(contains(conv, "Baumgarte gains"));
  // GGL's points at its derived μ and λ tolerances, which tight rtol can bring to roundoff.
  const std::string ggl_collapsed = failure_suggestion(
      Scheme::ggl, failure(FailureKind::step_size_collapsed, 4.6e-5, 5e-22, 10.0, 100000));
  CHECK(contains(ggl_collapsed, "singular configuration"));
  CHECK(contains(ggl_collapsed, "set [solve] atol_mu and atol_multiplier larger"));
  // The advice follows the kind, not the message: a message with another kind's words in it.
  IntegrationError misleading(FailureKind::first_step, "took 10 steps without reaching NaN");
  CHECK(contains(failure_suggestion(Scheme::ggl, failure_of(misleading)), "before its first step"));
}

TEST_CASE("a collapse at an atol near roundoff says to raise atol") {
  // A conical pendulum at rtol 1e-8 and atol 1e-16 collapsed under GGL with advice about
  // singular configurations and rtol 1e-10 alone.
  const RunFailure collapsed = failure(FailureKind::step_size_collapsed, 0.02, 1e-18, 10.0, 1000);
  const std::string tiny = roundoff_advice(collapsed, 1e-16, 0.01, 0.0);
  CHECK(contains(tiny,
                 "; atol 1e-16 is within 100 ulps of 1 (the largest of 1, the model's "
                 "coordinates, 0, and the largest displacement reached, 0.01), which "
                 "doubles hold to about 2.2e-16"));
  // The model's coordinates set it when larger: a pendulum of length 1e6 at atol 1e-10
  // (roundoff 2.2e-10) failed under projection with advice about singular configurations.
  CHECK(contains(roundoff_advice(collapsed, 1e-10, 4.4, 1e6), "within 100 ulps of 1e+06"));
  CHECK(contains(tiny, "raise atol"));
  // The largest displacement sets the scale when above 1: 1e-12 beside 1e5 (roundoff 2.2e-11).
  CHECK(contains(roundoff_advice(collapsed, 1e-12, 1e5, 0.0), "within 100 ulps of 1e+05"));
  // Not near roundoff, or a failure the tolerances do not explain: nothing.
  CHECK(roundoff_advice(collapsed, 1e-13, 1.0, 0.0).empty());  // 450 ulps of 1
  CHECK(roundoff_advice(failure(FailureKind::step_budget, 0.02, 1e-18, 10.0, 1000), 1e-16, 1.0, 0.0)
            .empty());
  // Before the first step too (GGL at atol 1e-20 and rtol 1e-4 on an SI oscillator).
  CHECK(
      contains(roundoff_advice(failure(FailureKind::first_step, 0.0, 0.0, 1.0, 0), 1e-20, 0.0, 0.0),
               "; atol 1e-20 is within 100 ulps of 1"));
}

TEST_CASE("a failure a tolerance below roundoff explains names the tolerance, not a singularity") {
  // A hanging chain of 30,000 links under GGL failed at t = 9.4e-6 (IDA_CONV_FAIL) with advice
  // about singular configurations while its atol_mu (1e-10) lay below what the constraint rows'
  // roundoff allows (about 3e-10, dae/formulations/model_scales.hpp).
  const RunFailure conv = failure(FailureKind::convergence, 9.4e-6, 1e-6, 1.0, 9);
  const std::string cause = mu_roundoff_advice(conv, 1e-10, 4.8e-9);
  CHECK(contains(cause, "; atol_mu 1e-10 lies below 4.8e-09, the smallest GGL's μ can be held to"));
  CHECK(contains(cause, "set it to 4.8e-09 or more"));
  const std::string advice = failure_suggestion(Scheme::ggl, conv, cause);
  CHECK(advice.find("repeated convergence or error-test failures because a tolerance asks for more "
                    "than double precision holds; atol_mu 1e-10") == 0);
  CHECK_FALSE(contains(advice, "singular configuration"));
  const RunFailure collapsed = failure(FailureKind::step_size_collapsed, 607.0, 1e-13, 700.0, 9);
  CHECK(failure_suggestion(Scheme::ggl, collapsed, cause)
            .find("the step size collapsed to roundoff of the time reached because a tolerance") ==
        0);
  // At or above the floor, or a failure no tolerance explains: nothing.
  CHECK(mu_roundoff_advice(conv, 4.8e-9, 4.8e-9).empty());
  CHECK(mu_roundoff_advice(conv, 1e-10, 0.0).empty());  // no floor known (linear rows)
  CHECK(mu_roundoff_advice(failure(FailureKind::step_budget, 0.02, 1e-3, 10.0, 1000), 1e-10, 4.8e-9)
            .empty());
  // Without a cause the same failure keeps its guess at a singular configuration: a genuinely
  // singular passage still hears of it.
  CHECK(failure_suggestion(Scheme::ggl, conv, "") == failure_suggestion(Scheme::ggl, conv));
  CHECK(contains(failure_suggestion(Scheme::ggl, conv, ""), "singular configuration"));
  CHECK(contains(failure_suggestion(Scheme::ggl, collapsed, ""), "singular configuration"));
  // Kinds whose own advice guesses no singularity keep it, the cause after it.
  const std::string start =
      failure_suggestion(Scheme::ggl, failure(FailureKind::first_step, 0.0, 0.0, 1.0, 0), cause);
  CHECK(contains(start, "before its first step"));
  CHECK(contains(start, cause));
}

TEST_CASE("a run whose atol exceeds its whole motion is flagged") {
  // An SI oscillator (m = 1e4 kg, k = 1e8 N/m, a step of 1e5 N: peak 2 mm) at atol 10 was 85 to
  // 224 % off under every scheme, exit 0 and no word.
  SolveSummary summary;
  summary.max_abs_displacement = 0.002;
  const auto loose = summary.atol_warning(10.0);
  REQUIRE(loose.has_value());
  CHECK(contains(*loose,
                 "warning: atol 10 exceeds the largest displacement of the run (0.002): "
                 "the error test held none of the motion"));
  CHECK_FALSE(summary.atol_warning(1e-3).has_value());  // below the motion
  summary.max_abs_displacement = 0.0;                   // at rest: nothing to hold
  CHECK_FALSE(summary.atol_warning(10.0).has_value());
}

TEST_CASE("the loop refines a solver failure from the facts: no step taken, step at roundoff") {
  const IntegratorOptions options = quarter_outputs();
  FakeStepper at_start(kStep);
  at_start.fail_at = 1;  // the very first step
  const IntegrationError start = drive_failure(at_start, options);
  CHECK(start.kind == FailureKind::first_step);
  CHECK(start.steps == 0);
  CHECK(start.t_reached == 0.0);

  FakeStepper collapsing(kStep);
  collapsing.fail_at = 35;        // after 34 steps: t = 34/64
  collapsing.last_step = 1e-300;  // far below roundoff of t
  const IntegrationError collapsed = drive_failure(collapsing, options);
  CHECK(collapsed.kind == FailureKind::step_size_collapsed);
  CHECK(collapsed.steps == 34);
  CHECK(collapsed.t_reached == 34 * kStep);

  FakeStepper converging(kStep);
  converging.fail_at = 35;
  converging.last_step = 1e-4;  // an ordinary step: the integrator's word stands
  CHECK(drive_failure(converging, options).kind == FailureKind::convergence);
}

TEST_CASE("penalty's advice names its weight on a linear model, not on a nonlinear one") {
  // On a nonlinear model penalty is the augmented Lagrangian, its weight set from the model:
  // the advice to lower [solve] penalty's weight pointed at a key that run ignores.
  const RunFailure e = failure(FailureKind::convergence, 1.0, 1e-3, 2.0, 10);
  const std::string linear = failure_suggestion(Scheme::penalty, e);
  CHECK(contains(linear, "try a smaller [solve] penalty weight"));
  const std::string nonlinear = failure_suggestion(Scheme::penalty, e, {.nonlinear_model = true});
  CHECK_FALSE(contains(nonlinear, "try a smaller [solve] penalty weight"));
  CHECK(contains(nonlinear, "augmented Lagrangian"));
  CHECK(contains(nonlinear, "try ggl"));
  // The same through the other overload (with roundoff causes after it).
  CHECK(contains(
      failure_suggestion(Scheme::penalty, failure(FailureKind::linear_solver, 1.0, 1e-3, 2.0, 10),
                         "; causes", {.nonlinear_model = true}),
      "augmented Lagrangian"));
}

TEST_CASE("a step size at roundoff of t for 1000 steps in a row ends the run as a collapse") {
  // A collapsed integrator used to run on to the budget of steps per output (100,000 by
  // default): minutes for a run that had stopped advancing.
  const IntegratorOptions options = quarter_outputs();
  FakeStepper stalled(kStep);
  stalled.stall_at = 11;  // after 10 steps: t = 10/64
  stalled.stall_steps = 1'000'000;
  const IntegrationError e = drive_failure(stalled, options);
  CHECK(e.kind == FailureKind::step_size_collapsed);
  CHECK(e.steps == 10 + 1000);
  CHECK(contains(e.what(), "for 1000 steps in a row"));
  REQUIRE(e.raw_partial);
  CHECK(e.raw_partial->t == std::vector<double>{0.0});  // t = 10/64 is short of the first output
  // 999 such steps, then steps of 1/64 again (a cut at a discontinuity that grows back): the run
  // goes on to its end.
  FakeStepper recovering(kStep);
  recovering.stall_at = 11;
  recovering.stall_steps = 999;
  SolveSummary summary;
  const RawTrajectory out =
      drive(recovering, Eigen::VectorXd::Zero(1), Eigen::VectorXd::Ones(1), options, summary);
  CHECK(out.t.size() == 5);
}

TEST_CASE("a step budget ends the run as a failure with its kind and the rows before it") {
  IntegratorOptions options = quarter_outputs();
  options.max_steps = 25;
  FakeStepper stepper(kStep);
  const IntegrationError e = drive_failure(stepper, options);
  CHECK(e.kind == FailureKind::step_budget);
  CHECK(contains(e.what(), "25 steps in all"));
  CHECK(e.steps == 26);  // the step that went over the budget is the one that failed
  REQUIRE(e.raw_partial);
  // Rows at 0 and 1/4 (25 steps of 1/64 reach 25/64).
  CHECK(e.raw_partial->t == std::vector<double>{0.0, 0.25});
  // The 26th step succeeded before the budget ended the run: the time reached is where it
  // landed, the time the message names too.
  CHECK(e.t_reached == 26 * kStep);
  CHECK(contains(e.what(), "at t = 0.40625"));
}

TEST_CASE("a wall-time budget ends the run as a failure with its kind") {
  IntegratorOptions options = quarter_outputs();
  options.max_wall_seconds = 1e-300;  // exceeded by any step at all: no timing is asserted
  FakeStepper stepper(kStep);
  const IntegrationError e = drive_failure(stepper, options);
  CHECK(e.kind == FailureKind::wall_time_budget);
  CHECK(e.steps == 1);
  REQUIRE(e.raw_partial);
  CHECK(e.raw_partial->t.size() == 1);  // the row at t0
}

TEST_CASE("the loop reports progress through its callback once the threshold has passed") {
  IntegratorOptions options = quarter_outputs();
  options.progress_after_seconds = 0.0;  // at once, then at every step
  options.progress_every_seconds = 0.0;
  std::vector<Progress> seen;
  options.on_progress = [&](const Progress& p) { seen.push_back(p); };
  FakeStepper stepper(kStep);
  SolveSummary summary;
  const RawTrajectory out =
      drive(stepper, Eigen::VectorXd::Zero(1), Eigen::VectorXd::Ones(1), options, summary);
  CHECK(out.t.size() == 5);
  // Every step but the last (no progress line for a run that has ended): 64 steps of 1/64.
  REQUIRE(seen.size() == 63);
  for (std::size_t k = 0; k < seen.size(); ++k) {
    CHECK(seen[k].t0 == 0.0);
    CHECK(seen[k].t_end == 1.0);
    CHECK(seen[k].steps == static_cast<long>(k) + 1);
    CHECK(seen[k].t == kStep * static_cast<double>(k + 1));
    if (k > 0) CHECK(seen[k].elapsed_seconds >= seen[k - 1].elapsed_seconds);
  }
  // The default threshold (seconds) is not reached by a run this short: no call at all.
  IntegratorOptions quiet = quarter_outputs();
  int calls = 0;
  quiet.on_progress = [&](const Progress&) { ++calls; };
  quiet.progress_after_seconds = 1e9;
  FakeStepper again(kStep);
  (void)drive(again, Eigen::VectorXd::Zero(1), Eigen::VectorXd::Ones(1), quiet, summary);
  CHECK(calls == 0);
}

namespace {

/// y' = 1 at t = 0 and NaN at every later time: CVODE's recoverable retries shrink the first step
/// ten times and give up (CV_REPTD_RHSFUNC_ERR). A switch at a later time would not do: CVODE
/// creeps up to it in ever smaller steps.
class OdeBreaksAtT : public OdeProblem {
 public:
  [[nodiscard]] int size() const override { return 1; }
  void begin_segment(double /*t0*/) override {}
  void rhs(double t, ConstRef /*y*/, Ref ydot) const override {
    ydot[0] = t <= 0.0 ? 1.0 : std::numeric_limits<double>::quiet_NaN();
  }
  [[nodiscard]] bool has_projection() const override { return false; }
  bool project(double /*t*/, ConstRef /*y*/, Ref corr,
               const Eigen::VectorXd& /*settled*/) const override {
    corr.setZero();
    return true;
  }
  void project_error(Ref /*err*/) const override {}
};

}  // namespace

TEST_CASE("a CVODE failure in process: its kind from the flag's code") {
  OdeBreaksAtT problem;
  IntegratorOptions options;
  for (int k = 0; k <= 10; ++k) options.output_times.push_back(0.1 * k);
  SolveSummary summary;
  bool thrown = false;
  try {
    (void)integrate_ode(problem, Eigen::VectorXd::Zero(1), options, summary);
  } catch (const IntegrationError& e) {
    thrown = true;
    CAPTURE(std::string(e.what()));
    CHECK(contains(e.what(), "CV_"));  // the flag's name (a string CVODE allocates: freed)
    CHECK(contains(e.what(), "CV_REPTD_RHSFUNC_ERR"));
    CHECK(e.kind == FailureKind::residual_non_finite);
    CHECK(e.t_reached == 0.0);
    REQUIRE(e.raw_partial);
    CHECK(e.raw_partial->t.size() == 1);  // the row at t0
  }
  CHECK(thrown);
}

namespace {

/// y' = 1 at t = 0, a NaN residual at every later time: IDA's recoverable retries fail ten times
/// at the first step (IDA_REP_RES_ERR). (A NaN from a later time on does not make IDA fail: it
/// creeps up to that time and the loop's per-output limit ends the run, without a SUNDIALS flag;
/// the older test in test_integration_failure.cpp does that, so no flag name was ever asked for
/// in process and the sanitizer tier could not see the leaked strings.)
class DaeNanAfterStart : public DaeProblem {
 public:
  [[nodiscard]] int size() const override { return 1; }
  void begin_segment(double /*t0*/) override {}
  void residual(double t, ConstRef /*y*/, ConstRef yp, Ref r) const override {
    r[0] = t <= 0.0 ? yp[0] - 1.0 : std::numeric_limits<double>::quiet_NaN();
  }
  [[nodiscard]] const JacobianPattern& jacobian_pattern() const override { return pattern_; }
  void fill_jacobian(double /*t*/, ConstRef /*y*/, ConstRef /*yp*/, double cj,
                     JacobianMap J) const override {
    J.valuePtr()[0] = cj;
  }
  [[nodiscard]] Eigen::VectorXd differential_id() const override {
    return Eigen::VectorXd::Ones(1);
  }
  void make_consistent(double /*t*/, Eigen::VectorXd& /*y*/, Eigen::VectorXd& yp) const override {
    yp = Eigen::VectorXd::Ones(1);
  }

 private:
  JacobianPattern pattern_{1, {0, 1}, {0}};  // the one entry (0, 0)
};

}  // namespace

TEST_CASE("an IDA failure in process: its kind from the flag's code") {
  DaeNanAfterStart problem;
  IntegratorOptions options;
  for (int k = 0; k <= 10; ++k) options.output_times.push_back(0.1 * k);
  SolveSummary summary;
  bool thrown = false;
  try {
    (void)integrate(problem, Eigen::VectorXd::Zero(1), options, summary);
  } catch (const IntegrationError& e) {
    thrown = true;
    CAPTURE(std::string(e.what()));
    CHECK(contains(e.what(), "IDA_REP_RES_ERR"));  // a string IDA allocates: freed
    CHECK(e.kind == FailureKind::residual_non_finite);
    CHECK(e.t_reached == 0.0);
  }
  CHECK(thrown);
}

namespace {

std::string pendulum(const std::string& solve_keys) {
  return condyn::test::pendulum_scene(solve_keys);
}

}  // namespace

TEST_CASE("real failures: t_end = 1e300 stops at the step budget, a failure at t = 0 is a start") {
  {
    // index1 takes ordinary steps toward 1e300: the budget ends it, and the advice says how far
    // off t_end is, not that the step collapsed.
    const SceneSpec spec = parse_scene_text(
        pendulum("t_end = 1e300\noutput_step = 1e297\nscheme = \"index1\"\nmax_steps = 500\n"),
        "p.toml");
    const SolveResult result = solve(build_model(spec), spec.solve);
    const bool thrown = !result.ok();
    if (const auto& e = result.failure) {
      CAPTURE(e->message);
      CAPTURE(e->suggestion);
      CHECK(e->kind == FailureKind::step_budget);
      CHECK(e->steps == 501);
      CHECK(contains(e->suggestion, "step budget"));
      CHECK(contains(e->suggestion, "more steps"));
      CHECK_FALSE(contains(e->suggestion, "collapsed"));
      CHECK_FALSE(contains(e->suggestion, "singular"));
    }
    CHECK(thrown);
  }
  {
    // GGL asked for 15 digits with atol 1e-30: the error test fails at every trial of the first
    // step (h down to 4e-14), so IDA gives up at t = 0 with no step taken.
    SceneSpec spec = parse_scene_text(
        pendulum("t_end = 10.0\noutput_step = 0.1\nrtol = 1e-15\natol = 1e-30\n"), "p.toml");
    spec.solve.scheme = Scheme::ggl;
    const SolveResult result = solve(build_model(spec), spec.solve);
    const bool thrown = !result.ok();
    if (const auto& e = result.failure) {
      CAPTURE(e->message);
      CAPTURE(e->suggestion);
      CHECK(contains(e->message, "IDA_"));  // the flag's name (a string IDA allocates: freed)
      CHECK(e->kind == FailureKind::first_step);
      CHECK(e->t_reached == 0.0);
      CHECK(e->steps == 0);
      CHECK(contains(e->suggestion, "before its first step"));
      CHECK_FALSE(contains(e->suggestion, "singular configuration"));
      CHECK_FALSE(contains(e->suggestion, "collapsed"));
    }
    CHECK(thrown);
  }
}

TEST_CASE("a run whose steps mostly failed the error test is flagged, a normal one is not") {
  // The conical pendulum's GGL run: 248,279 steps, 245,905 failures, 0.5 % off at exit 0.
  SolveSummary s;
  s.steps = 248279;
  s.error_test_failures = 245905;
  const auto warning = s.error_test_warning();
  REQUIRE(warning.has_value());
  CHECK(*warning ==
        "warning: 245905 of 248279 steps failed the error test: the result may be off by far "
        "more than rtol; compare it with another scheme (index1 or projection)");
  // The El Centro frame at rtol 1e-8 (compare_builds): 42,614 steps, 3,721 failures.
  s.steps = 42614;
  s.error_test_failures = 3721;
  CHECK_FALSE(s.error_test_warning().has_value());
  // Half of a short run: too few steps to judge.
  s.steps = 9999;
  s.error_test_failures = 9999;
  CHECK_FALSE(s.error_test_warning().has_value());
  s.steps = 10000;
  s.error_test_failures = 5000;
  CHECK(s.error_test_warning().has_value());
}

TEST_CASE("the Newmark family's advice follows its step and its damping") {
  // A run without [solve] step was told to try a smaller step; an undamped member at index 3
  // (average acceleration) is pointed at the stabilized form or a damped member.
  const RunFailure e = failure(FailureKind::steps_per_output, 4.0, 1e-7, 10.0, 100000);
  const std::string fixed = failure_suggestion(Scheme::hht, e, {.fixed_step = true});
  CHECK(contains(fixed, "fixed [solve] step: try a smaller step"));
  CHECK_FALSE(contains(fixed, "stabilized"));
  const std::string controlled = failure_suggestion(Scheme::hht, e);
  CHECK(contains(controlled, "controlled by the method's error estimate"));
  CHECK_FALSE(contains(controlled, "fixed [solve] step"));
  const std::string undamped = failure_suggestion(Scheme::newmark, e, {.undamped_index3 = true});
  CHECK(contains(undamped, "newmark_constraints = \"stabilized\""));
  CHECK(contains(undamped, "use hht or generalized_alpha"));
}

}  // namespace test_failure_kinds
