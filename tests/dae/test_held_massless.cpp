// Massless DOFs held by stiffness (issue 13, dae/interface/held_massless.hpp): every scheme that
// integrates a DAE integrates them, and agrees with the same model condensed by hand.

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "dae/interface/held_massless.hpp"
#include "dae/run/solve.hpp"
#include "models/scene/scene_parser.hpp"
#include "tests/scene_text.hpp"
#include "tests/solve_helpers.hpp"

using namespace condyn;

namespace test_held_massless {

namespace {

/// A chain ground-u1-u2-u3-u4 of springs 200, 100 (u1-u2: the row of u1 is 300 with its ground
/// spring), 200, 150; u2 has no mass and carries 5 sin 7t; a step of 3 on u4 at t = 0.1; the
/// row u1 − 0.5 u4 = 0 ties u1 to u4. u2's row is algebraic:
///   300 u2 − 100 u1 − 200 u3 = 5 sin 7t.
const std::string kChain = R"([model]
type = "matrix"
dofs = ["u1", "u2", "u3", "u4"]
mass = [[2.0, 0, 0, 0], [0, 0.0, 0, 0], [0, 0, 1.0, 0], [0, 0, 0, 1.5]]
stiffness = [[300.0, -100.0, 0, 0], [-100.0, 300.0, -200.0, 0], [0, -200.0, 350.0, -150.0], [0, 0, -150.0, 150.0]]
[[load]]
dof = "u2"
value = { type = "harmonic", amplitude = 5.0, omega = 7.0 }
[[load]]
dof = "u4"
value = { type = "step", amplitude = 3.0, start = 0.1 }
[[constraint]]
name = "tie"
terms = { u1 = 1.0, u4 = -0.5 }
[solve]
t_end = 2.0
output_step = 0.1
rtol = 1e-10
atol = 1e-12
)";

/// The chain with u2 condensed by hand: u2 = (5 sin 7t + 100 u1 + 200 u3)/300, so
/// K̃ = K_rr − K_r2 K_2r / 300 (rows u1, u3, u4): 300 − 100²/300 = 800/3, −100·200/300 = −200/3,
/// 350 − 200²/300 = 650/3; the load on u2 goes to u1 and u3 as 100/300 and 200/300 of it.
const std::string kCondensed = R"([model]
type = "matrix"
dofs = ["u1", "u3", "u4"]
mass = [[2.0, 0, 0], [0, 1.0, 0], [0, 0, 1.5]]
stiffness = [[266.66666666666669, -66.666666666666671, 0], [-66.666666666666671, 216.66666666666669, -150.0], [0, -150.0, 150.0]]
[[load]]
dof = "u1"
value = { type = "harmonic", amplitude = 1.6666666666666667, omega = 7.0 }
[[load]]
dof = "u3"
value = { type = "harmonic", amplitude = 3.3333333333333335, omega = 7.0 }
[[load]]
dof = "u4"
value = { type = "step", amplitude = 3.0, start = 0.1 }
[[constraint]]
name = "tie"
terms = { u1 = 1.0, u4 = -0.5 }
[solve]
t_end = 2.0
output_step = 0.1
rtol = 1e-10
atol = 1e-12
)";

RunHooks with_accelerations() {
  RunHooks hooks;
  hooks.accelerations = true;
  return hooks;
}

double max_abs(const Eigen::MatrixXd& m) { return m.size() ? m.cwiseAbs().maxCoeff() : 0.0; }

}  // namespace

TEST_CASE("held_massless: null without massless DOFs, the held ones found from a system") {
  const auto chain = test::built(parse_scene_text(kChain, "chain.toml"));
  const auto held = held_massless_of(*chain.model.system);
  REQUIRE(held);
  CHECK(held->dofs() == std::vector<int>{1});
  CHECK(held_massless_of(chain.model));
  const auto condensed = test::built(parse_scene_text(kCondensed, "condensed.toml"));
  CHECK_FALSE(held_massless_of(*condensed.model.system));
  CHECK_FALSE(held_massless_of(condensed.model));
  const Model& m = condensed.model;
  CHECK_FALSE(held_massless(m.M, m.C, *m.K, m.A));
}

TEST_CASE("a massless DOF held by stiffness: every DAE scheme agrees with the hand condensation") {
  const auto ref = test::built(parse_scene_text(kCondensed, "condensed.toml"));
  const SolveResult exact = test::solved(
      ref.model, test::under(ref.spec.solve, Scheme::elimination), with_accelerations());
  const Trajectory& c = exact.trajectory;
  // Rows of the full model's u1, u3, u4 in the condensed one.
  const int rows[3][2] = {{0, 0}, {2, 1}, {3, 2}};
  const auto full = test::built(parse_scene_text(kChain, "chain.toml"));
  struct Case {
    Scheme scheme;
    bool mixed;  ///< the tie eliminated, the massless DOF a master of the reduced multiplier DAE
  };
  for (const Case run :
       {Case{Scheme::index1, false}, Case{Scheme::baumgarte, false}, Case{Scheme::ggl, false},
        Case{Scheme::index2, false}, Case{Scheme::index3, false}, Case{Scheme::elimination, false},
        Case{Scheme::penalty, false}, Case{Scheme::projection, false}, Case{Scheme::ggl, true},
        Case{Scheme::index1, true}}) {
    const Scheme scheme = run.scheme;
    CAPTURE(std::string(to_string(scheme)));
    CAPTURE(run.mixed);
    const bool penalty = scheme == Scheme::penalty;
    SolveSpec settings = test::under(full.spec.solve, scheme);
    if (run.mixed) settings.treatment = SolveSpec::Treatment::mixed;
    const SolveResult r = test::solved(full.model, settings, with_accelerations());
    const Trajectory& d = r.trajectory;
    REQUIRE(d.t.size() == c.t.size());
    double du = 0.0, dv = 0.0, da = 0.0, dr = 0.0, row2 = 0.0, vel2 = 0.0, acc2 = 0.0;
    for (std::size_t k = 0; k < d.t.size(); ++k) {
      const auto col = static_cast<Eigen::Index>(k);
      const double t = d.t[k];
      for (const auto& p : rows) {
        du = std::max(du, std::abs(d.u(p[0], col) - c.u(p[1], col)));
        dv = std::max(dv, std::abs(d.v(p[0], col) - c.v(p[1], col)));
        da = std::max(da, std::abs(d.acceleration(p[0], col) - c.acceleration(p[1], col)));
        dr = std::max(dr, std::abs(d.reaction(p[0], col) - c.reaction(p[1], col)));
      }
      // u2's row and its first and second time derivatives.
      const double f = 5.0 * std::sin(7.0 * t), fd = 35.0 * std::cos(7.0 * t), fdd = -49.0 * f;
      row2 = std::max(
          row2, std::abs(300.0 * d.u(1, col) - 100.0 * d.u(0, col) - 200.0 * d.u(2, col) - f));
      vel2 = std::max(
          vel2, std::abs(300.0 * d.v(1, col) - 100.0 * d.v(0, col) - 200.0 * d.v(2, col) - fd));
      acc2 =
          std::max(acc2, std::abs(300.0 * d.acceleration(1, col) - 100.0 * d.acceleration(0, col) -
                                  200.0 * d.acceleration(2, col) - fdd));
    }
    // Scales: |u| <= 0.16, |v| <= 1.3, |u''| <= 4.1, |reaction| <= 9.7. Observed:
    // u 2.5e-10 (elimination) to 2.8e-9 (index3); the condensed model itself under ggl differs
    // from its elimination run by 7.4e-10 in u and 1.6e-7 in u''. Penalty holds the tie only to
    // its weight (w = 3.5e6): u 5e-6, v 4.9e-4; its accelerations and reactions ring with the
    // penalty spring after the step (0.75 and 1.5), so they are not compared.
    CHECK(du <= (penalty ? 5e-5 : 1e-8));
    CHECK(dv <= (penalty ? 5e-3 : 1e-7));
    if (!penalty) {
      CHECK(da <= 2e-6);
      CHECK(dr <= 2e-7);
    }
    // u2's row, and the rows differentiated once and twice, hold at every output to roundoff:
    // the rows settle u2 and v2 from the other DOFs (HeldMassless::settle; measured 1.4e-17 and
    // 5.6e-17; before, v2 was the BDF derivative of u2, 2.6e-8 off at the step) and the
    // acceleration comes from the row differentiated twice (dae/formulations/acceleration.hpp).
    CHECK(row2 <= 300.0 * 1e-14);
    CHECK(vel2 <= 300.0 * 1e-14);
    CHECK(acc2 <= 300.0 * 1e-14);
  }
  // The condensed reference's own u, for scale: the comparison is not between zeros.
  CHECK(max_abs(c.u) > 0.1);
  CHECK(max_abs(c.reaction) > 5.0);
}

TEST_CASE("a damped massless DOF: first order in u, every DAE scheme agrees, energy closes") {
  // Rayleigh damping gives u2 damping of its own (a1 k22): its row is 0.6 u2' + 300 u2 + ... .
  const std::string damped =
      test::replace(kChain, "[[load]]", "damping = { rayleigh = [0.1, 0.002] }\n[[load]]") +
      "[output]\nquantities = [\"displacement\", \"energy\"]\n";
  const auto s = test::built(parse_scene_text(damped, "damped.toml"));
  REQUIRE(s.model.has_damping());
  const SolveResult base =
      test::solved(s.model, test::under(s.spec.solve, Scheme::elimination), with_accelerations());
  const Trajectory& e = base.trajectory;
  for (Scheme scheme : {Scheme::index1, Scheme::baumgarte, Scheme::ggl, Scheme::index2,
                        Scheme::index3, Scheme::penalty, Scheme::projection}) {
    CAPTURE(std::string(to_string(scheme)));
    RunHooks hooks = with_accelerations();
    hooks.energy_balance = true;
    const SolveResult r = test::solved(s.model, test::under(s.spec.solve, scheme), hooks);
    const Trajectory& d = r.trajectory;
    REQUIRE(d.t.size() == e.t.size());
    // Observed <= 4e-9 (rtol 1e-10), scale 0.15; penalty to its weight.
    CHECK(max_abs(d.u - e.u) <= (scheme == Scheme::penalty ? 5e-5 : 2e-8));
    for (std::size_t k = 0; k < d.t.size(); ++k) {
      const auto col = static_cast<Eigen::Index>(k);
      // u2's row, C_2· v + K_2· u = f_2, holds at every row to roundoff (v2 settled on it).
      const Eigen::VectorXd r2 =
          s.model.C * d.v.col(col) + *s.model.K * d.u.col(col) - s.model.applied_forces(d.t[k]);
      CHECK(std::abs(r2[1]) <= 1e-12);
      // And its acceleration, from the row differentiated once.
      const Eigen::VectorXd a2 = s.model.C * d.acceleration.col(col) + *s.model.K * d.v.col(col);
      CHECK(std::abs(a2[1] - 35.0 * std::cos(7.0 * d.t[k])) <= 1e-11);
    }
    // The energy balance (kinetic + strain − work of the loads and of the constraint forces +
    // dissipated) closes to the tolerance: the massless DOF's strain energy and its dashpot's
    // dissipation included.
    REQUIRE(d.balance.size() == d.t.size());
    double worst = 0.0;
    for (const auto& b : d.balance) worst = std::max(worst, std::abs(b.error()));
    CHECK(worst <= 1e-7);
  }
}

TEST_CASE("values [initial] gives a massless DOF that it does not keep are warned of") {
  // u2 has no mass: without damping its u and v follow its stiffness row, with damping its v
  // does (its u is a first-order state and is kept).
  const std::string given =
      "[initial]\ndisplacement = { u2 = 0.5, u3 = 0.1 }\nvelocity = { u2 = 3.0 }\n";
  const auto plain = test::built(parse_scene_text(kChain + given, "c.toml"));
  REQUIRE(plain.report.warnings.size() == 2);
  CHECK(plain.report.warnings[0] ==
        "[initial] displacement gives u2 = 0.5, but u2 has no mass nor damping: its stiffness rows "
        "set it at every instant, t = 0 included, so the value given is not kept (the output's "
        "first row shows the one used)");
  CHECK(plain.report.warnings[1].rfind("[initial] velocity gives u2 = 3, but u2 has no mass nor",
                                       0) == 0);
  const std::string damped =
      test::replace(kChain, "[[load]]", "damping = { rayleigh = [0.1, 0.002] }\n[[load]]");
  const auto first_order = test::built(parse_scene_text(damped + given, "d.toml"));
  REQUIRE(first_order.report.warnings.size() == 1);
  CHECK(first_order.report.warnings[0].rfind(
            "[initial] velocity gives u2 = 3, but u2 has no mass: its damping and stiffness rows "
            "set its velocity",
            0) == 0);
  // A massive DOF's values are kept: no warning.
  CHECK(test::built(parse_scene_text(kChain + "[initial]\nvelocity = { u3 = 1.0 }\n", "m.toml"))
            .report.warnings.empty());
}

TEST_CASE(
    "every scheme accepts massless DOFs held by stiffness, and refusals name only usable ones") {
  const auto s = test::built(parse_scene_text(kChain, "chain.toml"));
  for (Scheme scheme :
       {Scheme::index1, Scheme::ggl, Scheme::elimination, Scheme::penalty, Scheme::projection})
    CHECK_FALSE(scheme_refusal(s.model, scheme).has_value());
  // A static start rules penalty out: its refusal names no scheme, and projection runs it (it
  // used to refuse every model with held massless DOFs).
  const auto preloaded = test::built(parse_scene_text(
      test::replace(kChain, "[solve]", "[initial]\nstatic = true\n[solve]"), "chain.toml"));
  REQUIRE(scheme_refusal(preloaded.model, Scheme::penalty).has_value());
  CHECK_FALSE(scheme_refusal(preloaded.model, Scheme::projection).has_value());
}

TEST_CASE("massless DOFs that stiffness does not hold are bad input, DOFs named") {
  // u2 and u3 massless, joined to each other by a spring and to nothing else: each has stiffness
  // on its diagonal, but together they move freely (a mechanism of massless DOFs).
  const std::string mechanism = R"([model]
type = "matrix"
dofs = ["u1", "u2", "u3"]
mass = [[1.0, 0, 0], [0, 0.0, 0], [0, 0, 0.0]]
stiffness = [[100.0, 0, 0], [0, 50.0, -50.0], [0, -50.0, 50.0]]
[solve]
t_end = 1.0
output_step = 0.5
)";
  CHECK_THROWS_WITH_AS((void)test::built(parse_scene_text(mechanism, "mech.toml")),
                       doctest::Contains("mech.toml:1: model.mass: 2 DOFs (u2, u3) have no mass "
                                         "and no constraint, and their stiffness block K_hh is "
                                         "singular"),
                       SceneError);
  // Neither stiffness nor damping on u2: nothing holds it.
  const std::string loose = test::replace(
      test::replace(mechanism, "[0, 50.0, -50.0], [0, -50.0, 50.0]", "[0, 0, 0], [0, 0, 50.0]"),
      "[0, 0, 0.0]]", "[0, 0, 1.0]]");
  CHECK_THROWS_WITH_AS(
      (void)test::built(parse_scene_text(loose, "loose.toml")),
      doctest::Contains("loose.toml:1: model: DOF 'u2' has neither mass nor stiffness nor damping "
                        "nor a constraint"),
      SceneError);
}

}  // namespace test_held_massless
