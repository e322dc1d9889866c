// Issue 10, item 4: index1 on a mechanism at a tight tolerance, against GGL (the slider-crank over
// 5 s at rtol 1e-10). The other starts of issue 10 are in test_scheme_starts.cpp.
#include <doctest/doctest.h>

#include "dae/run/solve.hpp"
#include "tests/solve_helpers.hpp"
#include "validation/references/accuracy.hpp"

using namespace condyn;

namespace test_scheme_starts_validation {

TEST_CASE("index1 on a mechanism at a tight tolerance: steps of the order of GGL's") {
  // The slider-crank at rtol 1e-10 took 316,635 steps under index1 (40,595 Newton and 39,213
  // error-test failures) against GGL's 9,870: λ was in the local error test. λ is an index-1
  // function of (u, v) whose error estimate carries the drift index1 lets grow; out of the test
  // (as under Baumgarte) index1 takes 4,643 steps and is more accurate. The bound: index1 within
  // a factor 2 of GGL's steps (it has fewer unknowns and no μ; observed 0.63).
  SceneSpec spec = test::shipped_scene("slider_crank.toml");
  spec.solve.t_end = 5.0;
  spec.solve.rtol = 1e-10;
  const test::BuiltScene scene = test::built(spec);
  const SolveResult r1 = test::solved(scene.model, test::under(scene.spec.solve, Scheme::index1));
  const SolveResult rg = test::solved(scene.model, test::under(scene.spec.solve, Scheme::ggl));
  const SolveSummary &s1 = r1.summary, &sg = rg.summary;
  const Trajectory &a = r1.trajectory, &b = rg.trajectory;
  MESSAGE("index1 " << s1.steps << " steps, ggl " << sg.steps);
  CHECK(s1.steps < 2 * sg.steps);
  // index1 drifts (nothing holds φ): its u error against GGL is the drift's, observed 6.6e-6
  // (max-norm, lengths of order 1; 3.3e-6 in the last run); before, 1.9e-4. 1e-4 = 1e6 × rtol is
  // not a multiple of rtol by principle: it separates the two (the drift of an unheld φ).
  CHECK(relative_error(a, b).displacement < 1e-4);
}

}  // namespace test_scheme_starts_validation
