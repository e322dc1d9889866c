#pragma once
/// The watch for a trapped run (dae/integrators/ida_integrator.cpp's error weights): a run whose
/// every step comes after an error-test failure, for kTrappedSteps steps in a row, engages the
/// floors under |y_i| in the error weights (DaeProblem::error_scale_floors) for the rest of the
/// run (docs/schemes.md, "Error weights on rows").

namespace condyn {

/// Steps in a row, each after an error-test failure, that engage the weights' floors. The
/// trapped runs seen (a conical pendulum in steady rotation under GGL and index3) went on like
/// that for 10⁵ steps, at order 1, or at order 3 with atol 1e-13; the scenes of models/ and
/// validation/ never reach 25 under GGL or index3 at rtol 1e-4 to 1e-10 (atol rtol/100).
inline constexpr int kTrappedSteps = 25;

struct TrapWatch {
  long steps = -1, fails = 0;  ///< the integrator's step and error-test failure counts last seen
  int run = 0;                 ///< steps in a row, each after a failure
  bool engaged = false;
  bool applied = false;  ///< engaged, and the problem has floors
  double since = 0.0;    ///< the time they were engaged

  /// Called once per step with the integrator's counts (cumulative; lower than last time after a
  /// restart, which resets the run) at time t: engages when the last kTrappedSteps steps were
  /// each after a failure.
  void observe(long step_count, long fail_count, double t) {
    if (step_count == steps + 1) {
      run = fail_count > fails ? run + 1 : 0;
    } else if (step_count < steps) {
      run = 0;
    }
    steps = step_count;
    fails = fail_count;
    if (run >= kTrappedSteps) {
      engaged = true;
      since = t;
    }
  }
};

}  // namespace condyn
