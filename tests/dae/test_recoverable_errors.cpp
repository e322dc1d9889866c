// An equation that cannot be evaluated at a trial state (dae/interface/recoverable_error.hpp) makes
// the integrator cut its step, not end the run: the trampolines return +1 for a RecoverableError.
#include <doctest/doctest.h>

#include <cmath>

#include "dae/integrators/cvode_integrator.hpp"
#include "dae/integrators/step_driver.hpp"
#include "dae/interface/ode_problem.hpp"
#include "dae/interface/recoverable_error.hpp"

using namespace condyn;

namespace test_recoverable_errors {

namespace {

/// y' = −y, whose right-hand side refuses the trial states of its first `refusals` calls after
/// t = 0 (a singular KKT system at a guessed configuration, say), then evaluates normally.
class OdeRefusesSomeTrials : public OdeProblem {
 public:
  explicit OdeRefusesSomeTrials(int refusals) : refusals_(refusals) {}
  [[nodiscard]] int size() const override { return 1; }
  void begin_segment(double /*t0*/) override {}
  void rhs(double t, ConstRef y, Ref ydot) const override {
    if (t > 0.0 && refusals_ > 0) {
      --refusals_;
      throw RecoverableError("singular at this trial state");
    }
    ydot[0] = -y[0];
  }
  [[nodiscard]] bool has_projection() const override { return false; }
  bool project(double /*t*/, ConstRef /*y*/, Ref corr,
               const Eigen::VectorXd& /*settled*/) const override {
    corr.setZero();
    return true;
  }
  void project_error(Ref /*err*/) const override {}

 private:
  mutable int refusals_;
};

IntegratorOptions unit_interval() {
  IntegratorOptions options;
  options.rtol = 1e-8;
  options.atol = 1e-10;
  for (int k = 0; k <= 10; ++k) options.output_times.push_back(0.1 * k);
  return options;
}

}  // namespace

TEST_CASE("a trial state the equations refuse once: the step is cut and the run goes on") {
  OdeRefusesSomeTrials problem(1);
  SolveSummary summary;
  const RawTrajectory out =
      integrate_ode(problem, Eigen::VectorXd::Ones(1), unit_interval(), summary);
  REQUIRE(out.t.size() == 11);
  // The exact solution e^{-t}: a multiple of rtol covers the global error of a 1e-8 run.
  CHECK(std::abs(out.y.back()[0] - std::exp(-1.0)) < 100 * 1e-8);
}

TEST_CASE("trial states refused again and again: a failure quoting the equations' complaint") {
  OdeRefusesSomeTrials problem(1000);
  SolveSummary summary;
  bool thrown = false;
  try {
    (void)integrate_ode(problem, Eigen::VectorXd::Ones(1), unit_interval(), summary);
  } catch (const IntegrationError& e) {
    thrown = true;
    CHECK(e.kind == FailureKind::residual_non_finite);
    CHECK(std::string(e.what()).find("singular at this trial state") != std::string::npos);
  }
  CHECK(thrown);
}

}  // namespace test_recoverable_errors
