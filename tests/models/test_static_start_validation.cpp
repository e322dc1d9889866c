// [initial] static = true on a large model: a 10,000-DOF lattice under gravity solves sparse to a
// small residual. Validation tier: a large solve, run optimized (test_static_start.cpp holds the
// unit cases, which reach every line of the library this one does under the sanitizers).
#include <doctest/doctest.h>

#include <limits>

#include <Eigen/Dense>

#include "models/assembly/build_model.hpp"
#include "models/assembly/static_equilibrium.hpp"
#include "models/core/model.hpp"
#include "models/scene/scene_parser.hpp"
#include "tests/lattice_scene.hpp"
#include "tests/solve_helpers.hpp"

using namespace condyn;

namespace test_static_start_validation {

namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();
// Equilibrium residual of a large solve relative to |f|: LU with one refinement step leaves a
// few hundred ulps (cond of the lattice ~1e4 times eps); 1e-10 is far above that and far below
// any physics.
constexpr double kResidualTolerance = 1e-10;

}  // namespace

TEST_CASE("static start: a 10,000-DOF lattice under gravity solves sparse to a small residual") {
  // 100 x 50 nodes, two DOFs each; the left column supported.
  const auto scene = test::built(parse_scene_text(
      test::lattice(100, 50, "gravity = [0.0, -1.0]\n[initial]\nstatic = true\n", ""),
      "lattice.toml"));
  const Model& m = scene.model;
  REQUIRE(m.dofs() == 10000);
  const Eigen::VectorXd f = m.applied_forces(0.0);
  const StaticEquilibrium eq = solve_static_equilibrium(*m.K, m.A, f, m.position_rhs(0, 0.0));
  CHECK((eq.u - m.u0).lpNorm<Eigen::Infinity>() <= 4 * kEps * m.u0.lpNorm<Eigen::Infinity>());
  Eigen::VectorXd r = *m.K * m.u0 - f;
  if (m.constraint_count() > 0) r += m.A.transpose() * eq.lambda;
  CHECK(r.lpNorm<Eigen::Infinity>() <= kResidualTolerance * f.lpNorm<Eigen::Infinity>());
  CHECK(m.u0.lpNorm<Eigen::Infinity>() > 0.0);  // the lattice sags: the test can fail
}

}  // namespace test_static_start_validation
