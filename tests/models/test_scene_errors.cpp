// Every bad input is refused before integration with a message naming the file, the line or key,
// and the problem.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "models/assembly/build_model.hpp"
#include "models/core/model.hpp"
#include "models/scene/scene_parser.hpp"
#include "tests/scene_errors.hpp"
#include "tests/scene_text.hpp"

using namespace condyn;

namespace test_scene_errors {

using condyn::test::build_error;
using condyn::test::check_build_error;

using condyn::test::replace;

namespace {

/// Machine epsilon: roundoff bounds below are multiples of it times a stated scale.
constexpr double kEps = std::numeric_limits<double>::epsilon();

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

}  // namespace

TEST_CASE("the base scene is valid" * doctest::test_suite("smoke")) {
  CHECK(build_error(kBase).empty());
}

TEST_CASE("syntax and structure" * doctest::test_suite("smoke")) {
  check_build_error(kBase + "\n[solve2]\n", "solve2: unknown key");
  check_build_error(replace(kBase, "t_end = 1.0", "t_end = 1.0\nrtoll = 1e-6"),
                    "solve.rtoll: unknown key");
  check_build_error(replace(kBase, "[[load]]", "[[load]\n"), "TOML syntax error");
  check_build_error(replace(kBase, "type = \"truss2d\"", "type = \"truss4d\""),
                    "unknown model type");
  check_build_error(replace(kBase, "type = \"truss2d\"", "type = \"truss3d\""),
                    "model.nodes[1]: a node is [x, y, z]");
  check_build_error(replace(kBase, "masses = [1.0, 1.0]\n", ""),
                    "model.masses: missing required key");
  check_build_error(replace(kBase, "value = 1.0", "value = \"one\""),
                    "load[1].value: expected a number");
  check_build_error(replace(kBase, "value = 1.0", "value = { type = \"ramp\" }"),
                    "unknown time function");
  check_build_error(
      replace(kBase, "value = 1.0", "value = { type = \"harmonic\", amplitude = 1.0 }"),
      "load[1].value.omega: missing required key");
  check_build_error(
      replace(kBase, "value = 1.0", "value = { type = \"step\", amplitude = 1.0, strat = 2.0 }"),
      "load[1].value.strat: unknown key");
}

TEST_CASE("line numbers point at the offending value") {
  const std::string msg = build_error(replace(kBase, "EA = 10.0", "EA = -10.0"));
  CHECK(msg.find("bad.toml:6:") == 0);
  CHECK(msg.find("model.members[1].EA: must be > 0") != std::string::npos);
}

TEST_CASE("values out of range") {
  check_build_error(replace(kBase, "masses = [1.0, 1.0]", "masses = [1.0, -1.0]"),
                    "model.masses[2]: a mass must be >= 0");
  check_build_error(replace(kBase, "masses = [1.0, 1.0]", "masses = [1.0, nan]"),
                    "model.masses[2]: must be finite");
  check_build_error(replace(kBase, "masses = [1.0, 1.0]", "masses = [1.0, inf]"), "must be finite");
  check_build_error(replace(kBase, "masses = [1.0, 1.0]", "masses = [1.0]"),
                    "has 1 entries for 2 nodes");
  check_build_error(replace(kBase, "t_end = 1.0", "t_end = 0.0"), "solve.t_end: must be > 0");
  // A nonzero number below the double range was read as 0 without a word: a check's value of
  // 1e-400 at tolerance 0 then passed on a computed 0.
  check_build_error(
      replace(kBase, "masses = [1.0, 1.0]", "masses = [1.0, -2.5e-400]"),
      "bad.toml:5: model.masses[2]: -2.5e-400 is nonzero but below the smallest double");
  check_build_error(
      replace(kBase, "value = 1.0", "value = 1_0e-4_00"),
      "bad.toml:10: load[1].value: 1_0e-4_00 is nonzero but below the smallest double");
  check_build_error(replace(kBase, "EA = 10.0", "EA = 10.0, x = 0.000_1e-330"),
                    "model.members[1].x: 0.000_1e-330 is nonzero");
  // toml++ counts columns in code points: with "ééé" earlier on the line, the 0.0 after 12 was
  // read at the byte offset of 12 and refused as "12 is nonzero but below ...".
  check_build_error(replace(kBase, "value = 1.0",
                            "value = { type = \"polynomial\", coefficients = [\"ééé\", 12,0.0] }"),
                    "load[1].value.coefficients[1]: expected a number");
  check_build_error(
      replace(kBase, "value = 1.0",
              "value = { type = \"polynomial\", coefficients = [\"ééé\", 12,1e-999] }"),
      "load[1].value.coefficients[3]: 1e-999 is nonzero");
  // On such a line each column is found on from the last one asked for: zeros before the value,
  // and keys visited in their order (a, then z) where the text has z first.
  check_build_error(
      replace(kBase, "value = 1.0",
              "value = { type = \"polynomial\", coefficients = [\"é\", 0.0, -0.0, 3e-999] }"),
      "load[1].value.coefficients[4]: 3e-999 is nonzero");
  check_build_error(replace(kBase, "EA = 10.0", "EA = 10.0, note = \"é\", z = 2e-999, a = 0.0"),
                    "model.members[1].z: 2e-999 is nonzero");
  // Zero written any way is zero.
  for (const char* zero : {"0.0", "-0.0", "0e-400", "0.000e5", "+0.0"}) {
    CAPTURE(zero);
    CHECK(build_error(replace(kBase, "value = 1.0", std::string("value = ") + zero)).empty());
  }
  // IDA's stop-time test multiplies times and steps: at 1e-200 it underflowed and the run was
  // refused at t = 0 as "tstop = 1e-200 is behind current t = 0".
  check_build_error(
      replace(replace(kBase, "t_end = 1.0", "t_end = 1e-200"), "output_step = 0.1",
              "output_step = 1e-200"),
      "solve.t_end: 1e-200 is below 1e-150, where the integrator's products of times and "
      "steps underflow: express time in a smaller unit");
  check_build_error(replace(kBase, "output_step = 0.1", "output_step = -0.1"),
                    "solve.output_step: must be > 0");
  check_build_error(replace(kBase, "output_step = 0.1", "output_step = 2.0"), "larger than t_end");
  check_build_error(replace(kBase, "output_step = 0.1", "output_step = 1e-9"), "would write");
  check_build_error(
      replace(kBase, "value = 1.0", "value = { type = \"exponential\", rate = 800.0 }"),
      "overflows before t_end");
  check_build_error(replace(kBase, "members = [{ nodes = [1, 2], EA = 10.0 }]",
                            "members = [{ nodes = [1, 3], EA = 10.0 }]"),
                    "node 3 does not exist");
  check_build_error(
      replace(kBase, "nodes = [[0.0, 0.0], [1.0, 0.0]]", "nodes = [[0.0, 0.0], [0.0, 0.0]]"),
      "zero length");
}

TEST_CASE("unknown DOF names") {
  check_build_error(replace(kBase, "dof = \"ux2\"", "dof = \"ux9\""),
                    "load[1].dof: no such DOF 'ux9'");
  // At the line of the key in its inline table (14), not of the [[constraint]] header (12).
  check_build_error(replace(kBase, "terms = { ux1 = 1.0 }", "terms = { ux9 = 1.0 }"),
                    "bad.toml:14: constraint[1].terms.ux9: no such DOF");
  check_build_error(kBase + "[initial]\nproject = false\ndisplacement = { uz1 = 1.0 }\n",
                    "bad.toml:29: initial.displacement.uz1: no such DOF");
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
  CHECK(build_error(matrix).empty());
  check_build_error(replace(matrix, "[[2.0, -1.0], [-1.0, 2.0]]", "[[2.0, -1.0], [-1.5, 2.0]]"),
                    "model.stiffness: is not symmetric: entry (2,1)");
  // A table of none of the forms names every form (an empty damping table read as a file whose
  // key was missing: "model.damping.file: missing required key").
  check_build_error(
      replace(matrix, "[solve]", "damping = { }\n[solve]"),
      "bad.toml:6: model.damping: is an empty table: expected rows ([[...], ...]) or { "
      "file = \"C.mtx\" }, { rayleigh = [a0, a1] } or { modal = ratio }");
  check_build_error(
      replace(matrix, "mass = [[1.0, 0.0], [0.0, 1.0]]", "mass = { fil = \"M.mtx\" }"),
      "bad.toml:4: model.mass: is a table without a known key: expected rows");
  // Values alike to ten digits are shown to round-trip precision: "-1 but -1" told nothing.
  check_build_error(
      replace(matrix, "[[2.0, -1.0], [-1.0, 2.0]]", "[[2.0, -1.0000000001], [-1.0, 2.0]]"),
      "entry (2,1) = -1 but (1,2) = -1.0000000001 (they differ by");
  // Refused at the key's own line (the mass on line 4, the stiffness on 5, damping on 6), not
  // at the [model] table's.
  check_build_error(
      replace(matrix, "mass = [[1.0, 0.0], [0.0, 1.0]]", "mass = [[1.0, 0.0], [0.0, -1.0]]"),
      "bad.toml:4: model.mass: is not positive semi-definite");
  check_build_error(replace(matrix, "[[2.0, -1.0], [-1.0, 2.0]]", "[[2.0, -3.0], [-3.0, 2.0]]"),
                    "bad.toml:5: model.stiffness: is not positive semi-definite");
  check_build_error(replace(matrix, "[solve]", "damping = [[1.0, 0.0], [0.0, -1.0]]\n[solve]"),
                    "bad.toml:6: model.damping: is not positive semi-definite");
  // Each matrix finite, their ratio not: ω² ≈ K_ii / M_ii = 2e160 / 1e-160 overflows. Spectra's
  // eigensolve failed on it (exit 1, no key).
  check_build_error(
      replace(replace(matrix, "[[1.0, 0.0], [0.0, 1.0]]", "[[1e-160, 0.0], [0.0, 1e-160]]"),
              "[[2.0, -1.0], [-1.0, 2.0]]", "[[2e160, -1e160], [-1e160, 2e160]]"),
      "bad.toml:5: model.stiffness: DOF 'a': K_ii / M_ii = 2e+160 / 1e-160 overflows");
  check_build_error(replace(matrix, "[[2.0, -1.0], [-1.0, 2.0]]", "[[2.0, -1.0], [-1.0]]"),
                    "model.stiffness[2]: has 1 entries for 2 DOFs");
  check_build_error(replace(matrix, "dofs = [\"a\", \"b\"]", "dofs = [\"a\", \"a\"]"),
                    "duplicate DOF name 'a'");
  // A DOF with neither mass, stiffness, damping nor constraint.
  check_build_error(
      replace(replace(matrix, "mass = [[1.0, 0.0], [0.0, 1.0]]", "mass = [[1.0, 0.0], [0.0, 0.0]]"),
              "[[2.0, -1.0], [-1.0, 2.0]]", "[[2.0, 0.0], [0.0, 0.0]]"),
      "DOF 'b' has neither mass nor stiffness");
}

TEST_CASE("a velocity row that conflicts through the initial displacements says so") {
  // v is p's derivative: they agree as written, but v's position form a + b = 0.06 + 0.1 t takes
  // a + b = 0.06 from [initial] where p asks 0.05. "Conflicting" alone sent the user to the
  // constraints.
  const std::string scene = R"([model]
type = "matrix"
dofs = ["a", "b", "c"]
mass = [[1.0, 0.0, 0.0], [0.0, 2.0, 0.0], [0.0, 0.0, 1.0]]
stiffness = [[4.0, -1.0, 0.0], [-1.0, 2.0, -1.0], [0.0, -1.0, 1.0]]
[[constraint]]
name = "v"
level = "velocity"
terms = { a = 1.0, b = 1.0 }
value = 0.1
[[constraint]]
name = "p"
terms = { a = 1.0, b = 1.0 }
value = { type = "polynomial", coefficients = [0.05, 0.1] }
[initial]
displacement = { a = 0.05, b = 0.01 }
velocity = { a = 0.1 }
[solve]
t_end = 1.0
output_step = 0.5
)";
  const std::string msg = build_error(scene);
  CAPTURE(msg);
  CHECK(msg.find("so the set is conflicting: no motion satisfies it. The velocity row 'v' holds "
                 "at position level as a·u = a·u(0) + the integral of its value, with a·u(0) from "
                 "the initial displacements") != std::string::npos);
  // Position rows alone: no such note.
  const std::string positions = build_error(
      replace(replace(scene, "level = \"velocity\"\n", ""), "value = 0.1", "value = 0.2"));
  CAPTURE(positions);
  CHECK(positions.find("conflicting") != std::string::npos);
  CHECK(positions.find("velocity row") == std::string::npos);
}

TEST_CASE("redundant and conflicting constraints are named") {
  const std::string redundant = replace(
      kBase, "[solve]", "[[constraint]]\nname = \"again\"\nterms = { ux1 = 2.0 }\n\n[solve]");
  const std::string msg = build_error(redundant);
  CAPTURE(msg);
  CHECK(msg.find("'pin_x'") != std::string::npos);
  CHECK(msg.find("'again'") != std::string::npos);
  CHECK(msg.find("linearly dependent") != std::string::npos);
  CHECK(msg.find("compatible, so the set is redundant") != std::string::npos);
  const std::string conflicting =
      replace(kBase, "[solve]",
              "[[constraint]]\nname = \"again\"\nterms = { ux1 = 2.0 }\nvalue = { type = "
              "\"polynomial\", coefficients = [0.0, 1.0] }\n\n[solve]");
  const std::string msg2 = build_error(conflicting);
  CAPTURE(msg2);
  CHECK(msg2.find("incompatible") != std::string::npos);
  CHECK(msg2.find("conflicting") != std::string::npos);
  // Combination of three: ux1 + uy1 and ux1 − uy1 make pin_x, pin_y... dependent with them.
  const std::string three =
      replace(kBase, "[solve]",
              "[[constraint]]\nname = \"diag\"\nterms = { ux1 = 1.0, uy1 = 1.0 }\n\n[solve]");
  const std::string msg3 = build_error(three);
  CAPTURE(msg3);
  CHECK(msg3.find("'diag'") != std::string::npos);
  CHECK(msg3.find("'pin_x'") != std::string::npos);
  CHECK(msg3.find("'pin_y'") != std::string::npos);
  CHECK(msg3.find("'roll'") == std::string::npos);
  check_build_error(replace(kBase, "terms = { ux1 = 1.0 }", "terms = { ux1 = 0.0 }"),
                    "has no nonzero coefficient");
}

/// A pendulum driven along x from the horizontal: the rod's row and the drive are parallel at
/// t = 0 only (x = 1 − t²/2, y = −t √(1 − t²/4) is a motion). Its [solve] table is last.
const std::string kDrivenPendulum = R"([model]
type = "truss2d"
nodes = [[0.0, 0.0], [1.0, 0.0]]
masses = [0.0, 1.0]
supports = [1]
members = [{ nodes = [1, 2], rigid = true }]
[[constraint]]
name = "drive"
terms = { ux2 = 1.0 }
value = { type = "polynomial", coefficients = [0.0, 0.0, -0.5] }
[initial]
velocity = { uy2 = -1.0 }
[solve]
t_end = 1.0
output_step = 0.1
)";

TEST_CASE("a nonlinear set dependent at the start is a singular configuration, not a conflict") {
  // A pendulum driven along x from the horizontal: the rod's row and the drive are parallel at
  // t = 0 only (x = 1 − t²/2, y = −t √(1 − t²/4) is a motion), and the set was refused as
  // "conflicting: no motion satisfies it".
  const std::string msg = build_error(kDrivenPendulum);
  CAPTURE(msg);
  CHECK(msg.find("are linearly dependent at the initial configuration") != std::string::npos);
  CHECK(msg.find("'rigid_1_2' is nonlinear, so this is a singular configuration of the set") !=
        std::string::npos);
  CHECK(msg.find("'drive'") != std::string::npos);
  CHECK(msg.find("conflicting") == std::string::npos);
  CHECK(msg.find("no motion satisfies it") == std::string::npos);
}

TEST_CASE("redundant = drop on a set dependent at a singular start is refused: not redundant") {
  // The same driven pendulum asking for drop: the rod's row and the drive are dependent at t = 0
  // only, so dropping either would lose it for the rest of the motion. The second-order test
  // (their accelerations' right-hand sides do not combine as their gradients do along the motions
  // the rows allow) tells it from a redundant joint (tests/models/test_nonlinear_drop.cpp).
  const std::string msg = build_error(kDrivenPendulum + "redundant = \"drop\"\n");
  CAPTURE(msg);
  CHECK(msg.rfind("bad.toml:", 0) == 0);
  CHECK(msg.find("'rigid_1_2'") != std::string::npos);
  CHECK(msg.find("'drive'") != std::string::npos);
  CHECK(msg.find("[solve] redundant = \"drop\" asks to drop one, but they are not redundant: "
                 "along a motion they allow there, their dependence fails at second order") !=
        std::string::npos);
  CHECK(msg.find("so this is a singular configuration of the set") != std::string::npos);
}

TEST_CASE("a second rigid member between the same nodes is refused, naming the first") {
  // It repeats the first's row (dependent everywhere), and both took the name rigid_1_2: the
  // message spoke of a singular configuration, two columns lambda_rigid_1_2. Either order of the
  // nodes; an elastic member beside a rigid one is allowed.
  const std::string scene = R"([model]
type = "truss2d"
nodes = [[0.0, 0.0], [1.0, 0.0]]
masses = [0.0, 1.0]
supports = [1]
members = [{ nodes = [1, 2], rigid = true }, SECOND]
gravity = [0.0, -9.81]
[solve]
t_end = 1.0
output_step = 0.1
)";
  for (const char* second :
       {"{ nodes = [1, 2], rigid = true }", "{ nodes = [2, 1], rigid = true }"}) {
    const std::string msg = build_error(replace(scene, "SECOND", second));
    CAPTURE(msg);
    CHECK(msg.find(":6: model.members[2].nodes: nodes 1 and 2 are already joined rigidly by "
                   "model.members[1]: a second rigid member repeats its constraint; remove one") !=
          std::string::npos);
  }
  CHECK(build_error(replace(scene, "SECOND", "{ nodes = [2, 1], EA = 10.0 }")).empty());
}

TEST_CASE("with an initial projection a conflicting linear set is named as such") {
  // The projection met the dependent rows first and said only that no velocity satisfies them:
  // the rank check, which does not depend on the state for linear
  // rows, now names them and says they conflict.
  const std::string drives = R"([[constraint]]
name = "drive"
terms = { ux2 = 1.0 }
value = { type = "harmonic", amplitude = 0.1, omega = 10.0 }

[[constraint]]
name = "drive2"
terms = { ux2 = 2.0 }
value = { type = "harmonic", amplitude = AMPLITUDE, omega = 10.0 }

[initial]
project = true

[solve])";
  const std::string scene = replace(kBase, "[solve]", drives);
  const std::string msg = build_error(replace(scene, "AMPLITUDE", "0.3"));
  CAPTURE(msg);
  CHECK(msg.find("the constraints 'drive2', 'drive' are linearly dependent") != std::string::npos);
  CHECK(msg.find("so the set is conflicting: no motion satisfies it") != std::string::npos);
  CHECK(msg.find("cannot project") == std::string::npos);
  // Compatible and dropped: it builds.
  CHECK(build_error(replace(replace(scene, "AMPLITUDE", "0.2"), "output_step = 0.1",
                            "output_step = 0.1\nredundant = \"drop\"")) == "");
}

TEST_CASE("inconsistent initial conditions name the constraint and the residual") {
  check_build_error(
      kBase + "[initial]\ndisplacement = { ux1 = 0.25 }\n",
      "initial displacements violate constraint 'pin_x': a·u(0) = 0.25 but the constraint "
      "requires 0 (residual 0.25)");
  check_build_error(kBase + "[initial]\nvelocity = { uy2 = -2.0 }\n",
                    "initial velocities violate constraint 'roll'");
  // A moving support needs the matching initial velocity.
  check_build_error(
      replace(
          kBase, "terms = { uy2 = 1.0 }",
          "terms = { uy2 = 1.0 }\nvalue = { type = \"harmonic\", amplitude = 0.1, omega = 2.0 }"),
      "a·v(0) = 0 but the constraint requires 0.2");
}

TEST_CASE("a position row and the velocity row of its derivative are redundant, not conflicting") {
  // ∫ 0.2 sin(2s + π/2) ds = 0.1 sin 2t: the integral's constant 0.1 cos(π/2) is 6e-18 in
  // doubles, and the pair was refused as conflicting ("leaves 6.123233996e-18 on the right").
  const std::string pair = R"([model]
type = "matrix"
dofs = ["u1", "u2"]
mass = [[1.0, 0.0], [0.0, 1.0]]
stiffness = [[2.0, -1.0], [-1.0, 1.0]]
[[constraint]]
name = "p"
terms = { u1 = 1.0 }
value = { type = "harmonic", amplitude = 0.1, omega = 2.0 }
[[constraint]]
name = "v"
level = "velocity"
terms = { u1 = 1.0 }
value = { type = "harmonic", amplitude = 0.2, omega = 2.0, phase = 1.5707963267948966 }
[initial]
velocity = { u1 = 0.2 }
[solve]
t_end = 1.0
output_step = 0.1
)";
  check_build_error(pair, "their right-hand sides are compatible, so the set is redundant");
  CHECK(build_error(
            replace(pair, "output_step = 0.1", "output_step = 0.1\nredundant = \"drop\"")) == "");
}

TEST_CASE("finite initial values whose forces overflow are refused at [initial]") {
  // K u(0) = 10 x 1e308: the run failed at t = 0 with "the solution became non-finite".
  check_build_error(
      kBase + "[initial]\ndisplacement = { ux2 = 1e308 }\n",
      "bad.toml:27: initial: the initial displacements times the model's stiffness overflow "
      "the double range");
  CHECK(build_error(kBase + "[initial]\ndisplacement = { ux2 = 1e300 }\n") == "");
}

TEST_CASE("a right-hand side that is zero up to roundoff at t = 0 is met by zero initial values") {
  // A cosine drive (sin at phase π/2) needs a·v(0) = 0.2 cos(π/2) = 1.2e-17, a sin at phase π
  // a·u(0) = 1.2e-17, and 0.1 + 0.2 − 0.3 is 5.6e-17: each is roundoff of its own terms, and a
  // start at 0 was refused for it, with no key that could fix it (project = true neither).
  const auto drive = [](const std::string& value, const std::string& initial) {
    return replace(kBase, "terms = { uy2 = 1.0 }", "terms = { uy2 = 1.0 }\nvalue = " + value) +
           initial;
  };
  const std::string harmonic = R"({ type = "harmonic", amplitude = 0.1, omega = 2.0, phase = )";
  CHECK(build_error(drive(harmonic + "1.5707963267948966 }",
                          "[initial]\ndisplacement = { uy2 = 0.1 }\n")) == "");
  CHECK(build_error(drive(harmonic + "3.141592653589793 }",
                          "[initial]\nvelocity = { uy2 = -0.2 }\n")) == "");
  CHECK(
      build_error(drive(
          R"([{ type = "polynomial", coefficients = [0.1, 0, 1] }, { type = "polynomial", coefficients = [0.2] }, { type = "polynomial", coefficients = [-0.3] }])",
          "")) == "");
  // A violation beyond roundoff of the terms is still one.
  check_build_error(
      drive(harmonic + "1.5707963267948966 }", "[initial]\ndisplacement = { uy2 = 0.1000001 }\n"),
      "a·u(0) = 0.1000001 but the constraint requires 0.1");
  check_build_error(drive(harmonic + "1.5707963267948966 }",
                          "[initial]\ndisplacement = { uy2 = 0.1 }\nvelocity = { uy2 = 1e-9 }\n"),
                    "initial velocities violate constraint 'roll'");
}

TEST_CASE("constraint right-hand sides may not jump after t = 0") {
  check_build_error(replace(kBase, "terms = { uy2 = 1.0 }",
                            "terms = { uy2 = 1.0 }\nvalue = { type = \"step\", start = 0.5 }"),
                    "a step at t = 0.5 > 0 would make the prescribed displacement jump");
  check_build_error(
      replace(
          kBase, "terms = { uy2 = 1.0 }",
          "terms = { uy2 = 1.0 }\nlevel = \"velocity\"\nvalue = { type = \"step\", start = 0.5 }"),
      "prescribed velocity jump");
  // At t_end itself the last row would jump: refused too.
  check_build_error(replace(kBase, "terms = { uy2 = 1.0 }",
                            "terms = { uy2 = 1.0 }\nvalue = { type = \"step\", start = 1.0 }"),
                    "a step at t = 1 > 0 would make the prescribed displacement jump");
  // After t_end the run never reaches it: accepted with a warning, at both levels (a velocity
  // row's integral would have been a ramp).
  for (const std::string level : {"", "level = \"velocity\"\n"}) {
    CAPTURE(level);
    BuildReport report;
    const Model model = build_model(
        parse_scene_text(
            replace(kBase, "terms = { uy2 = 1.0 }",
                    "terms = { uy2 = 1.0 }\n" + level + "value = { type = \"step\", start = 1.5 }"),
            "s.toml"),
        report);
    REQUIRE(report.warnings.size() == 1);
    CHECK(report.warnings[0] ==
          "constraint[3].value: the step at t = 1.5 starts after t_end = 1 "
          "and has no effect on this run");
    CHECK(model.constraints[2].position_value.is_zero());
  }
  // A load's step after t_end, on a DOF or a pattern, is warned about as a constraint's is; it
  // used to be left out silently.
  {
    BuildReport report;
    const Model model = build_model(
        parse_scene_text(replace(kBase, "dof = \"ux2\"\nvalue = 1.0",
                                 "dof = \"ux2\"\nvalue = { type = \"step\", amplitude = 2.0, "
                                 "start = 3.0 }"),
                         "s.toml"),
        report);
    REQUIRE(report.warnings.size() == 1);
    CHECK(report.warnings[0] ==
          "load[1].value: the step at t = 3 starts after t_end = 1 and has no effect on this run");
    CHECK(model.applied_forces(1.0).cwiseAbs().maxCoeff() == 0.0);
  }
  // One ulp after t_end: warned with the figures that show why (10 digits printed "t = 1").
  BuildReport ulp;
  (void)build_model(parse_scene_text(replace(kBase, "terms = { uy2 = 1.0 }",
                                             "terms = { uy2 = 1.0 }\nvalue = { type = \"step\", "
                                             "start = 1.0000000000000002 }"),
                                     "s.toml"),
                    ulp);
  REQUIRE(ulp.warnings.size() == 1);
  CHECK(ulp.warnings[0].find("the step at t = 1.0000000000000002 starts after t_end = 1 ") !=
        std::string::npos);
}

TEST_CASE("duplicate names and bad output settings") {
  check_build_error(replace(kBase, "name = \"pin_y\"", "name = \"pin_x\""),
                    "duplicate constraint name 'pin_x': constraint[1] is named so too; give the "
                    "constraints distinct names");
  // The second constraint unnamed: its default name c2 is the first's given name.
  check_build_error(
      replace(replace(kBase, "name = \"pin_x\"", "name = \"c2\""), "name = \"pin_y\"\n", ""),
      "duplicate constraint name 'c2' (the default name of unnamed constraint[2]): "
      "constraint[1] is named so too");
  check_build_error(kBase + "[output]\nquantities = [\"displacement\", \"stress\"]\n",
                    "unknown quantity 'stress'");
  check_build_error(kBase + "[output]\nquantities = [\"drift\", \"drift\"]\n",
                    "'drift' is listed twice");
  check_build_error(replace(kBase, "output_step = 0.1", "output_step = 0.1\nscheme = \"rk4\""),
                    "unknown scheme 'rk4'");
  check_build_error(replace(kBase, "output_step = 0.1", "output_step = 0.1\nslaves = [\"uq1\"]"),
                    "solve.slaves");
  check_build_error(replace(kBase, "output_step = 0.1", "output_step = 0.1\nslaves = []"),
                    "solve.slaves: the list is empty; name one slave DOF per constraint");
  check_build_error(
      replace(kBase, "output_step = 0.1", "output_step = 0.1\npenalty = { weight = -5.0 }"),
      "solve.penalty.weight: must be > 0");
  check_build_error(
      replace(kBase, "output_step = 0.1", "output_step = 0.1\npenalty = { wieght = 5.0 }"),
      "solve.penalty.wieght: unknown key");
  check_build_error(
      replace(kBase, "output_step = 0.1", "output_step = 0.1\nbaumgarte = { alpha = 0.0 }"),
      "solve.baumgarte.alpha: must be > 0");
  // Gains whose terms overflow: NaN at t = 0 and a message about loads before (β = 1e160).
  check_build_error(
      replace(kBase, "output_step = 0.1", "output_step = 0.1\nbaumgarte = { beta = 1e160 }"),
      "solve.baumgarte.beta: beta^2 overflows the double range: give at most 1e150");
  check_build_error(
      replace(kBase, "output_step = 0.1", "output_step = 0.1\nbaumgarte = { alpha = 1e305 }"),
      "solve.baumgarte.alpha: 2 alpha overflows the double range: give at most 1e300");
  check_build_error(
      replace(kBase, "output_step = 0.1", "output_step = 0.1\nscheme = \"projektion\""),
      "unknown scheme 'projektion' (expected auto, elimination, index1, baumgarte, ggl, "
      "index2, index3, penalty, projection, newmark, hht, generalized_alpha, rattle)");
}

// Issue 6, robustness under bad input: what the fuzzer (tests/fuzz/fuzz_scene.cpp) and a reading
// of the parser and builder found. Each input once crashed, hung or was accepted with an inf or
// NaN in the model; each is now refused with a message naming the file, the line and the key.

TEST_CASE("fuzz: an exponential load that overflows below the rate limit") {
  // exp(7 * 100) is finite but 1e300 times it is not: the load was accepted as inf.
  check_build_error(
      replace(replace(kBase, "value = 1.0",
                      "value = { type = \"exponential\", amplitude = 1e300, rate = 7.0 }"),
              "t_end = 1.0", "t_end = 100.0"),
      "bad.toml:8: load[1].value: 1e+300*exp(7*t) or its first two time derivatives "
      "overflow the double range");
  // Derivatives count too: a harmonic whose omega^2 overflows, a polynomial past 1e308.
  check_build_error(
      replace(kBase, "value = 1.0",
              "value = { type = \"harmonic\", amplitude = 1e200, omega = 1e120 }"),
      "load[1].value: 1e+200*sin(1e+120*t+0) or its first two time derivatives overflow");
  check_build_error(
      replace(replace(kBase, "value = 1.0",
                      "value = { type = \"polynomial\", coefficients = [0.0, 0.0, 1.0] }"),
              "t_end = 1.0\noutput_step = 0.1", "t_end = 1e200\noutput_step = 1e195"),
      "load[1].value: 1*t^2 or its first two time derivatives overflow");
  // Two finite loads on one DOF that add up to inf.
  check_build_error(
      replace(kBase, "dof = \"ux2\"\nvalue = 1.0",
              "dof = \"ux2\"\nvalue = 1.7e308\n\n[[load]]\ndof = \"ux2\"\nvalue = 1.7e308"),
      "bad.toml:12: load[2].value: the loads on DOF 'ux2' add up to more than the double "
      "range");
}

TEST_CASE("deeply nested keys are refused before toml++ overflows its stack") {
  // toml++ 3.3 recursed once per key part and segfaulted on these (about 30000 parts).
  std::string dotted = "a";
  for (int i = 0; i < 100000; ++i) dotted += ".a";
  check_build_error(dotted + " = 1\n" + kBase,
                    "bad.toml:1: a dotted key or table header nests more than 32 tables deep");
  check_build_error(kBase + "[" + dotted + "]\n",
                    "bad.toml:27: a dotted key or table header nests more than 32 tables deep");
  // Dots inside strings, comments and numbers are not key parts.
  CHECK(build_error(replace(kBase, "name = \"base\"",
                            "name = \"" + dotted + "\" # " + dotted + "\n# '''" + dotted)) == "");
  CHECK(build_error(replace(kBase, "name = \"base\"", "name = '''\n" + dotted + "\n'''")) == "");
}

TEST_CASE("geometry and gravity that overflow the double range") {
  // |x2 - x1| = 3.4e308 overflowed to inf: K held NaN (EA / inf * inf / inf).
  check_build_error(
      replace(kBase, "nodes = [[0.0, 0.0], [1.0, 0.0]]",
              "nodes = [[-1.7e308, 0.0], [1.7e308, 0.0]]"),
      "bad.toml:6: model.members[1]: member joins nodes 1 and 2, whose distance overflows");
  // Coordinates of 1e200 square to inf, but the length is finite: the bar lost its stiffness
  // (EA / inf = 0) without a word. Now K = EA / L.
  const Model far = build_model(parse_scene_text(
      replace(kBase, "nodes = [[0.0, 0.0], [1.0, 0.0]]", "nodes = [[0.0, 0.0], [1e200, 0.0]]"),
      "bad.toml"));
  // EA / L to a few roundings: 4 eps relative (observed exact).
  CHECK(std::abs(far.K->coeff(2, 2) / 1e-199 - 1.0) < 4 * kEps);
  // Lengths of 1e-300 squared to 0: "zero length" for nodes that do not coincide.
  check_build_error(replace(replace(kBase, "nodes = [[0.0, 0.0], [1.0, 0.0]]",
                                    "nodes = [[0.0, 0.0], [1e-300, 0.0]]"),
                            "EA = 10.0", "EA = 1e10"),
                    "model.members[1].EA: EA / length = 1e+10 / 1e-300 overflows the double range");
  check_build_error(
      replace(kBase, "masses = [1.0, 1.0]", "masses = [1.0, 1e300]\ngravity = [0.0, -1e10]"),
      "bad.toml:2: model.gravity: the weight of node 2 (mass 1e+300 times -1e+10) overflows");
  const std::string matrix = R"([model]
type = "matrix"
dofs = ["a", "b"]
mass = [[1e308, 1e308], [1e308, 1e308]]
stiffness = [[1.0, 0.0], [0.0, 1.0]]
[solve]
t_end = 1.0
output_step = 0.5
)";
  check_build_error(matrix, "model.mass: has eigenvalues beyond the double range");
}

TEST_CASE("constraints with coefficients or initial values near the double range") {
  // The row norm overflowed (1e200^2) or underflowed (1e-200^2): a valid set was called
  // dependent, or a row "without a nonzero coefficient".
  CHECK(build_error(replace(kBase, "terms = { ux1 = 1.0 }", "terms = { ux1 = 1e200 }")) == "");
  CHECK(build_error(replace(kBase, "terms = { ux1 = 1.0 }", "terms = { ux1 = 1e-200 }")) == "");
  check_build_error(
      replace(kBase, "[solve]",
              "[[constraint]]\nname = \"again\"\nterms = { ux1 = 1e200 }\n\n[solve]"),
      "the constraints 'again', 'pin_x' are linearly dependent (constraint matrix rank 3 < "
      "4); their right-hand sides are compatible");
  // Two dependent rows: the refusal names the first pair and says there are more.
  check_build_error(
      replace(kBase, "[solve]",
              "[[constraint]]\nname = \"again\"\nterms = { ux1 = 2.0 }\n\n"
              "[[constraint]]\nname = \"twice\"\nterms = { ux1 = -3.0 }\n\n[solve]"),
      "(constraint matrix rank 3 < 5: 2 constraints depend on others, these are the "
      "first found); their right-hand sides are compatible, so the set is redundant: "
      "remove one of them, or set [solve] redundant = \"drop\" to drop it (a run then "
      "lists each redundant constraint it drops)");
  // a·u(0) = 1e150 * 1e300 overflowed to inf and inf > tolerance * inf is false: the start passed
  // as consistent.
  check_build_error(
      replace(kBase, "terms = { uy2 = 1.0 }", "terms = { uy2 = 1e150 }") +
          "[initial]\ndisplacement = { uy2 = 1e300 }\n",
      "bad.toml:27: initial: a·u(0) or a·v(0) of constraint 'roll' overflows the double "
      "range");
  check_build_error(
      replace(kBase, "terms = { uy2 = 1.0 }", "terms = { uy2 = 1e150 }\nlevel = \"velocity\"") +
          "[initial]\ndisplacement = { uy2 = 1e300 }\n",
      "initial: a·u(0) of constraint 'roll' overflows the double range");
  // h = sin(1e-310 t) integrates to 1e-310 t²/2: in range, and computed without 1/ω (which
  // overflows), as A t sinc(ωt/2) sin(ωt/2).
  const std::string slow = replace(kBase, "terms = { uy2 = 1.0 }",
                                   "terms = { uy2 = 1.0 }\nlevel = \"velocity\"\nvalue = { type = "
                                   "\"harmonic\", omega = 1e-310 }");
  CHECK(build_error(slow) == "");
  const Model slow_model = build_model(parse_scene_text(slow, "slow.toml"));
  CHECK(slow_model.constraints[2].position_value.value(1.0) == 0.5e-310);
  // An integral beyond the double range is refused: |A| t_end = 1e308 x 10.
  check_build_error(
      replace(replace(kBase, "terms = { uy2 = 1.0 }",
                      "terms = { uy2 = 1.0 }\nlevel = \"velocity\"\nvalue = { type = "
                      "\"harmonic\", amplitude = 1e308, omega = 0.5 }"),
              "t_end = 1.0", "t_end = 10.0"),
      "constraint[3].value: integrating this velocity constraint's right-hand side from "
      "t = 0 gives 1e+308*int_0^t sin(0.5*s+0) ds, which overflows the double range");
}

TEST_CASE("a nonlinear model linearized at an initial state near the double range") {
  // Andrews' mechanism at beta' = 1e300 (projected: Theta' = -0.75e300, the only motion the
  // constraints allow there): its linearization holds inf. This was refused already, by the
  // consistency check (a residual of 1e282, with "set project = true" when it is set); the
  // finiteness check that guards every accepted model now names the cause first.
  check_build_error(
      "[model]\ntype = \"andrews\"\n\n[initial]\nvelocity = { beta = 1e300 }\nproject = "
      "true\n\n[solve]\nt_end = 0.03\noutput_step = 0.03\n",
      "bad.toml:4: initial: the stiffness matrix K linearized at the initial state has "
      "entries beyond the double range");
}

namespace {

/// A truss2d of `nodes` nodes in a row, unit masses, one bar, with `extra` appended.
std::string row_of_nodes(int nodes, const std::string& extra) {
  std::string coords, masses;
  for (int k = 0; k < nodes; ++k) {
    coords += (k ? ", [" : "[") + std::to_string(k) + ".0, 0.0]";
    masses += k ? ", 1.0" : "1.0";
  }
  return "[model]\ntype = \"truss2d\"\nnodes = [" + coords + "]\nmasses = [" + masses +
         "]\nmembers = [{ nodes = [1, 2], EA = 1.0 }]\n" + extra +
         "[solve]\nt_end = 1.0\noutput_step = 0.1\n";
}

}  // namespace

TEST_CASE("models beyond the old fixed limits build: size is judged by memory, not by count") {
  // 6000 DOFs, 6000 support rows: refused before as "more than condyn's limit of 5000"; the
  // supports are single-DOF rows, 6000 independent 1 x 1 rank checks.
  std::string supports;
  for (int k = 1; k <= 3000; ++k) supports += (k > 1 ? ", " : "") + std::to_string(k);
  CHECK(build_error(row_of_nodes(3000, "supports = [" + supports + "]\n")) == "");
  // 2001 rows chained through shared DOFs form one group of 2001 x 2002: refused before as "too
  // many for the dense rank check"; SuiteSparseQR factors it (all rows independent).
  std::string chain;
  for (int k = 1; k <= 1001; ++k) {
    const std::string x = "ux" + std::to_string(k), y = "uy" + std::to_string(k);
    chain += "[[constraint]]\nterms = { " + x + " = 1.0, " + y + " = -1.0 }\n";
    if (k < 1001)
      chain +=
          "[[constraint]]\nterms = { " + y + " = 1.0, ux" + std::to_string(k + 1) + " = -1.0 }\n";
  }
  CHECK(build_error(row_of_nodes(1001, chain)) == "");
}

TEST_CASE("redundant constraints are dropped with a report when the scene asks") {
  // The same row twice: refused by default, with the remedy named.
  const std::string twice = replace(kBase, "terms = { uy2 = 1.0 }",
                                    "terms = { uy2 = 1.0 }\n"
                                    "[[constraint]]\nname = \"again\"\nterms = { uy2 = 2.0 }");
  const std::string refused = build_error(twice);
  CHECK(refused.find("linearly dependent") != std::string::npos);
  CHECK(refused.find("redundant = \"drop\"") != std::string::npos);
  // Dropped on request: one constraint fewer, and the report names it and its partner.
  BuildReport report;
  const Model model = build_model(
      parse_scene_text(replace(twice, "t_end = 1.0", "t_end = 1.0\nredundant = \"drop\""), "s"),
      report);
  CHECK(model.constraint_count() == 3);
  CHECK(model.A.rows() == 3);
  REQUIRE(report.dropped_constraints.size() == 1);
  CHECK(report.dropped_constraints[0].find("(a combination of ") != std::string::npos);
  // Conflicting right-hand sides are refused even then: no motion satisfies them.
  const std::string conflicting =
      replace(twice, "terms = { uy2 = 2.0 }", "terms = { uy2 = 2.0 }\nvalue = 0.5");
  CHECK(build_error(replace(conflicting, "t_end = 1.0", "t_end = 1.0\nredundant = \"drop\""))
            .find("incompatible") != std::string::npos);
  CHECK(build_error(replace(kBase, "t_end = 1.0", "t_end = 1.0\nredundant = \"maybe\""))
            .find("solve.redundant: expected 'refuse' or 'drop'") != std::string::npos);
  // Of the same kind: a switch given as anything but a boolean.
  for (const char* given : {"1", "\"yes\"", "{ on = true }"}) {
    CHECK(build_error(
              replace(kBase, "t_end = 1.0", std::string("t_end = 1.0\nbridge_singular = ") + given))
              .find("solve.bridge_singular: expected true or false") != std::string::npos);
  }
  // A velocity row and the position row it integrates to: the velocity row goes, in either
  // order (dropping the position row left index1 drifting 0.6 from it, unmeasured).
  const std::string vel =
      "[[constraint]]\nname = \"vel\"\nlevel = \"velocity\"\nterms = { uy2 = 2.0 }\n";
  const std::string pos = "[[constraint]]\nname = \"pos\"\nterms = { uy2 = 1.0 }\n";
  for (const auto& [first, second] : {std::pair{vel, pos}, std::pair{pos, vel}}) {
    BuildReport both;
    const Model kept = build_model(
        parse_scene_text(replace(replace(kBase,
                                         "[[constraint]]\nname = \"roll\"\nterms = { uy2 = "
                                         "1.0 }\n",
                                         first + second),
                                 "t_end = 1.0", "t_end = 1.0\nredundant = \"drop\""),
                         "s"),
        both);
    REQUIRE(both.dropped_constraints.size() == 1);
    CHECK(both.dropped_constraints[0] ==
          "'vel' (a combination of 'pos'; their reactions carry its force too: not "
          "unique)");
    CHECK(kept.constraints.back().name == "pos");
  }
  // A nonlinear model (a rigid member) drops one of its two identical linear rows too (it was
  // refused: drop was for linear models only), and its system integrates the rest.
  const std::string nonlinear = replace(replace(twice, "EA = 10.0", "rigid = true"), "t_end = 1.0",
                                        "t_end = 1.0\nredundant = \"drop\"");
  BuildReport rigid;
  const Model with_rod = build_model(parse_scene_text(nonlinear, "s"), rigid);
  REQUIRE(with_rod.is_nonlinear());
  CHECK(rigid.dropped_constraints.size() == 1);
  CHECK(with_rod.system->constraints() == with_rod.constraint_count());
}

TEST_CASE("absurd magnitudes are accepted with a warning") {
  const auto warnings = [](const std::string& text) {
    BuildReport report;
    (void)build_model(parse_scene_text(text, "s.toml"), report);
    return report.warnings;
  };
  CHECK(warnings(kBase).empty());
  // EA = 1e20 over a unit length: K entries of 1e20.
  const auto stiff = warnings(replace(kBase, "EA = 10.0", "EA = 1e20"));
  REQUIRE_FALSE(stiff.empty());
  CHECK(stiff[0].find("stiffness matrix K has entries up to magnitude") != std::string::npos);
  // Masses 1 and 1e-16: a diagonal spread beyond what double precision resolves.
  const auto light = warnings(replace(kBase, "masses = [1.0, 1.0]", "masses = [1.0, 1e-16]"));
  bool spread = false;
  for (const auto& w : light) {
    spread = spread || w.find("diagonal of the mass matrix M spans") != std::string::npos;
  }
  CHECK(spread);
  // Initial values of 1e30: the run's motion is below their roundoff.
  const auto far = warnings(kBase + "[initial]\ndisplacement = { ux2 = 1e30 }\n");
  REQUIRE(far.size() == 1);
  CHECK(far[0] ==
        "[initial] displacements up to magnitude 1e+30: beyond 1e15, motion smaller than "
        "1e-16 of them is lost in roundoff; check the units");
  CHECK(warnings(kBase + "[initial]\nvelocity = { ux2 = -2e16 }\n").size() == 1);
  CHECK(warnings(kBase + "[initial]\nvelocity = { ux2 = 1e15 }\n").empty());
}

TEST_CASE("a dependent set of many constraints is named by its first 12 and counted") {
  // 15 DOFs tied in a chain, a_k = a_{k+1}, and a_1 = a_15 besides: a_1 = a_15 is the sum of the
  // 14 ties, so the 15 rows are dependent. The message named every one (4,001 on one line for a
  // chain of ties in a review).
  std::string dofs, mass, constraints;
  for (int k = 1; k <= 15; ++k) {
    dofs += std::string(k > 1 ? ", " : "") + "\"a" + std::to_string(k) + "\"";
    mass += std::string(k > 1 ? ", " : "") + "[";
    for (int j = 1; j <= 15; ++j) mass += std::string(j > 1 ? ", " : "") + (j == k ? "1.0" : "0.0");
    mass += "]";
    if (k < 15) {
      constraints += "[[constraint]]\nname = \"tie" + std::to_string(k) + "\"\nterms = { a" +
                     std::to_string(k) + " = 1.0, a" + std::to_string(k + 1) + " = -1.0 }\n";
    }
  }
  constraints += "[[constraint]]\nname = \"ends\"\nterms = { a1 = 1.0, a15 = -1.0 }\n";
  const std::string scene = "[model]\ntype = \"matrix\"\ndofs = [" + dofs + "]\nmass = [" + mass +
                            "]\nstiffness = [" + mass + "]\n" + constraints +
                            "[solve]\nt_end = 1.0\noutput_step = 0.5\n";
  const std::string msg = build_error(scene);
  CAPTURE(msg);
  CHECK(msg.find("are linearly dependent") != std::string::npos);
  CHECK(msg.find(" and 3 more (15 in all)") != std::string::npos);
  // Twelve names quoted before the count, each once (the order is the combination's).
  const std::string named = msg.substr(0, msg.find(" and 3 more"));
  CHECK(std::count(named.begin(), named.end(), '\'') == 24);
}

}  // namespace test_scene_errors
