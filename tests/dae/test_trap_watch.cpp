// The watch for a trapped run (dae/integrators/trap_watch.hpp) and IDA's flags as failure kinds
// (dae/integrators/ida_failure_kind.hpp).
#include <doctest/doctest.h>

#include <ida/ida.h>

#include "dae/integrators/ida_failure_kind.hpp"
#include "dae/integrators/trap_watch.hpp"

using namespace condyn;

namespace test_trap_watch {

TEST_CASE("a trapped run engages after kTrappedSteps failing steps in a row, and only then") {
  TrapWatch w;
  long steps = 0, fails = 0;
  // One more step, after a failure or not, at t = 0.1 × steps.
  const auto step = [&](bool failed) {
    ++steps;
    if (failed) ++fails;
    w.observe(steps, fails, 0.1 * static_cast<double>(steps));
  };
  // Steps that each follow a failure, one short of the count; then a clean step resets the run.
  for (int k = 0; k < kTrappedSteps - 1; ++k) step(true);
  CHECK_FALSE(w.engaged);
  step(false);
  CHECK(w.run == 0);
  for (int k = 0; k < kTrappedSteps - 1; ++k) step(true);
  CHECK_FALSE(w.engaged);
  // A restart (IDAReInit) resets the integrator's counts: the run starts again.
  w.observe(1, 1, 5.0);
  CHECK(w.run == 0);
  CHECK_FALSE(w.engaged);
  steps = 1;
  fails = 1;
  for (int k = 0; k < kTrappedSteps; ++k) step(true);
  CHECK(w.engaged);
  CHECK(w.since == doctest::Approx(0.1 * (1 + kTrappedSteps)));
  CHECK_FALSE(w.applied);  // the weight function sets it when the problem has floors
}

TEST_CASE("IDA's return flags map to the failure kinds a run reports") {
  CHECK(ida_failure_kind(IDA_TOO_MUCH_WORK) == FailureKind::steps_per_output);
  CHECK(ida_failure_kind(IDA_TOO_MUCH_ACC) == FailureKind::tolerance_too_tight);
  CHECK(ida_failure_kind(IDA_ERR_FAIL) == FailureKind::error_test);
  CHECK(ida_failure_kind(IDA_CONV_FAIL) == FailureKind::convergence);
  CHECK(ida_failure_kind(IDA_LSETUP_FAIL) == FailureKind::linear_solver);
  CHECK(ida_failure_kind(IDA_REP_RES_ERR) == FailureKind::residual_non_finite);
  CHECK(ida_failure_kind(IDA_ILL_INPUT) == FailureKind::bad_input);
  CHECK(ida_failure_kind(-12345) == FailureKind::unknown);
}

}  // namespace test_trap_watch
