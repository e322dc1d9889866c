// RATTLE (scheme = "rattle"; dae/integrators/rattle_step.hpp): on an unconstrained oscillator the
// run is the Störmer–Verlet recurrence to roundoff; on the pendulum the step is time-reversible
// to Newton's tolerance and the energy error stays bounded (no drift) with the constraints held;
// what it cannot integrate is refused, naming why.

#include <doctest/doctest.h>

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <memory>
#include <string>

#include "dae/integrators/rattle_step.hpp"
#include "dae/interface/scheme_not_applicable.hpp"
#include "models/scene/scene_parser.hpp"
#include "tests/solve_helpers.hpp"

using namespace condyn;

namespace test_rattle {

namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

/// IFToMM A01 (models/scenes/iftomm/A01_simple_pendulum.toml): a 1 kg bob on a 1 m link,
/// released horizontal, period 2.3676 s; `solve` the [solve] table's keys.
std::string pendulum(const std::string& solve) {
  return R"([model]
type = "multibody"
dimension = 2
gravity = [0.0, -9.81]
ground = { O = [0.0, 0.0] }
[[body]]
name = "bob"
mass = 1.0
inertia = 1.0e-3
position = [1.0, 0.0]
angle = 0.0
points = { P1 = [0.0, 0.0] }
[[joint]]
name = "link"
type = "distance"
bodies = ["ground", "bob"]
points = ["O", "P1"]
length = 1.0
[solve]
scheme = "rattle"
)" + solve;
}

}  // namespace

TEST_CASE("rattle: an unconstrained oscillator follows the Stoermer-Verlet recurrence") {
  // m u'' = −k u: v½ = v + (h/2) a(u), u₁ = u + h v½, v₁ = v½ + (h/2) a(u₁), a(u) = −k u / m,
  // applied n times by hand. Both sides do the same operations in another order (a sparse solve
  // against a division): roundoff, 64 eps of |u| + h|v| per step over 200 steps.
  const double m = 2.0, k = 50.0, h = 0.01;
  const int steps = 200;
  const std::string scene = R"([model]
type = "matrix"
dofs = ["x"]
mass = [[2.0]]
stiffness = [[50.0]]
[initial]
displacement = { x = 1.0 }
velocity = { x = 0.5 }
[solve]
t_end = 2.0
output_step = 0.01
step = 0.01
scheme = "rattle"
)";
  const auto built = test::built(parse_scene_text(scene, "osc.toml"));
  const SolveResult r = test::solved(built.model, built.spec.solve);
  REQUIRE(r.trajectory.t.size() == steps + 1);
  double u = 1.0, v = 0.5, worst = 0.0;
  for (int n = 1; n <= steps; ++n) {
    const double v_half = v - 0.5 * h * k * u / m;
    u += h * v_half;
    v = v_half - 0.5 * h * k * u / m;
    worst = std::max(
        {worst, std::abs(r.trajectory.u(0, n) - u), std::abs(r.trajectory.v(0, n) - v) * h});
  }
  const double kRoundoff = 64.0 * kEps * steps * 2.0;  // |u| + h |v| ≤ 2
  MESSAGE("largest difference from the recurrence " << worst);
  CHECK(worst <= kRoundoff);
  CHECK(r.summary.steps == steps);
  CHECK(r.summary.jacobian_evals == 1);  // M alone, factored once for the run
}

TEST_CASE("rattle: the pendulum's step is time-reversible to Newton's tolerance") {
  // N steps forward, the velocities reversed, N steps again: back at the start with the velocity
  // reversed (the method is symmetric: Hairer, Lubich and Wanner, §VII.1.4). Each step's
  // positions are solved to rtol |u| + atol = 1e-12 or better (Newton converges quadratically, so
  // the last update's size bounds the error by far); 2N = 400 of them bound the difference at
  // 4e-10, times 10 for the errors' growth along the motion: 4e-9. Observed: see the message.
  const auto built = test::built(
      parse_scene_text(pendulum("t_end = 1.0\noutput_step = 0.1\nstep = 0.01\n"), "pendulum.toml"));
  const auto system = built.model.system->clone();
  RattleStep step(*system, RattleSettings{1e-12, 1e-12});
  Eigen::VectorXd u = built.model.u0, v = built.model.v0, mu;
  const int n = 200;
  const double h = 0.005;
  for (int k = 0; k < n; ++k) step.advance(k * h, h, u, v, mu);
  CHECK((u - built.model.u0).cwiseAbs().maxCoeff() > 0.1);  // it went somewhere
  v = -v;
  for (int k = 0; k < n; ++k) step.advance(k * h, h, u, v, mu);
  const double du = (u - built.model.u0).cwiseAbs().maxCoeff();
  const double dv = (v + built.model.v0).cwiseAbs().maxCoeff();
  MESSAGE("back at the start within " << du << " (u), " << dv << " (v)");
  constexpr double kReversible = 4e-9;
  CHECK(du <= kReversible);
  CHECK(dv <= kReversible);
}

TEST_CASE(
    "rattle: the pendulum's energy error stays bounded, the constraints at Newton's "
    "tolerance") {
  // 100 periods (237 s) at h = 0.02, 11,838 steps. A symplectic method keeps the energy error
  // at O(h²) with no drift: the largest error over the last 50 periods is no larger than 1.5
  // times that over the first 50 (a drift would double it); observed: see the message. The
  // error itself is O(h² ω² m g L): below 1e-2 m g L at h ω = 0.063. The position rows hold
  // to Newton's tolerance (rtol |u| + atol ≤ 2e-8 at rtol 1e-8; observed at roundoff, Newton
  // converging quadratically) and the velocity rows to the roundoff of the projection's solve.
  const auto built = test::built(parse_scene_text(
      pendulum("t_end = 236.76\noutput_step = 0.04\nstep = 0.02\nrtol = 1e-8\natol = 1e-10\n"),
      "pendulum.toml"));
  const SolveResult r = test::solved(built.model, built.spec.solve);
  const Eigen::VectorXd& e = r.trajectory.energy;
  REQUIRE(e.size() > 100);
  const double mgl = 9.81;
  const Eigen::Index half = e.size() / 2;
  const double first = (e.head(half).array() - e[0]).abs().maxCoeff() / mgl;
  const double second = (e.tail(e.size() - half).array() - e[0]).abs().maxCoeff() / mgl;
  MESSAGE("energy error / mgL: " << first << " (first 50 periods), " << second
                                 << " (last 50); drift " << r.summary.max_drift_position
                                 << " (positions), " << r.summary.max_drift_velocity
                                 << " (velocities)");
  constexpr double kNoDrift = 1.5, kEnergyBound = 1e-2;
  CHECK(second <= kNoDrift * first);
  CHECK(first <= kEnergyBound);
  constexpr double kNewtonTolerance = 2e-8;
  CHECK(r.summary.max_drift_position <= kNewtonTolerance);
  // The projection is refined once on its residual: 64 ulps of |v| ≤ √(2 g L) = 4.4 m/s.
  constexpr double kProjectionRoundoff = 64.0 * kEps * 5.0;
  CHECK(r.summary.max_drift_velocity <= kProjectionRoundoff);
}

TEST_CASE("rattle: what it cannot integrate is refused, naming why") {
  const std::string oscillator = R"([model]
type = "matrix"
dofs = ["a", "b"]
mass = [[1.0, 0.0], [0.0, 1.0]]
stiffness = [[2.0, -1.0], [-1.0, 1.0]]
)";
  const std::string solve_keys =
      "[solve]\nt_end = 1.0\noutput_step = 0.1\nstep = 0.01\n"
      "scheme = \"rattle\"\n";
  const struct {
    std::string scene, why;
  } cases[] = {
      {oscillator + "damping = [[0.1, 0.0], [0.0, 0.0]]\n" + solve_keys, "has damping"},
      {oscillator +
           "[[constraint]]\nname = \"tie\"\nterms = { a = 1.0, b = -1.0 }\n"
           "value = { type = \"harmonic\", amplitude = 0.1, omega = 2.0, phase = "
           "1.5707963267948966 }\n"
           "[initial]\ndisplacement = { a = 0.1 }\n" +
           solve_keys,
       "constraint 'tie' depends on time"},
      {oscillator +
           "[[constraint]]\nname = \"slide\"\nlevel = \"velocity\"\nterms = { a = 1.0 }\n" +
           solve_keys,
       "constraint 'slide' is written on velocities"},
      {R"([model]
type = "matrix"
dofs = ["a", "b"]
mass = [[1.0, 0.0], [0.0, 0.0]]
stiffness = [[2.0, -1.0], [-1.0, 1.0]]
)" + solve_keys,
       "DOF b has no mass"},
      {"[model]\ntype = \"andrews\"\n" + solve_keys, "mass matrix depends on its coordinates"},
  };
  for (const auto& c : cases) {
    CAPTURE(c.scene);
    const auto built = test::built(parse_scene_text(c.scene, "bad.toml"));
    CHECK_THROWS_WITH_AS((void)solve(built.model, built.spec.solve),
                         doctest::Contains(c.why.c_str()), SchemeNotApplicable);
    CHECK_THROWS_WITH_AS((void)solve(built.model, built.spec.solve),
                         doctest::Contains("rattle integrates conservative mechanisms only"),
                         SchemeNotApplicable);
  }
  // No step: refused when the run is planned, naming the key (not by the reader, so that a
  // command line's --step or --scheme can supply or lift what the file lacks).
  const auto no_step = parse_scene_text(
      oscillator + "[solve]\nt_end = 1.0\noutput_step = 0.1\nscheme = \"rattle\"\n", "nostep.toml");
  const auto built = test::built(no_step);
  CHECK_THROWS_WITH_AS((void)solve(built.model, built.spec.solve),
                       doctest::Contains("solve.step: the rattle scheme runs with a fixed step"),
                       std::invalid_argument);
}

}  // namespace test_rattle
