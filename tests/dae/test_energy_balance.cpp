// The energy balance (dae/run/energy_balance.hpp, docs/energy.md) against closed forms: the work of
// a load step switched on between output times, the energy a damper dissipates (integrated here
// from the exact solution, independently of the run's quadrature), nonlinear models under
// time-dependent loading. The long runs under every scheme (a damped, loaded chain on a moving
// support, a pre-stressed pendulum) are validation-tier cases: test_energy_balance_validation.cpp.

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "dae/run/solve.hpp"
#include "dae/run/trajectory.hpp"
#include "models/assembly/build_model.hpp"
#include "models/scene/scene_parser.hpp"
#include "tests/energy_runs.hpp"
#include "tests/solve_helpers.hpp"

using namespace condyn;

namespace test_energy_balance {

using namespace condyn::test::energy;

TEST_CASE("the work of a load step switched on between output times, against the closed form") {
  // m = 1 kg, k = 4 N/m (ω = 2 rad/s) at rest; F = 1 N from t_s = 0.35 s (between the outputs
  // 0.3 and 0.4): u = F/k (1 − cos ω(t − t_s)) after it, and W_loads = F u exactly.
  const std::string text = scene(R"([model]
type = "matrix"
dofs = ["x"]
mass = [[1.0]]
stiffness = [[4.0]]
[[load]]
dof = "x"
value = { type = "step", amplitude = 1.0, start = 0.35 }
)");
  for (const bool streamed : {false, true}) {
    for (const Scheme scheme : {Scheme::elimination, Scheme::ggl, Scheme::projection}) {
      CAPTURE(to_string(scheme));
      CAPTURE(streamed);
      const Balances run = balances(text, scheme, streamed);
      for (std::size_t k = 0; k < run.t.size(); ++k) {
        const double t = run.t[k], s = std::max(0.0, t - 0.35);
        const double u = 0.25 * (1.0 - std::cos(2.0 * s)), v = 0.5 * std::sin(2.0 * s);
        const EnergyBalance& b = run.b[k];
        CAPTURE(t);
        CHECK(std::abs(b.work_loads - u) < 1e-8);
        CHECK(std::abs(b.kinetic - 0.5 * v * v) < 1e-8);
        CHECK(std::abs(b.potential - 2.0 * u * u) < 1e-8);
        CHECK(b.dissipated == 0.0);
        CHECK(b.work_constraints == 0.0);
        CHECK(std::abs(b.error()) < 1e-8);
      }
      CHECK(run.b.back().work_loads > 0.1);  // the load did work: the check above means something
    }
  }
}

TEST_CASE("a load step on a preloaded massless DOF: the jump's work, and the half it loses") {
  // y massless (k = 9 N/m) under a preload P and a step of 2 N at t = 0.5: y jumps from P/9 to
  // (P + 2)/9. The load, already at P + 2, does (P + 2) Δy over the jump; the spring stores
  // P Δy + 2 Δy / 2; the balance misses −2 Δy / 2 = −2/9 J whatever P (the jump's own loss, as
  // any damping however small would dissipate). Without the jump's work the error was
  // P Δy + 2 Δy / 2: +1.33 J for P = 5, −0.89 J for P = −5.
  for (const double preload : {5.0, -5.0, 0.0}) {
    const std::string text = scene(R"([model]
type = "matrix"
dofs = ["x", "y"]
mass = [[1.0, 0.0], [0.0, 0.0]]
stiffness = [[10.0, 0.0], [0.0, 9.0]]
[[load]]
dof = "y"
value = [{ type = "step", amplitude = 2.0, start = 0.5 }, { type = "polynomial", coefficients = [)" +
                                   std::to_string(preload) + R"(] }]
)");
    for (const Scheme scheme : {Scheme::elimination, Scheme::ggl, Scheme::index1}) {
      CAPTURE(preload);
      CAPTURE(to_string(scheme));
      const Balances run = balances(text, scheme, false);
      const double dy = 2.0 / 9.0;
      for (std::size_t k = 0; k < run.t.size(); ++k) {
        const EnergyBalance& b = run.b[k];
        CAPTURE(run.t[k]);
        const bool after = run.t[k] >= 0.5;
        CHECK(std::abs(b.work_loads - (after ? (preload + 2.0) * dy : 0.0)) < 1e-12);
        CHECK(std::abs(b.error() - (after ? -dy : 0.0)) < 1e-12);  // −2 Δy / 2
      }
    }
  }
}

TEST_CASE("the energy a damper dissipates, against the exact solution integrated here") {
  // m = 1, k = 4, c = 0.4 (ζ = 0.1), released from x = 1: v(t) = −(ω²/ω_d) e^{−ζωt} sin ω_d t.
  // D(t) = ∫ c v² dt by composite Simpson on 30,000 intervals of the exact v (error ~1e-15).
  const std::string text = scene(R"([model]
type = "matrix"
dofs = ["x"]
mass = [[1.0]]
stiffness = [[4.0]]
damping = [[0.4]]
[initial]
displacement = { x = 1.0 }
)");
  const double w = 2.0, z = 0.1, wd = w * std::sqrt(1.0 - z * z);
  const auto v = [&](double t) { return -(w * w / wd) * std::exp(-z * w * t) * std::sin(wd * t); };
  const auto dissipated = [&](double t) {
    const int n = 30000;
    const double h = t / n;
    double sum = 0.0;
    for (int i = 0; i <= n; ++i) {
      const double weight = (i == 0 || i == n) ? 1.0 : (i % 2 ? 4.0 : 2.0);
      sum += weight * 0.4 * v(i * h) * v(i * h);
    }
    return sum * h / 3.0;
  };
  for (const Scheme scheme : {Scheme::elimination, Scheme::index1, Scheme::penalty}) {
    CAPTURE(to_string(scheme));
    const Balances run = balances(text, scheme, true);
    for (std::size_t k = 0; k < run.t.size(); k += 5) {
      CAPTURE(run.t[k]);
      CHECK(std::abs(run.b[k].dissipated - dissipated(run.t[k])) < 1e-8);
      CHECK(std::abs(run.b[k].error()) < 1e-8);
    }
    // Most of the initial 2 J is gone by t = 3 s (e^{−2ζωt} = 0.3).
    CHECK(run.b.back().dissipated > 1.0);
    CHECK(run.b.front().initial == doctest::Approx(2.0).epsilon(1e-12));
  }
}

TEST_CASE("nonlinear models under time-dependent loading: the balance closes with the tolerance") {
  // The car axis (its road moves the right spring's anchor: the road's work is reported as the
  // loads'; its rheonomic road row's as the constraints'), a pendulum (rigid member) pushed by a
  // harmonic load, and the Chaplygin sleigh (nonholonomic) pushed the same way. Observed
  // (ggl, rtol 1e-10, atol 1e-12): errors 4.2e-8 (car axis), 1.7e-9 and 8e-10 of
  // the largest term, and 1,400 to 900,000 times smaller than at rtol 1e-6.
  const std::string harmonic = "value = { type = \"harmonic\", amplitude = 1.0, omega = 2.0 }\n";
  const std::string models[] = {
      "[model]\ntype = \"car_axis\"\n",
      "[model]\ntype = \"truss2d\"\nnodes = [[0.0, 0.0], [1.0, 0.0]]\nmasses = [0.0, 1.0]\n"
      "supports = [1]\nmembers = [{ nodes = [1, 2], rigid = true }]\ngravity = [0.0, -9.81]\n"
      "[[load]]\ndof = \"ux2\"\n" +
          harmonic,
      "[model]\ntype = \"sleigh\"\nmass = 1.0\ninertia = 0.5\ncontact_offset = 0.3\n"
      "[[load]]\ndof = \"x\"\n" +
          harmonic + "[initial]\nvelocity = { x = 1.0, y = -0.3, theta = 1.0 }\n"};
  for (const std::string& model : models) {
    CAPTURE(model);
    const auto tight = worst(balances(scene(model), Scheme::ggl, false));
    const double error = tight.first, scale = tight.second;
    CAPTURE(error);
    CAPTURE(scale);
    CHECK(error < 1e-7 * scale);
    const double loose = loose_error(model, Scheme::ggl, true);
    CAPTURE(loose);
    CHECK(loose > 30.0 * error);
  }
}

TEST_CASE("relative_energy_error: NaN, not a figure, when an energy leaves the double range") {
  // A load of 1e200 times its displacement: energies of inf, and inf - inf read as an error of 0.
  Trajectory traj;
  traj.energy = Eigen::VectorXd::Zero(3);
  traj.kinetic = Eigen::VectorXd::Zero(3);
  traj.energy << 0.0, 1.0, 2.0;
  traj.kinetic << 0.0, 4.0, 1.0;
  CHECK(relative_energy_error(traj) == 0.5);  // max |E - E0| = 2 over max(|E0|, max T) = 4
  traj.energy[2] = std::numeric_limits<double>::infinity();
  CHECK(std::isnan(relative_energy_error(traj)));
  traj.energy[2] = 2.0;
  traj.kinetic[1] = std::numeric_limits<double>::quiet_NaN();
  CHECK(std::isnan(relative_energy_error(traj)));
  CHECK(relative_energy_error(Trajectory{}) == -1.0);  // no energies: none asked for
}

TEST_CASE("relative_energy_error at rest in an unstable equilibrium: relative to m g L, not 0") {
  // A pendulum balanced upright, its bob at the origin (the potential's zero) straight above its
  // pivot, gravity along the rod (9.81 split 0.6 : 0.8, the rod's direction): every energy starts
  // at 0 and stays at roundoff while the bob barely leaves the top. Relative to max(|E(0)|, max T)
  // the error read 2.8 (and up to 4e47 where T stayed at 1e-63); relative to the model's energy
  // scale m g L = 1 · (5.886 + 7.848) · 1 (the 1-norm of the weight) it is roundoff.
  const std::string solve = R"(
[solve]
t_end = 0.2
output_step = 0.02
rtol = 1e-8
atol = 1e-10
)";
  const std::string mechanism = R"([model]
type = "multibody"
dimension = 2
gravity = [-5.886, -7.848]
ground = { O = [-0.6, -0.8] }
[[body]]
name = "bob"
mass = 1.0
inertia = 0.001
position = [0.0, 0.0]
points = { G = [0.0, 0.0] }
[[joint]]
name = "rod"
type = "distance"
bodies = ["ground", "bob"]
points = ["O", "G"]
length = 1.0
)" + solve;
  const std::string truss = R"([model]
type = "truss2d"
nodes = [[-0.6, -0.8], [0.0, 0.0]]
masses = [0.0, 1.0]
supports = [1]
members = [{ nodes = [1, 2], rigid = true }]
gravity = [-5.886, -7.848]
)" + solve;
  // The energy drifts by the integration error over a slight motion: within rtol of m g L.
  constexpr double kRtol = 1e-8;
  constexpr double kWeight = 5.886 + 7.848;
  // Pairs, not structured bindings: CAPTURE's lambda cannot capture a binding before C++20's
  // P1091 (clang-tidy's clang refuses it).
  for (const auto& scene : {std::pair{"mechanism", mechanism}, std::pair{"truss", truss}}) {
    CAPTURE(scene.first);
    const test::BuiltScene s = test::built(parse_scene_text(scene.second, "upright.toml"));
    for (const bool streamed : {false, true}) {
      CAPTURE(streamed);
      RunHooks hooks;
      if (streamed) hooks.on_row = [](const TrajectoryRow&) {};
      const SolveResult r = test::solved(s.model, s.spec.solve, hooks);
      REQUIRE(r.trajectory.energy.size() > 0);
      CHECK(r.trajectory.energy[0] == 0.0);  // at rest at the potential's zero
      // ‖f‖₁ = m (5.886 + 7.848) times a size of at least the rod's length.
      CHECK(r.trajectory.energy_scale >= kWeight);
      CHECK(relative_energy_error(r.trajectory) < kRtol);
    }
  }
}

}  // namespace test_energy_balance
