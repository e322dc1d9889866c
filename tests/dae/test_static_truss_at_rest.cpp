// [initial] static = true: a truss under gravity started at its static equilibrium stays at rest
// under elimination, index-1 and GGL; started from u = 0 the same truss falls (the test can fail).
#include <doctest/doctest.h>

#include <string>

#include "models/scene/scene_parser.hpp"
#include "tests/solve_helpers.hpp"

using namespace condyn;

namespace test_static_truss_at_rest {

namespace {

// The run's tolerances. At the static equilibrium the accelerations are roundoff (a few ulps of
// K u / M ≈ 1e-15 here), so the velocities the integrator produces stay at that level over the
// run: bounded by the run's atol = 1e-10 (the absolute resolution it is asked for) with five
// orders to spare, and the displacements stay at u(0) to rtol relative.
constexpr double kRtol = 1e-8;
constexpr double kAtol = 1e-10;

/// Two supports, two free nodes; EA = 100 and unit masses: sag about 0.1 under gravity, periods
/// around 0.5 s, so three seconds hold several oscillations of a truss that is not in equilibrium.
std::string truss(const std::string& initial) {
  return R"([model]
type = "truss2d"
nodes = [[0.0, 0.0], [1.0, 0.0], [2.0, 0.0], [1.0, 1.0]]
masses = [1.0, 1.0, 1.0, 1.0]
supports = [1, 3]
members = [{ nodes = [1, 2], EA = 100.0 }, { nodes = [2, 3], EA = 100.0 },
           { nodes = [1, 4], EA = 100.0 }, { nodes = [4, 3], EA = 100.0 },
           { nodes = [2, 4], EA = 100.0 }]
gravity = [0.0, -9.81]
)" + initial +
         R"([solve]
t_end = 3.0
output_step = 0.05
rtol = 1e-8
atol = 1e-10
)";
}

}  // namespace

TEST_CASE("static start: a truss settled by static = true stays at rest under every scheme") {
  const auto at_rest = test::built(parse_scene_text(truss("[initial]\nstatic = true\n"), "t.toml"));
  const auto falling = test::built(parse_scene_text(truss(""), "t.toml"));
  const Eigen::VectorXd& u0 = at_rest.model.u0;
  REQUIRE(u0.lpNorm<Eigen::Infinity>() > 1e-3);  // it sags: the equilibrium is not u = 0
  for (const Scheme scheme : {Scheme::elimination, Scheme::index1, Scheme::ggl}) {
    CAPTURE(std::string(to_string(scheme)));
    const SolveResult rest = test::solved(at_rest.model, test::under(at_rest.spec.solve, scheme));
    const auto& tr = rest.trajectory;
    REQUIRE(tr.v.cols() > 50);
    CHECK(tr.v.lpNorm<Eigen::Infinity>() < kAtol);
    CHECK((tr.u.colwise() - u0).lpNorm<Eigen::Infinity>() <= kRtol * u0.lpNorm<Eigen::Infinity>());
    const SolveResult fall = test::solved(falling.model, test::under(falling.spec.solve, scheme));
    CHECK(fall.trajectory.v.lpNorm<Eigen::Infinity>() > 1e-2);
  }
}

}  // namespace test_static_truss_at_rest
