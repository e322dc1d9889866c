// The mechanism scenes of models/scenes/multibody/ run from their files under every scheme that
// applies, through the scene reader and the builder (models/assembly/multibody_model.cpp), and
// meet their closed forms: the slider-crank's slider position (kinematics of a driven crank)
// and the pendulum's turning point at half its period (an elliptic integral).
#include <doctest/doctest.h>

#include <Eigen/Dense>
#include <cmath>
#include <string>

#include "dae/run/solve.hpp"
#include "models/core/model.hpp"
#include "tests/solve_helpers.hpp"

using namespace condyn;

namespace test_multibody_scene_runs {

namespace {

/// The global error of a run at the scene's rtol: up to 1e3 rtol relative to the size (1 for
/// the pendulum, 0.4 for the slider's stroke), 1e4 under index3, which leaves the velocities out
/// of its error test (as tests/models/test_multibody_runs.cpp bounds them).
double error_bound(Scheme scheme, double rtol) {
  return (scheme == Scheme::index3 ? 1e4 : 1e3) * rtol;
}

test::BuiltScene scene(const std::string& name) {
  return test::built(
      parse_scene_file(std::string(CONDYN_SOURCE_DIR) + "/models/scenes/multibody/" + name));
}

/// The column of the output row at time `t` (an output time of the run).
Eigen::Index row_at(const Trajectory& traj, double t) {
  Eigen::Index best = 0;
  for (Eigen::Index k = 0; k < static_cast<Eigen::Index>(traj.t.size()); ++k) {
    if (std::abs(traj.t[static_cast<std::size_t>(k)] - t) <
        std::abs(traj.t[static_cast<std::size_t>(best)] - t))
      best = k;
  }
  return best;
}

constexpr Scheme kMechanismSchemes[] = {Scheme::index1, Scheme::baumgarte, Scheme::ggl,
                                        Scheme::index2, Scheme::index3,    Scheme::projection};

}  // namespace

TEST_CASE("the slider-crank scene: the slider follows the driven crank's kinematics") {
  const auto s = scene("slider_crank.toml");
  const int x = s.model.dof_at("slider.rx");
  for (Scheme scheme : kMechanismSchemes) {
    CAPTURE(std::string(to_string(scheme)));
    const SolveResult result = test::solved(s.model, test::under(s.spec.solve, scheme));
    const Trajectory& traj = result.trajectory;
    // θ = π at t = 0.25: x = −r + l = 0.2; θ = 2π at 0.75: x = r + l = 0.4.
    CHECK(std::abs(traj.u(x, row_at(traj, 0.25)) - 0.2) <= error_bound(scheme, s.spec.solve.rtol));
    CHECK(std::abs(traj.u(x, row_at(traj, 0.75)) - 0.4) <= error_bound(scheme, s.spec.solve.rtol));
  }
}

TEST_CASE("the pendulum scene: at rest at (-1, 0) after half its period") {
  const auto s = scene("pendulum_a01.toml");
  const int x = s.model.dof_at("mass.rx"), y = s.model.dof_at("mass.ry");
  for (Scheme scheme : kMechanismSchemes) {
    CAPTURE(std::string(to_string(scheme)));
    const SolveResult result = test::solved(s.model, test::under(s.spec.solve, scheme));
    const Trajectory& traj = result.trajectory;
    const auto last = static_cast<Eigen::Index>(traj.t.size()) - 1;
    CHECK(std::abs(traj.u(x, last) + 1.0) <= error_bound(scheme, s.spec.solve.rtol));
    // At the turning point the speed is 0: both coordinates are stationary in time, so their
    // errors are the run's global error alone.
    CHECK(std::abs(traj.u(y, last)) <= error_bound(scheme, s.spec.solve.rtol));
  }
}

TEST_CASE("the four-bars run under every scheme, the spatial one included") {
  for (const char* name : {"four_bar.toml", "spatial_four_bar.toml"}) {
    const auto s = scene(name);
    for (Scheme scheme : kMechanismSchemes) {
      CAPTURE(name);
      CAPTURE(std::string(to_string(scheme)));
      const SolveResult result = test::solved(s.model, test::under(s.spec.solve, scheme));
      CHECK(result.trajectory.t.back() == doctest::Approx(s.spec.solve.t_end));
    }
  }
}

}  // namespace test_multibody_scene_runs
