// The elimination path at real size (issue 12): a 20,000-DOF tied lattice runs under elimination
// as under index1 (validation tier: two runs of a few seconds each).

#include <doctest/doctest.h>

#include <limits>
#include <string>

#include "models/scene/scene_parser.hpp"
#include "tests/solve_helpers.hpp"
#include "tests/sparse_elimination_scene.hpp"

using namespace condyn;

namespace test_sparse_elimination_validation {

namespace {
constexpr double kEps = std::numeric_limits<double>::epsilon();
}  // namespace

TEST_CASE("a 20,000-DOF tied lattice runs under elimination and agrees with index1") {
  // Refused before at 5,000 DOFs; the dense transform alone wanted n x (n - m) doubles (3.2 GB).
  const auto scene = test::built(
      parse_scene_text(test::tied_lattice("rtol = 1e-6\natol = 1e-8\n"), "lattice.toml"));
  const SolveResult elim =
      test::solved(scene.model, test::under(scene.spec.solve, Scheme::elimination));
  const SolveResult index1 =
      test::solved(scene.model, test::under(scene.spec.solve, Scheme::index1));
  const Trajectory& a = elim.trajectory;
  const Trajectory& b = index1.trajectory;
  REQUIRE(a.u.cols() == b.u.cols());
  const double scale = b.u.cwiseAbs().maxCoeff();
  REQUIRE(scale > 0.0);
  // Two schemes at rtol 1e-6, each within a small multiple of rtol of the solution: 100 rtol
  // (observed below 2 rtol).
  CHECK((a.u - b.u).cwiseAbs().maxCoeff() <= 100 * 1e-6 * scale);
  // The ties hold exactly under elimination (u_slave = T û: the same value).
  CHECK(elim.summary.max_drift_position <= 4 * kEps * scale);
}

}  // namespace test_sparse_elimination_validation
