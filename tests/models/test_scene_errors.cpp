// Every bad input is refused before integration with a message naming the file, the line or key,
// and the problem.
#include <doctest/doctest.h>

#include <string>

#include "models/model.hpp"
#include "models/scene_parser.hpp"

using namespace condyn;

namespace {

// A valid two-node scene; each case below changes one thing.
const std::string kBase = R"(name = "base"
[model]
type = "truss2d"
nodes = [[0.0, 0.0], [1.0, 0.0]]
masses = [1.0, 1.0]
members = [{ nodes = [1, 2], EA = 10.0 }]

[[load]]
dof = "ux2"
value = 1.0

[[constraint]]
name = "pin_x"
terms = { ux1 = 1.0 }

[[constraint]]
name = "pin_y"
terms = { uy1 = 1.0 }

[[constraint]]
name = "roll"
terms = { uy2 = 1.0 }

[solve]
t_end = 1.0
output_step = 0.1
)";

std::string replace(std::string s, const std::string& from, const std::string& to) {
  const auto pos = s.find(from);
  REQUIRE_MESSAGE(pos != std::string::npos, from);
  return s.replace(pos, from.size(), to);
}

/// The message of the SceneError thrown while parsing and building, or "" when none is thrown.
std::string error_of(const std::string& text) {
  try {
    (void)build_model(parse_scene_text(text, "bad.toml"));
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

void check_error(const std::string& text, const std::string& needle) {
  const std::string msg = error_of(text);
  CAPTURE(msg);
  CHECK(msg.rfind("bad.toml", 0) == 0);
  CHECK(msg.find(needle) != std::string::npos);
}

}  // namespace

TEST_CASE("the base scene is valid") { CHECK(error_of(kBase).empty()); }

TEST_CASE("syntax and structure") {
  check_error(kBase + "\n[solve2]\n", "solve2: unknown key");
  check_error(replace(kBase, "t_end = 1.0", "t_end = 1.0\nrtoll = 1e-6"),
              "solve.rtoll: unknown key");
  check_error(replace(kBase, "[[load]]", "[[load]\n"), "TOML syntax error");
  check_error(replace(kBase, "type = \"truss2d\"", "type = \"truss4d\""), "unknown model type");
  check_error(replace(kBase, "type = \"truss2d\"", "type = \"truss3d\""),
              "model.nodes[1]: a node is [x, y, z]");
  check_error(replace(kBase, "masses = [1.0, 1.0]\n", ""), "model.masses: missing required key");
  check_error(replace(kBase, "value = 1.0", "value = \"one\""), "load[1].value: expected a number");
  check_error(replace(kBase, "value = 1.0", "value = { type = \"ramp\" }"),
              "unknown time function");
  check_error(replace(kBase, "value = 1.0", "value = { type = \"harmonic\", amplitude = 1.0 }"),
              "load[1].value.omega: missing required key");
  check_error(
      replace(kBase, "value = 1.0", "value = { type = \"step\", amplitude = 1.0, strat = 2.0 }"),
      "load[1].value.strat: unknown key");
}

TEST_CASE("line numbers point at the offending value") {
  const std::string msg = error_of(replace(kBase, "EA = 10.0", "EA = -10.0"));
  CHECK(msg.find("bad.toml:6:") == 0);
  CHECK(msg.find("model.members[1].EA: must be > 0") != std::string::npos);
}

TEST_CASE("values out of range") {
  check_error(replace(kBase, "masses = [1.0, 1.0]", "masses = [1.0, -1.0]"),
              "model.masses[2]: a mass must be >= 0");
  check_error(replace(kBase, "masses = [1.0, 1.0]", "masses = [1.0, nan]"),
              "model.masses[2]: must be finite");
  check_error(replace(kBase, "masses = [1.0, 1.0]", "masses = [1.0, inf]"), "must be finite");
  check_error(replace(kBase, "masses = [1.0, 1.0]", "masses = [1.0]"), "has 1 entries for 2 nodes");
  check_error(replace(kBase, "t_end = 1.0", "t_end = 0.0"), "solve.t_end: must be > 0");
  check_error(replace(kBase, "output_step = 0.1", "output_step = -0.1"),
              "solve.output_step: must be > 0");
  check_error(replace(kBase, "output_step = 0.1", "output_step = 2.0"), "larger than t_end");
  check_error(replace(kBase, "output_step = 0.1", "output_step = 1e-9"), "would write");
  check_error(replace(kBase, "value = 1.0", "value = { type = \"exponential\", rate = 800.0 }"),
              "overflows before t_end");
  check_error(replace(kBase, "members = [{ nodes = [1, 2], EA = 10.0 }]",
                      "members = [{ nodes = [1, 3], EA = 10.0 }]"),
              "node 3 does not exist");
  check_error(
      replace(kBase, "nodes = [[0.0, 0.0], [1.0, 0.0]]", "nodes = [[0.0, 0.0], [0.0, 0.0]]"),
      "zero length");
}

TEST_CASE("unknown DOF names") {
  check_error(replace(kBase, "dof = \"ux2\"", "dof = \"ux9\""), "load[1].dof: no such DOF 'ux9'");
  check_error(replace(kBase, "terms = { ux1 = 1.0 }", "terms = { ux9 = 1.0 }"),
              "constraint[1].terms.ux9: no such DOF");
  check_error(kBase + "[initial]\ndisplacement = { uz1 = 1.0 }\n",
              "initial.displacement.uz1: no such DOF");
}

TEST_CASE("matrix models: symmetry and definiteness") {
  const std::string matrix = R"([model]
type = "matrix"
dofs = ["a", "b"]
mass = [[1.0, 0.0], [0.0, 1.0]]
stiffness = [[2.0, -1.0], [-1.0, 2.0]]
[solve]
t_end = 1.0
output_step = 0.5
)";
  CHECK(error_of(matrix).empty());
  check_error(replace(matrix, "[[2.0, -1.0], [-1.0, 2.0]]", "[[2.0, -1.0], [-1.5, 2.0]]"),
              "model.stiffness: is not symmetric: entry (2,1)");
  check_error(
      replace(matrix, "mass = [[1.0, 0.0], [0.0, 1.0]]", "mass = [[1.0, 0.0], [0.0, -1.0]]"),
      "model.mass: is not positive semi-definite");
  check_error(replace(matrix, "[[2.0, -1.0], [-1.0, 2.0]]", "[[2.0, -1.0], [-1.0]]"),
              "model.stiffness[2]: has 1 entries for 2 DOFs");
  check_error(replace(matrix, "dofs = [\"a\", \"b\"]", "dofs = [\"a\", \"a\"]"),
              "duplicate DOF name 'a'");
  // A DOF with neither mass, stiffness, damping nor constraint.
  check_error(
      replace(replace(matrix, "mass = [[1.0, 0.0], [0.0, 1.0]]", "mass = [[1.0, 0.0], [0.0, 0.0]]"),
              "[[2.0, -1.0], [-1.0, 2.0]]", "[[2.0, 0.0], [0.0, 0.0]]"),
      "DOF 'b' has neither mass nor stiffness");
}

TEST_CASE("redundant and conflicting constraints are named") {
  const std::string redundant = replace(
      kBase, "[solve]", "[[constraint]]\nname = \"again\"\nterms = { ux1 = 2.0 }\n\n[solve]");
  const std::string msg = error_of(redundant);
  CAPTURE(msg);
  CHECK(msg.find("'pin_x'") != std::string::npos);
  CHECK(msg.find("'again'") != std::string::npos);
  CHECK(msg.find("linearly dependent") != std::string::npos);
  CHECK(msg.find("compatible, so the set is redundant") != std::string::npos);
  const std::string conflicting =
      replace(kBase, "[solve]",
              "[[constraint]]\nname = \"again\"\nterms = { ux1 = 2.0 }\nvalue = { type = "
              "\"polynomial\", coefficients = [0.0, 1.0] }\n\n[solve]");
  const std::string msg2 = error_of(conflicting);
  CAPTURE(msg2);
  CHECK(msg2.find("incompatible") != std::string::npos);
  CHECK(msg2.find("conflicting") != std::string::npos);
  // Combination of three: ux1 + uy1 and ux1 − uy1 make pin_x, pin_y... dependent with them.
  const std::string three =
      replace(kBase, "[solve]",
              "[[constraint]]\nname = \"diag\"\nterms = { ux1 = 1.0, uy1 = 1.0 }\n\n[solve]");
  const std::string msg3 = error_of(three);
  CAPTURE(msg3);
  CHECK(msg3.find("'diag'") != std::string::npos);
  CHECK(msg3.find("'pin_x'") != std::string::npos);
  CHECK(msg3.find("'pin_y'") != std::string::npos);
  CHECK(msg3.find("'roll'") == std::string::npos);
  check_error(replace(kBase, "terms = { ux1 = 1.0 }", "terms = { ux1 = 0.0 }"),
              "has no nonzero coefficient");
}

TEST_CASE("inconsistent initial conditions name the constraint and the residual") {
  check_error(kBase + "[initial]\ndisplacement = { ux1 = 0.25 }\n",
              "initial displacements violate constraint 'pin_x': a·u(0) = 0.25 but the constraint "
              "requires 0 (residual 0.25)");
  check_error(kBase + "[initial]\nvelocity = { uy2 = -2.0 }\n",
              "initial velocities violate constraint 'roll'");
  // A moving support needs the matching initial velocity.
  check_error(
      replace(
          kBase, "terms = { uy2 = 1.0 }",
          "terms = { uy2 = 1.0 }\nvalue = { type = \"harmonic\", amplitude = 0.1, omega = 2.0 }"),
      "a·v(0) = 0 but the constraint requires 0.2");
}

TEST_CASE("constraint right-hand sides may not jump after t = 0") {
  check_error(replace(kBase, "terms = { uy2 = 1.0 }",
                      "terms = { uy2 = 1.0 }\nvalue = { type = \"step\", start = 0.5 }"),
              "a step at t = 0.5 > 0 would make the prescribed displacement jump");
  check_error(
      replace(
          kBase, "terms = { uy2 = 1.0 }",
          "terms = { uy2 = 1.0 }\nlevel = \"velocity\"\nvalue = { type = \"step\", start = 0.5 }"),
      "prescribed velocity jump");
}

TEST_CASE("duplicate names and bad output settings") {
  check_error(replace(kBase, "name = \"pin_y\"", "name = \"pin_x\""),
              "duplicate constraint name 'pin_x'");
  check_error(kBase + "[output]\nquantities = [\"displacement\", \"stress\"]\n",
              "unknown quantity 'stress'");
  check_error(kBase + "[output]\nquantities = [\"drift\", \"drift\"]\n", "'drift' is listed twice");
  check_error(replace(kBase, "output_step = 0.1", "output_step = 0.1\nscheme = \"rk4\""),
              "unknown scheme 'rk4'");
  check_error(replace(kBase, "output_step = 0.1", "output_step = 0.1\nslaves = [\"uq1\"]"),
              "solve.slaves");
  check_error(replace(kBase, "output_step = 0.1", "output_step = 0.1\npenalty = { weight = -5.0 }"),
              "solve.penalty.weight: must be > 0");
  check_error(replace(kBase, "output_step = 0.1", "output_step = 0.1\npenalty = { wieght = 5.0 }"),
              "solve.penalty.wieght: unknown key");
  check_error(replace(kBase, "output_step = 0.1", "output_step = 0.1\nbaumgarte = { alpha = 0.0 }"),
              "solve.baumgarte.alpha: must be > 0");
  check_error(replace(kBase, "output_step = 0.1", "output_step = 0.1\nscheme = \"projektion\""),
              "unknown scheme 'projektion' (expected auto, elimination, index1, baumgarte, ggl, "
              "index2, index3, penalty, projection)");
}
