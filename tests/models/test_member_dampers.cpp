// Members' rest lengths and axial dampers on truss models (issue 44, item 4): `length` (a bar's
// rest length, a rigid member's length) and `c` (a dashpot along a bar), in the large-displacement
// system (exact tangents) and the linear model (its small-displacement C); Rayleigh damping beside
// rigid members (a0 M and dashpots of a1 EA/L); the refusals.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "dae/run/solve.hpp"
#include "models/assembly/build_model.hpp"
#include "models/scene/scene_parser.hpp"
#include "tests/compare.hpp"
#include "tests/scene_errors.hpp"
#include "tests/scene_text.hpp"
#include "tests/solve_helpers.hpp"
#include "tests/system_check.hpp"

using namespace condyn;

namespace test_member_dampers {

using condyn::test::replace;

namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

Model model_of(const std::string& text) { return build_model(parse_scene_text(text, "m.toml")); }

std::string build_error(const std::string& text) { return test::build_error(text, "m.toml"); }

const std::string kSolve = "[solve]\nt_end = 6.0\noutput_step = 0.1\nrtol = 1e-10\natol = 1e-12\n";

/// A pendulum with a spring: a rigid rod of length 1.1 (its nodes 1 m apart: the start is found
/// by projection) from the support to node 2, a pre-stressed damped bar (rest length 0.9, nodes
/// 1 m apart) from node 2 to node 3, gravity, and mass-proportional Rayleigh damping.
const std::string kDampedSpringPendulum = R"([model]
type = "truss2d"
geometry = "nonlinear"
nodes = [[0.0, 0.0], [1.0, 0.0], [1.0, -1.0]]
masses = [0.0, 1.0, 0.5]
supports = [1]
members = [
  { nodes = [1, 2], rigid = true, length = 1.1 },
  { nodes = [2, 3], EA = 100.0, length = 0.9, c = 0.5 },
]
gravity = [0.0, -9.81]
damping = { rayleigh = [0.05, 0.002] }
[initial]
project = true
displacement = { ux3 = 0.1 }
)";

/// The same in 3D, with two bars (one undamped) and the rod at its nodes' distance.
const std::string kSpatial = R"([model]
type = "truss3d"
geometry = "nonlinear"
nodes = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, -1.0, 0.5], [0.0, -1.0, 0.0]]
masses = [0.0, 1.0, 0.5, 2.0]
supports = [1]
members = [
  { nodes = [1, 2], rigid = true },
  { nodes = [2, 3], EA = 100.0, length = 1.3, c = 0.5 },
  { nodes = [3, 4], EA = 80.0, c = 2.0 },
  { nodes = [1, 4], EA = 60.0, length = 0.7 },
]
gravity = [0.0, -9.81, 0.0]
)";

/// Small-displacement bars beside a rigid member: constant K and C in the point-mass system.
const std::string kLinearWithRod = R"([model]
type = "truss2d"
nodes = [[0.0, 0.0], [1.0, 0.0], [1.0, -1.0]]
masses = [0.0, 1.0, 0.5]
supports = [1]
members = [{ nodes = [1, 2], rigid = true }, { nodes = [2, 3], EA = 100.0, c = 0.5 }]
damping = { rayleigh = [0.05, 0.002] }
)";

/// A state away from the start: u0 plus a perturbation, nonzero velocities (the dashpots work),
/// accelerations and multipliers.
struct State {
  Eigen::VectorXd u, v, a, w;
};
State generic_state(const Model& model) {
  const int n = model.dofs(), m = model.constraint_count();
  return {model.u0 + 0.05 * Eigen::VectorXd::LinSpaced(n, -1.0, 1.3),
          Eigen::VectorXd::LinSpaced(n, 0.7, -0.4), Eigen::VectorXd::LinSpaced(n, -1.1, 0.9),
          Eigen::VectorXd::LinSpaced(m, 0.8, -1.7)};
}

/// x(t) − x_eq of m x'' + c x' + k (x − x_eq) = 0 from x − x_eq = y0 at rest (underdamped).
double damped_oscillator(double m, double c, double k, double y0, double t) {
  const double w = std::sqrt(k / m), z = c / (2.0 * std::sqrt(k * m));
  const double wd = w * std::sqrt(1.0 - z * z);
  return y0 * std::exp(-z * w * t) * (std::cos(wd * t) + z * w / wd * std::sin(wd * t));
}

/// The largest |ux2(t) − x_eq − closed form| of a run.
double oscillator_error(const SolveResult& r, int dof, double x_eq, double m, double c, double k,
                        double y0) {
  double worst = 0.0;
  for (std::size_t i = 0; i < r.trajectory.t.size(); ++i) {
    const double exact = x_eq + damped_oscillator(m, c, k, y0, r.trajectory.t[i]);
    worst = std::max(worst, std::abs(r.trajectory.u(dof, static_cast<Eigen::Index>(i)) - exact));
  }
  return worst;
}

}  // namespace

TEST_CASE("member dampers and rest lengths: every derivative agrees with finite differences") {
  for (const std::string& text : {kDampedSpringPendulum, kSpatial, kLinearWithRod}) {
    CAPTURE(text);
    const Model model = model_of(text + kSolve);
    REQUIRE(model.is_nonlinear());
    const State s = generic_state(model);
    const auto system = model.evaluator();
    // The dashpots act: a damping block that the check below compares, not an empty one.
    REQUIRE(system->damping(0.3, s.u, s.v).norm() > 0.1);
    const auto problems = test::check_system_derivatives(*model.system, 0.3, s.u, s.v, s.a, s.w);
    for (const auto& p : problems) FAIL_CHECK(p);
    CHECK(problems.empty());
  }
}

TEST_CASE("a pre-stressed bar: its force at the reference positions is EA (l − L)/L") {
  // The spatial scene's bar 1-4 (EA 60, rest 0.7, nodes 1 m apart along y) pulls node 4
  // (DOFs 9..11) towards node 1 with EA (1 − 0.7)/0.7; at rest only gravity acts beside it, and
  // the dashpot on bar 3-4 adds nothing. Roundoff of a few operations on values of 26: 8 eps.
  const Model model = model_of(kSpatial + kSolve);
  const auto system = model.evaluator();
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(model.dofs());
  Eigen::VectorXd f(model.dofs());
  system->force(0.0, zero, zero, f);
  const double pull = 60.0 * (1.0 - 0.7) / 0.7;
  CHECK(std::abs(f[10] - (pull - 2.0 * 9.81)) < 8 * kEps * pull);
  // Its strain energy from the rest length: ½ EA/L (l − L)², with the other bar's (rest 1.3,
  // nodes √1.25 apart) beside it, and gravity's potential 0 at the reference positions.
  const double stretch = std::sqrt(1.25) - 1.3;
  const double expected = 0.5 * 60.0 / 0.7 * 0.09 + 0.5 * 100.0 / 1.3 * stretch * stretch;
  const auto parts = system->energy_parts(0.0, zero, zero);
  REQUIRE(parts.has_value());
  CHECK(std::abs(parts->potential - expected) < 8 * kEps * expected);
  CHECK(parts->dissipation_power == 0.0);  // at rest
}

TEST_CASE("a damped spring-mass with a rest length: frequency and decay of the closed form") {
  // Mass 2 on a bar (EA 40, rest length 0.8) from a support 1 m away, dashpot c = 0.8: along its
  // axis the bar is exactly the linear oscillator 2 x'' + 0.8 x' + (40/0.8)(x − x_eq) = 0 with
  // x_eq = 0.8 − 1 (ω = 5, ζ = 0.04, about 5 periods), started pre-stressed at x = 0 from rest.
  // Integrated at rtol 1e-10: the error is the integration's, a few hundred rtol times the
  // amplitude over the run; 1e3 rtol of it bounds it.
  const std::string text = R"([model]
type = "truss2d"
geometry = "nonlinear"
nodes = [[0.0, 0.0], [1.0, 0.0]]
masses = [0.0, 2.0]
supports = [1]
members = [{ nodes = [1, 2], EA = 40.0, length = 0.8, c = 0.8 }]
)" + kSolve;
  const test::BuiltScene built = test::built(parse_scene_text(text, "m.toml"));
  constexpr double kAmplitude = 0.2, kTolerance = 1e3 * 1e-10 * kAmplitude;
  for (const Scheme scheme : {Scheme::ggl, Scheme::index1, Scheme::index3, Scheme::projection}) {
    CAPTURE(to_string(scheme));
    const SolveResult r = test::solved(built.model, test::under(built.spec.solve, scheme));
    const double error = oscillator_error(r, 2, -0.2, 2.0, 0.8, 50.0, kAmplitude);
    MESSAGE(std::string(to_string(scheme)) << ": off the closed form by " << error);
    CHECK(error < kTolerance);
    // Against the undamped frequency or no decay the same comparison fails by far: the decay
    // e^(−ζωt) is 0.3 at t = 6.
    CHECK(oscillator_error(r, 2, -0.2, 2.0, 0.0, 50.0, kAmplitude) > 1e3 * kTolerance);
  }
}

TEST_CASE("a damped bar in the linear model: its small-displacement C and the closed form") {
  // The same bar without a rest length (k = EA/L = 40), geometry linear: C = c e eᵀ on the DOFs
  // of its nodes, and x(t) the damped oscillator from x = 0.1.
  const std::string text = R"([model]
type = "truss2d"
nodes = [[0.0, 0.0], [1.0, 0.0]]
masses = [0.0, 2.0]
supports = [1]
members = [{ nodes = [1, 2], EA = 40.0, c = 0.8 }]
[initial]
displacement = { ux2 = 0.1 }
)" + kSolve;
  const test::BuiltScene built = test::built(parse_scene_text(text, "m.toml"));
  REQUIRE_FALSE(built.model.is_nonlinear());
  Eigen::MatrixXd expected = Eigen::MatrixXd::Zero(4, 4);
  expected(0, 0) = expected(2, 2) = 0.8;
  expected(0, 2) = expected(2, 0) = -0.8;
  CONDYN_CHECK_CLOSE(Eigen::MatrixXd(built.model.C), expected, 0.0);
  constexpr double kAmplitude = 0.1, kTolerance = 1e3 * 1e-10 * kAmplitude;
  for (const Scheme scheme : {Scheme::elimination, Scheme::ggl}) {
    CAPTURE(to_string(scheme));
    const SolveResult r = test::solved(built.model, test::under(built.spec.solve, scheme));
    const double error = oscillator_error(r, 2, 0.0, 2.0, 0.8, 40.0, kAmplitude);
    MESSAGE(std::string(to_string(scheme)) << ": off the closed form by " << error);
    CHECK(error < kTolerance);
  }
  // Rayleigh damping adds to the dashpot: C = a0 M + a1 K + c e eᵀ (entries of size 1: 8 eps).
  const Model rayleigh =
      model_of(replace(text, "[initial]", "damping = { rayleigh = [0.5, 0.02] }\n[initial]"));
  const Eigen::MatrixXd sum =
      0.5 * Eigen::MatrixXd(rayleigh.M) + 0.02 * Eigen::MatrixXd(*rayleigh.K) + expected;
  CONDYN_CHECK_CLOSE(Eigen::MatrixXd(rayleigh.C), sum, 8 * kEps);
}

TEST_CASE("Rayleigh damping beside rigid members: a0 M and dashpots a1 EA/L along the bars") {
  // At the unloaded reference configuration (no pre-stress) the system's C is the linear model's
  // a0 M + a1 K (K the bars' small-displacement stiffness); in the linear-geometry scene it stays
  // that. Entries of size 1: a few roundings, 8 eps.
  const std::string pendulum = replace(
      replace(replace(kDampedSpringPendulum, ", length = 1.1", ""), ", length = 0.9, c = 0.5", ""),
      "[initial]\nproject = true\ndisplacement = { ux3 = 0.1 }\n", "");
  for (const std::string& text : {pendulum, replace(kLinearWithRod, ", c = 0.5", "")}) {
    CAPTURE(text);
    const Model model = model_of(text + kSolve);
    REQUIRE(model.is_nonlinear());
    // The bar 2-3 along y (DOFs 3 and 5): a1 EA/L = 0.2.
    Eigen::MatrixXd expected = Eigen::MatrixXd::Zero(6, 6);
    expected.diagonal() << 0.0, 0.0, 0.05, 0.05, 0.025, 0.025;
    expected(3, 3) += 0.2;
    expected(5, 5) += 0.2;
    expected(3, 5) = expected(5, 3) = -0.2;
    const auto system = model.evaluator();
    const Eigen::VectorXd zero = Eigen::VectorXd::Zero(6);
    CONDYN_CHECK_CLOSE(Eigen::MatrixXd(system->damping(0.0, zero, zero)), expected, 8 * kEps);
    CONDYN_CHECK_CLOSE(Eigen::MatrixXd(model.C), expected, 8 * kEps);
  }
}

TEST_CASE("member length and damper errors name the key and the problem") {
  const std::string head = R"([model]
type = "truss2d"
geometry = "nonlinear"
nodes = [[0.0, 0.0], [1.0, 0.0]]
masses = [0.0, 1.0]
supports = [1]
)";
  const auto error_of = [&](const std::string& members, const std::string& h) {
    return build_error(h + "members = [" + members + "]\n" + kSolve);
  };
  const auto refused = [&](const std::string& members, const std::string& needle,
                           const std::string& h) {
    const std::string e = error_of(members, h);
    CAPTURE(e);
    CHECK(e.find(needle) != std::string::npos);
  };
  refused("{ nodes = [1, 2], EA = 1.0, c = -0.5 }",
          "m.toml:7: model.members[1].c: must be >= 0 (got -0.5", head);
  refused("{ nodes = [1, 2], EA = 1.0, length = 0.0 }",
          "m.toml:7: model.members[1].length: must be > 0 (got 0)", head);
  refused("{ nodes = [1, 2], rigid = true, length = -1.0 }",
          "m.toml:7: model.members[1].length: must be > 0 (got -1)", head);
  refused("{ nodes = [1, 2], rigid = true, c = 1.0 }",
          "m.toml:7: model.members[1].c: a rigid member keeps its length", head);
  refused("{ nodes = [1, 2], EA = 1.0, c = \"big\" }", "model.members[1].c: ", head);
  const std::string linear = replace(head, "geometry = \"nonlinear\"\n", "");
  refused("{ nodes = [1, 2], EA = 1.0, length = 0.9 }",
          "m.toml:6: model.members[1].length: a bar's rest length needs geometry = \"nonlinear\"",
          linear);
  // A rigid member's length differing from its nodes' distance: the start violates it.
  refused("{ nodes = [1, 2], rigid = true, length = 0.9 }",
          "initial displacements violate constraint 'rigid_1_2'", head);
  // Modal damping would replace the dampers' C.
  refused("{ nodes = [1, 2], EA = 1.0, c = 1.0 }",
          "model.damping.modal: modal damping gives every mode its ratio, and the members' "
          "dampers (c) would be lost",
          linear + "damping = { modal = 0.05 }\n");
  // Accepted: a rigid member's length in linear geometry, an undamped c = 0.
  CHECK(error_of("{ nodes = [1, 2], rigid = true, length = 1.0 }", linear).empty());
  CHECK(error_of("{ nodes = [1, 2], EA = 1.0, c = 0.0 }", linear).empty());
}

}  // namespace test_member_dampers
