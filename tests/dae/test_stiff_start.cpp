// Issue 47, item 4: the start of a stiff run. A braced wall under El Centro started IDA at 1e-7 s
// (√rtol / ω_max from its stiffest bar, or IDA's own 0.5 / ‖y'(0)‖) and refactored its condensed
// Newton matrix at every change of cj. The first step now comes from the frequency of the motion
// the run starts with (dae/formulations/model_scales.hpp, ModelScales::omega_start), and the
// condensed matrix serves while cj stays in IDA's band (dae/integrators/ida_integrator.cpp).
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <string>

#include "dae/formulations/model_scales.hpp"
#include "dae/run/solve.hpp"
#include "models/scene/scene_parser.hpp"
#include "tests/solve_helpers.hpp"

using namespace condyn;

namespace test_stiff_start {

namespace {

/// Roundoff of a Rayleigh quotient of an exact shape (a few products and one KKT solve of
/// condition about 1e8, the stiff spring over the unit mass): a relative 1e-6, far below the
/// factor of 1e4 between the two rules.
constexpr double kQuotientRoundoff = 1e-6;

/// A soft oscillator (u1: m = 1, k = 1, ω = 1) beside a stiff one (u2 between springs of 1e8 to
/// the ground and to u3, which a constraint holds at 0: ω = √2e8), with `extra` appended
/// ([[load]] and [initial] tables); [solve] at rtol 1e-6 over 2 s.
std::string soft_and_stiff(const std::string& extra) {
  return "[model]\ntype = \"matrix\"\ndofs = [\"u1\", \"u2\", \"u3\"]\n"
         "mass = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]\n"
         "stiffness = [[1.0, 0.0, 0.0], [0.0, 2e8, -1e8], [0.0, -1e8, 1e8]]\n"
         "[[constraint]]\nname = \"held\"\nterms = { u3 = 1.0 }\n"
         "[solve]\nt_end = 2.0\noutput_step = 0.1\nrtol = 1e-6\natol = 1e-9\n" +
         extra;
}

test::BuiltScene scene(const std::string& extra) {
  return test::built(parse_scene_text(soft_and_stiff(extra), "soft_and_stiff.toml"));
}

const std::string kSoftLoad =
    "[[load]]\ndof = \"u1\"\nvalue = { type = \"step\", amplitude = 1.0 }\n";

}  // namespace

TEST_CASE("the first step comes from the modes the loads excite, not the stiffest") {
  const double rtol = 1e-6, atol = 1e-9, omega_stiff = std::sqrt(2e8);
  SUBCASE("a load on the soft oscillator: its ω = 1") {
    const auto s = scene(kSoftLoad);
    const AbsoluteTolerances a = absolute_tolerances(s.model, s.spec.solve);
    CHECK(a.scales.omega_max == doctest::Approx(omega_stiff).epsilon(kQuotientRoundoff));
    CHECK(a.scales.omega_start == doctest::Approx(1.0).epsilon(kQuotientRoundoff));
    CHECK(a.scales.acceleration_start == doctest::Approx(1.0).epsilon(kQuotientRoundoff));
    // From rest at a = 1: the step over which u1 moves by atol, √(2 atol / a) = 4.5e-5, below
    // √rtol / ω_start = 1e-3. Before: √rtol / ω_max = 7.1e-8, which the higher-index schemes
    // keep (first_step).
    CHECK(a.first_step_from_motion ==
          doctest::Approx(std::sqrt(2.0 * atol)).epsilon(kQuotientRoundoff));
    CHECK(a.first_step ==
          doctest::Approx(std::sqrt(rtol) / omega_stiff).epsilon(kQuotientRoundoff));
  }
  SUBCASE("an initial velocity of the soft oscillator, no load: its ω, no acceleration") {
    const auto s = scene("[initial]\nvelocity = { u1 = 1.0 }\n");
    const AbsoluteTolerances a = absolute_tolerances(s.model, s.spec.solve);
    CHECK(a.scales.acceleration_start == 0.0);
    CHECK(a.first_step_from_motion == doctest::Approx(std::sqrt(rtol)).epsilon(kQuotientRoundoff));
  }
  SUBCASE("a load on the stiff one: its ω") {
    const auto s = scene("[[load]]\ndof = \"u2\"\nvalue = { type = \"step\", amplitude = 1.0 }\n");
    const AbsoluteTolerances a = absolute_tolerances(s.model, s.spec.solve);
    CHECK(a.first_step_from_motion ==
          doctest::Approx(std::sqrt(rtol) / omega_stiff).epsilon(kQuotientRoundoff));
  }
  SUBCASE("at rest, no load: nothing starts the motion, the stiffest frequency as before") {
    const auto s = scene("");
    const AbsoluteTolerances a = absolute_tolerances(s.model, s.spec.solve);
    CHECK(a.scales.omega_start == 0.0);
    CHECK(a.first_step_from_motion ==
          doctest::Approx(std::sqrt(rtol) / omega_stiff).epsilon(kQuotientRoundoff));
  }
}

TEST_CASE("IDA takes the first step guessed under elimination, and GGL its own") {
  // Before, only the higher-index schemes passed one (√rtol / ω_max, which they keep):
  // elimination started from IDA's own 0.5 / ‖y'(0)‖ (index1 and Baumgarte still do).
  const auto s = scene(kSoftLoad);
  const AbsoluteTolerances a = absolute_tolerances(s.model, s.spec.solve);
  RunHooks hooks;
  hooks.record_steps = true;
  for (const Scheme scheme : {Scheme::elimination, Scheme::ggl}) {
    CAPTURE(to_string(scheme));
    const double guess = scheme == Scheme::elimination ? a.first_step_from_motion : a.first_step;
    const SolveResult r = test::solved(s.model, test::under(s.spec.solve, scheme), hooks);
    REQUIRE(!r.trajectory.steps.empty());
    // The first step is the guess, accepted: no error-test failure before it. IDA's own was
    // 2.2e-5 of it here (0.5 / ‖y'(0)‖, the step over which v changes by half its atol).
    CHECK(r.trajectory.steps.front().t == doctest::Approx(guess).epsilon(kQuotientRoundoff));
  }
}

TEST_CASE("the condensed Newton matrix serves while cj stays in IDA's band") {
  // A damped three-storey shear frame (storey masses 1, stiffnesses 1e3 to 3e3) under a harmonic
  // load, under elimination with the condensed Newton solve and with IDA's own matrix (KLU):
  // IDA renews its matrix when cj leaves [0.6, 1.67] or Newton fails, the condensed one when cj
  // leaves [0.6, 1.4]. Before, the condensed one was refactored at every change of cj: 1.5
  // times as often as IDA's on models/scenes/shear_frame_el_centro.toml, 2.3 times here (86
  // against 37). Now 1.07 and 1.08 (40 against 37). Bound: 1.25, between them.
  constexpr double kSetupRatio = 1.25;
  const std::string frame =
      "[model]\ntype = \"matrix\"\ndofs = [\"u1\", \"u2\", \"u3\"]\n"
      "mass = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]\n"
      "stiffness = [[5e3, -2e3, 0.0], [-2e3, 3e3, -1e3], [0.0, -1e3, 1e3]]\n"
      "damping = { rayleigh = [0.5, 1e-3] }\n"
      "[[load]]\ndof = \"u3\"\nvalue = { type = \"harmonic\", amplitude = 1.0, omega = 3.0 }\n"
      "[solve]\nt_end = 10.0\noutput_step = 0.1\nrtol = 1e-8\natol = 1e-10\n"
      "scheme = \"elimination\"\n";
  auto s = test::built(parse_scene_text(frame, "frame.toml"));
  s.spec.solve.condensed_newton = false;
  const SolveResult full = test::solved(s.model, s.spec.solve);
  s.spec.solve.condensed_newton = true;
  const SolveResult condensed = test::solved(s.model, s.spec.solve);
  CAPTURE(full.summary.jacobian_evals);
  CAPTURE(full.summary.steps);
  CAPTURE(condensed.summary.jacobian_evals);
  CAPTURE(condensed.summary.steps);
  CHECK(condensed.summary.jacobian_evals <=
        static_cast<long>(kSetupRatio * static_cast<double>(full.summary.jacobian_evals)));
}

}  // namespace test_stiff_start
