// Issue 47 item 8, validation: a two-support bridge under multi-support excitation. A chain of
// three masses on four springs between two massless support DOFs, each support moved by its own
// recorded displacement (constraint right-hand sides of type "displacement_record"), against the
// exact solution of the same bridge whose supports follow the analytic functions the records
// were sampled from (exact_trajectory: the modal closed form, u = N q + A⁺ g(t), which never sees
// the records). Two record forms: record triples (displacement, velocity, acceleration) at both
// supports, and at one support an acceleration record with a linear drift added, integrated twice
// after the linear baseline correction.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <string>

#include "models/scene/scene_parser.hpp"
#include "tests/cli_sandbox.hpp"
#include "tests/solve_helpers.hpp"
#include "validation/references/exact_solution.hpp"

using namespace condyn;

namespace test_support_motion_validation {

using condyn::test::Sandbox;

namespace {

/// The bridge: supports sL and sR (massless), masses 1, 1.5, 1 on springs of 100, Rayleigh
/// damping (classical: the modal solution is exact). The supports' constraints are appended.
const std::string kBridge = R"([model]
type = "matrix"
dofs = ["sL", "u1", "u2", "u3", "sR"]
mass = [[0.0, 0.0, 0.0, 0.0, 0.0], [0.0, 1.0, 0.0, 0.0, 0.0], [0.0, 0.0, 1.5, 0.0, 0.0], [0.0, 0.0, 0.0, 1.0, 0.0], [0.0, 0.0, 0.0, 0.0, 0.0]]
stiffness = [[100.0, -100.0, 0.0, 0.0, 0.0], [-100.0, 200.0, -100.0, 0.0, 0.0], [0.0, -100.0, 200.0, -100.0, 0.0], [0.0, 0.0, -100.0, 200.0, -100.0], [0.0, 0.0, 0.0, -100.0, 100.0]]
damping = { rayleigh = [0.2, 0.001] }
[output]
quantities = ["displacement", "reaction"]
)";

/// rtol 1e-10, atol 1e-14 (displacements of order 0.01): as `condyn validate`'s chapter cases,
/// the global error of the variable-order BDF over about 10³ steps stays within 10³ rtol of the
/// peak.
constexpr double kRtol = 1e-10;
constexpr double kGlobalError = 1e3 * kRtol;
/// The absolute row sum of K at a support DOF (100 + 100).
constexpr double kReactionRow = 200.0;

std::string solve_block(double t_end) {
  std::ostringstream s;
  s << "[solve]\nt_end = " << t_end << "\noutput_step = 0.02\nrtol = " << kRtol
    << "\natol = 1e-14\n";
  return s.str();
}

/// The support constraint named `name` on `dof` with right-hand side `value`.
std::string support(const std::string& name, const std::string& dof, const std::string& value) {
  return "[[constraint]]\nname = \"" + name + "\"\nterms = { " + dof +
         " = 1.0 }\nvalue = " + value + "\n";
}

/// g, g', g'' of `g` sampled every `h` over [0, t_end] as a CSV "t,d,v,a" (17 digits: the
/// samples are the function's values to roundoff).
std::string sampled(const TimeFunction& g, double h, double t_end, double drift0 = 0.0,
                    double drift1 = 0.0) {
  std::ostringstream s;
  s.precision(17);
  s << "t,d,v,a\n";
  const int n = static_cast<int>(std::lround(t_end / h));
  for (int k = 0; k <= n; ++k) {
    const double t = t_end * k / n;
    s << t << "," << g.derivative(0, t) << "," << g.derivative(1, t) << ","
      << g.derivative(2, t) + drift0 + drift1 * t << "\n";
  }
  return s.str();
}

struct Errors {
  double u = 0.0, u_peak = 0.0, reaction = 0.0, reaction_peak = 0.0;
};

/// Max over output rows and DOFs of |computed − exact| for displacements and reactions, and the
/// exact peaks.
Errors errors(const Trajectory& run, const Trajectory& exact) {
  Errors e;
  REQUIRE(run.t.size() == exact.t.size());
  e.u = (run.u - exact.u).cwiseAbs().maxCoeff();
  e.u_peak = exact.u.cwiseAbs().maxCoeff();
  e.reaction = (run.reaction - exact.reaction).cwiseAbs().maxCoeff();
  e.reaction_peak = exact.reaction.cwiseAbs().maxCoeff();
  return e;
}

const std::string kLeftExact =
    R"([{ type = "polynomial", coefficients = [0.02] }, { type = "harmonic", amplitude = -0.02, omega = 3.0, phase = 1.5707963267948966 }])";
const std::string kRightExact =
    R"([{ type = "harmonic", amplitude = 0.015, omega = 2.0 }, { type = "harmonic", amplitude = -0.0075, omega = 4.0 }])";

}  // namespace

TEST_CASE("support motion validation: two-support bridge, record triples, every scheme") {
  // Left g_L = 0.02 (1 − cos 3t), right g_R = 0.015 sin 2t − 0.0075 sin 4t: both start at rest
  // (g = g' = 0 at t = 0), so the bridge starts at rest too.
  constexpr double kTEnd = 4.0, kSample = 0.02;
  Sandbox box;
  const std::string analytic = kBridge + support("left", "sL", kLeftExact) +
                               support("right", "sR", kRightExact) + solve_block(kTEnd);
  const auto exact_scene =
      condyn::test::built(parse_scene_file(box.write("exact.toml", analytic).string()));
  const TimeFunction& gl = exact_scene.model.constraints.at(0).position_value;
  const TimeFunction& gr = exact_scene.model.constraints.at(1).position_value;
  box.write("left.csv", sampled(gl, kSample, kTEnd));
  box.write("right.csv", sampled(gr, kSample, kTEnd));
  const std::string triple = R"(displacement = "d", velocity = "v", acceleration = "a" })";
  const std::string recorded =
      kBridge +
      support("left", "sL", R"({ type = "displacement_record", file = "left.csv", )" + triple) +
      support("right", "sR", R"({ type = "displacement_record", file = "right.csv", )" + triple) +
      solve_block(kTEnd);
  const auto scene =
      condyn::test::built(parse_scene_file(box.write("rec.toml", recorded).string()));
  const std::vector<double> times = scene.spec.solve.output_times();
  const Trajectory exact = exact_trajectory(exact_scene.model, times);

  // The interpolation error of the quintic Hermite on a piece of length h is at most
  // (h/2)⁶/6! max|g⁽⁶⁾| (the remainder of Hermite interpolation with three conditions at each
  // end); g_R⁽⁶⁾ ≤ 0.015·2⁶ + 0.0075·4⁶ = 31.7 and g_L⁽⁶⁾ ≤ 0.02·3⁶ = 14.6: at h = 0.02 below
  // 5e-14, far under the integration's tolerance, which it must not use up.
  const double interpolation = std::pow(kSample / 2.0, 6) / 720.0 * 31.7;
  const double tolerance_u = kGlobalError * exact.u.cwiseAbs().maxCoeff();
  REQUIRE(interpolation <= 1e-3 * tolerance_u);
  // The records move the supports as the functions do: the run's support DOFs follow them.
  for (Scheme s : {Scheme::elimination, Scheme::index1, Scheme::ggl, Scheme::baumgarte}) {
    const std::string name = to_string(s);
    CAPTURE(name);
    const SolveResult result =
        condyn::test::solved(scene.model, condyn::test::under(scene.spec.solve, s));
    REQUIRE(result.ok());
    const Errors e = errors(result.trajectory, exact);
    MESSAGE("bridge, record triples, " << name << ": max |u - exact| = " << e.u << " (peak "
                                       << e.u_peak << "), max |reaction - exact| = " << e.reaction
                                       << " (peak " << e.reaction_peak << "), "
                                       << result.summary.steps << " steps");
    CHECK(e.u_peak > 0.01);        // the supports move the bridge: not a comparison of zeros
    CHECK(e.reaction_peak > 0.1);  // and the supports push it
    CHECK(e.u <= kGlobalError * e.u_peak + interpolation);
    // At a massless support the reaction is its row of K times u (0 = f_con − K u there), whose
    // absolute row sum is 200: the displacements' error bound times 200.
    CHECK(e.reaction <= kReactionRow * (kGlobalError * e.u_peak + interpolation));
  }
}

TEST_CASE("support motion validation: an acceleration record with a drift, linear baseline") {
  // The left support follows g_L = A (1 − cos πt)² on [0, 2] (at rest at both ends, to second
  // order), given as its acceleration plus a drift 0.003 + 0.002 t (an accelerometer's offset and
  // tilt: uncorrected, it moves the support's end by 0.0087, twice the peak 4A); the right
  // support follows g_R as above, as a record triple. The run ends with the record, at t = 2.
  constexpr double kA = 0.01, kT = 2.0, kSample = 2e-4;
  Sandbox box;
  const std::string left_exact =
      R"([{ type = "polynomial", coefficients = [0.015] }, { type = "harmonic", amplitude = -0.02, omega = 3.141592653589793, phase = 1.5707963267948966 }, { type = "harmonic", amplitude = 0.005, omega = 6.283185307179586, phase = 1.5707963267948966 }])";
  const std::string analytic = kBridge + support("left", "sL", left_exact) +
                               support("right", "sR", kRightExact) + solve_block(kT);
  const auto exact_scene =
      condyn::test::built(parse_scene_file(box.write("exact.toml", analytic).string()));
  const TimeFunction& gl = exact_scene.model.constraints.at(0).position_value;
  REQUIRE(gl.derivative(0, 1.0) == doctest::Approx(4 * kA));  // (1 − cos π)² A = 4A
  box.write("left.csv", sampled(gl, kSample, kT, 0.003, 0.002));
  box.write("right.csv", sampled(exact_scene.model.constraints.at(1).position_value, 0.02, kT));
  const std::string recorded =
      kBridge +
      support(
          "left", "sL",
          R"({ type = "displacement_record", file = "left.csv", acceleration = "a", baseline = "linear" })") +
      support(
          "right", "sR",
          R"({ type = "displacement_record", file = "right.csv", displacement = "d", velocity = "v", acceleration = "a" })") +
      solve_block(kT);
  const auto scene =
      condyn::test::built(parse_scene_file(box.write("rec.toml", recorded).string()));
  const std::vector<double> times = scene.spec.solve.output_times();
  const Trajectory exact = exact_trajectory(exact_scene.model, times);

  // The record is g_L'' (plus the drift, which the baseline removes exactly: a linear part) at
  // samples h apart, linear between: its error is at most εa = h²/8 max|g_L⁽⁴⁾|, with
  // g_L⁽⁴⁾ ≤ A (2π⁴ + 8π⁴) = 10 A π⁴. Integrated twice over T it moves the support by at most
  // εa T²/2, and the baseline fitted to that error's end values by at most 4.5 εa T² more
  // (|c0| T²/2 + |c1| T³/6 ≤ 3|D| + 2|V| T with |V| ≤ εa T, |D| ≤ εa T²/2).
  const double eps_a = kSample * kSample / 8.0 * 10.0 * kA * std::pow(std::numbers::pi, 4);
  const double support_error = 5.0 * eps_a * kT * kT;
  // The masses respond to a support error δ(t) by at most its static influence (≤ 1: the
  // springs' weights) plus the resonant amplification 1/(2ζ) of the least damped mode: with
  // Rayleigh a0 = 0.2, a1 = 0.001 on the modes of 6.8, 14.1 and 16.9 rad/s (scipy.linalg.eigh of
  // the masses' K and M), ζ = a0/(2ω) + a1 ω/2 ≥ 0.0141, 1/(2ζ) ≤ 35.4; 50 is taken.
  constexpr double kAmplification = 50.0;
  const int sL = scene.model.dof_at("sL");
  for (Scheme s : {Scheme::index1, Scheme::ggl}) {
    const std::string name = to_string(s);
    CAPTURE(name);
    const SolveResult result =
        condyn::test::solved(scene.model, condyn::test::under(scene.spec.solve, s));
    REQUIRE(result.ok());
    const Errors e = errors(result.trajectory, exact);
    const double support_worst =
        (result.trajectory.u.row(sL) - exact.u.row(sL)).cwiseAbs().maxCoeff();
    MESSAGE("bridge, integrated acceleration, "
            << name << ": support error " << support_worst << " (bound " << support_error
            << "), max |u - exact| = " << e.u << " (peak " << e.u_peak << ")");
    CHECK(e.u_peak > 0.03);
    CHECK(support_worst <= support_error + kGlobalError * e.u_peak);
    CHECK(e.u <= kAmplification * support_error + kGlobalError * e.u_peak);
  }
}

}  // namespace test_support_motion_validation
