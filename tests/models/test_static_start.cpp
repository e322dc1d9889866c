// [initial] static = true: u(0) is the constrained static equilibrium at t = 0 (sparse KKT solve
// of a linear model); mechanisms, a wrong type and combinations with other [initial] keys are
// refused naming initial.static. The 10,000-DOF lattice is a validation-tier case
// (test_static_start_validation.cpp).
#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include "dae/run/solve.hpp"
#include "models/assembly/build_model.hpp"
#include "models/core/model.hpp"
#include "models/scene/scene_parser.hpp"
#include "tests/scene_errors.hpp"
#include "tests/scene_text.hpp"
#include "tests/solve_helpers.hpp"

using namespace condyn;

namespace test_static_start {

using condyn::test::build_error;

namespace {

// Hand-computed equilibria of a three-DOF chain: a handful of flops per entry, so 1e-12 relative
// leaves a wide margin over roundoff (a few eps).
constexpr double kChainTolerance = 1e-12;

/// Springs x1–x2 (k = 2) and x2–x3 (k = 3), x1 held by a constraint to `support`, a load of 6 at
/// x3: u = (s, s + 3, s + 5).
std::string chain(const std::string& support, const std::string& initial_extra) {
  return R"([model]
type = "matrix"
dofs = ["x1", "x2", "x3"]
mass = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]
stiffness = [[2.0, -2.0, 0.0], [-2.0, 5.0, -3.0], [0.0, -3.0, 3.0]]
[[load]]
dof = "x3"
value = 6.0
[[constraint]]
name = "support"
terms = { x1 = 1.0 }
value = )" +
         support +
         R"(
[initial]
static = true
)" + initial_extra +
         R"([solve]
t_end = 1.0
output_step = 0.1
)";
}

bool contains(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

void check_close(double computed, double expected) {
  CHECK(std::abs(computed - expected) <= kChainTolerance * std::abs(expected));
}

}  // namespace

TEST_CASE(
    "static start: a supported spring chain under load starts at its hand-computed equilibrium") {
  const auto scene = test::built(parse_scene_text(chain("0.0", ""), "chain.toml"));
  const Model& m = scene.model;
  CHECK(std::abs(m.u0[0]) <= kChainTolerance * 5.0);  // the support, to roundoff of |u|
  check_close(m.u0[1], 3.0);
  check_close(m.u0[2], 5.0);
  CHECK(m.v0.lpNorm<Eigen::Infinity>() == 0.0);
  CHECK(contains(scene.report.initial_projection, "static equilibrium"));
  CHECK(contains(scene.report.initial_projection, "max |u| = 5"));
}

TEST_CASE("static start: a prescribed support displacement at t = 0 is honored, v(0) kept") {
  // g(t) = 0.5 + t: the static solve takes g(0) = 0.5; the given velocity meets g'(0) = 1.
  const auto scene = test::built(parse_scene_text(
      chain(R"({ type = "polynomial", coefficients = [0.5, 1.0] })", "velocity = { x1 = 1.0 }\n"),
      "chain.toml"));
  const Model& m = scene.model;
  check_close(m.u0[0], 0.5);
  check_close(m.u0[1], 3.5);
  check_close(m.u0[2], 5.5);
  CHECK(m.v0[0] == 1.0);
}

TEST_CASE("static start: the ground motion at t = 0 is one of the loads, and the line says so") {
  // x3 is accelerated by a_g = 2 (mass 1): its load 6 becomes 6 - 2 = 4, u = (0, 2, 2 + 4/3).
  const std::string ground = "[ground_motion]\ninfluence = { x3 = 1.0 }\nacceleration = 2.0\n";
  const auto scene = test::built(parse_scene_text(
      test::replace(chain("0.0", ""), "[solve]", ground + "[solve]"), "chain.toml"));
  check_close(scene.model.u0[1], 2.0);
  check_close(scene.model.u0[2], 2.0 + 4.0 / 3.0);
  CHECK(contains(scene.report.initial_projection,
                 "; the loads at t = 0 include the ground motion's -M r a_g(0), a_g(0) = 2 (start "
                 "the record at 0 for a preload without it)"));
  // A record at rest at t = 0: the gravity-only equilibrium, and no note.
  const auto quiet = test::built(
      parse_scene_text(test::replace(chain("0.0", ""), "[solve]",
                                     test::replace(ground, "2.0\n",
                                                   "{ type = \"polynomial\", coefficients = "
                                                   "[0.0, 1.0] }\n") +
                                         "[solve]"),
                       "chain.toml"));
  check_close(quiet.model.u0[2], 5.0);
  CHECK(!contains(quiet.report.initial_projection, "ground motion"));
}

TEST_CASE("static start: refusals name initial.static") {
  SUBCASE("a DOF nothing holds") {
    const std::string e = build_error(R"([model]
type = "matrix"
dofs = ["a", "b"]
mass = [[1.0, 0.0], [0.0, 1.0]]
stiffness = [[1.0, 0.0], [0.0, 0.0]]
[initial]
static = true
[solve]
t_end = 1.0
output_step = 0.1
)");
    CHECK(contains(e, "initial.static"));
    CHECK(contains(e, "no static equilibrium"));
    CHECK(contains(e, "free to move: b"));
  }
  SUBCASE("a floating truss (rigid-body modes: K singular though every DOF has stiffness)") {
    const std::string e = build_error(R"([model]
type = "truss2d"
nodes = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]
masses = [1.0, 1.0, 1.0]
members = [{ nodes = [1, 2], EA = 100.0 }, { nodes = [2, 3], EA = 100.0 }, { nodes = [1, 3], EA = 100.0 }]
gravity = [0.0, -9.81]
[initial]
static = true
[solve]
t_end = 1.0
output_step = 0.1
)");
    CHECK(contains(e, "initial.static"));
    CHECK(contains(e, "no static equilibrium"));
    CHECK(contains(e, "singular"));
  }
  SUBCASE("an exact zero pivot: two DOFs free to move together, named") {
    const std::string e = build_error(R"([model]
type = "matrix"
dofs = ["a", "b", "c"]
mass = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]
stiffness = [[1.0, -1.0, 0.0], [-1.0, 1.0, 0.0], [0.0, 0.0, 1.0]]
[initial]
static = true
[solve]
t_end = 1.0
output_step = 0.1
)");
    CHECK(contains(e, "an exact zero pivot"));
    CHECK((contains(e, "free to move: a, b (") || contains(e, "free to move: b, a (")));
  }
  SUBCASE("a wrong type") {
    const std::string e =
        build_error(test::replace(chain("0.0", ""), "static = true", "static = \"yes\""));
    CHECK(contains(e, "initial.static"));
    CHECK(contains(e, "expected true or false"));
  }
  SUBCASE("with given displacements") {
    const std::string e = build_error(chain("0.0", "displacement = { x2 = 1.0 }\n"));
    CHECK(contains(e, "initial.static"));
    CHECK(contains(e, "remove [initial] displacement"));
  }
  SUBCASE("with project = true") {
    const std::string e = build_error(chain("0.0", "project = true\n"));
    CHECK(contains(e, "initial.static"));
    CHECK(contains(e, "cannot be combined"));
  }
  SUBCASE("a nonlinear model") {
    const std::string e = build_error(R"([model]
type = "truss2d"
nodes = [[0.0, 0.0], [1.0, 0.0]]
masses = [0.0, 1.0]
supports = [1]
members = [{ nodes = [1, 2], rigid = true }]
gravity = [0.0, -9.81]
[initial]
static = true
[solve]
t_end = 1.0
output_step = 0.1
)");
    CHECK(contains(e, "initial.static"));
    CHECK(contains(e, "needs a linear model"));
  }
}

TEST_CASE("static start: penalty is refused, its springs would start unloaded") {
  // The equilibrium holds the constraints exactly, where penalty's springs carry no force: the
  // support's reaction is missing at t = 0 and the structure swings about it (review: a truss's
  // support reaction 0 at t = 0, then 34 to 82 N about the true 54 N, in 100,000 steps).
  const auto scene = test::built(parse_scene_text(chain("0.0", ""), "chain.toml"));
  const auto refusal = scheme_refusal(scene.model, Scheme::penalty);
  REQUIRE(refusal.has_value());
  CHECK(contains(*refusal,
                 "[initial] static = true gives the equilibrium under exact "
                 "constraints, where penalty's springs carry no force"));
  CHECK_FALSE(scheme_refusal(scene.model, Scheme::ggl).has_value());
  // Without static = true penalty stays available.
  std::string given = chain("0.0", "");
  given.replace(given.find("static = true"), 13, "displacement = { x2 = 3.0, x3 = 5.0 }");
  const auto plain = test::built(parse_scene_text(given, "given.toml"));
  CHECK_FALSE(scheme_refusal(plain.model, Scheme::penalty).has_value());
}

}  // namespace test_static_start
