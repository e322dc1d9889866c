// Issue 10, item 16: bad input that used to exit 1 (a failed run) without naming a key now exits
// 2 with FILE:LINE: key.path: problem.
#include <doctest/doctest.h>

#include <string>

#include "tests/cli_sandbox.hpp"
#include "tests/scene_text.hpp"

namespace test_cli_bad_input_keys {

using condyn::test::Result;
using condyn::test::Sandbox;

using condyn::test::replace;

namespace {

// Two masses on a bar, node 1 pinned by two constraints.
const std::string kScene = R"([model]
type = "truss2d"
nodes = [[0.0, 0.0], [1.0, 0.0]]
masses = [1.0, 1.0]
members = [{ nodes = [1, 2], EA = 10.0 }]

[[constraint]]
name = "pin_x"
terms = { ux1 = 1.0 }

[[constraint]]
name = "pin_y"
terms = { uy1 = 1.0 }

[solve]
t_end = 1.0
output_step = 0.5
)";

Result run_scene(const std::string& text, const std::string& flags = "") {
  Sandbox box;
  box.write("bad.toml", text);
  return box.run("run bad.toml --out out.csv " + flags);
}

void check_refused(const Result& r, const std::string& needle) {
  CAPTURE(r.err);
  CAPTURE(needle);
  CHECK(r.code == 2);
  CHECK(r.err.find(needle) != std::string::npos);
}

}  // namespace

TEST_CASE("a subnormal or negligible constraint coefficient is refused with its key") {
  // 5e-324 squared underflows: the elimination saw a zero row ("rank deficient", exit 1).
  check_refused(run_scene(replace(kScene, "terms = { uy1 = 1.0 }", "terms = { uy1 = 5e-324 }")),
                "bad.toml:13: constraint[2].terms.uy1: the coefficient 5e-324 is "
                "subnormal");
  check_refused(
      run_scene(replace(kScene, "terms = { uy1 = 1.0 }", "terms = { uy1 = 1.0, uy2 = 1e-20 }")),
      "bad.toml:13: constraint[2].terms.uy2: the coefficient 1e-20 is below the roundoff");
}

TEST_CASE("[solve] slaves repeated, too many or on unconstrained DOFs: refused with the key") {
  const auto with = [](const std::string& slaves) {
    return replace(kScene, "output_step = 0.5", "output_step = 0.5\nslaves = " + slaves);
  };
  check_refused(run_scene(with("[\"ux1\", \"ux1\"]")),
                "bad.toml:18: solve.slaves[2]: 'ux1' is named twice");
  check_refused(run_scene(with("[\"ux1\", \"uy1\", \"ux2\"]")),
                "bad.toml:18: solve.slaves[3]: 'ux2' appears in no constraint");
  check_refused(run_scene(with("[\"ux1\"]")),
                "bad.toml:18: solve.slaves: names 1 slave but the scene has 2 constraints");
  // Slaves each in a constraint, but their columns of A are dependent ([1 1; 2 2]).
  const std::string coupled =
      replace(replace(kScene, "terms = { ux1 = 1.0 }", "terms = { ux1 = 1.0, ux2 = 1.0 }"),
              "terms = { uy1 = 1.0 }", "terms = { uy1 = 1.0, ux1 = 2.0, ux2 = 2.0 }");
  check_refused(run_scene(replace(coupled, "output_step = 0.5",
                                  "output_step = 0.5\nslaves = [\"ux1\", \"ux2\"]")),
                "bad.toml:18: solve.slaves: the slaves ux1, ux2 do not determine the constraints");
}

TEST_CASE("a massless DOF nothing holds is bad input under every scheme, DOFs named") {
  // A triangle, node 1 pinned; node 3 without mass, held by two bars: its stiffness holds it, so
  // every scheme runs it, projection included (tests/dae/test_held_massless.cpp).
  const std::string triangle = condyn::test::kMasslessTriangleScene;
  for (const std::string scheme :
       {"ggl", "index1", "elimination", "penalty", "projection", "auto"}) {
    CAPTURE(scheme);
    CHECK(run_scene(triangle, "--scheme " + scheme).code == 0);
  }
  // One bar only (2-3): node 3 swings about node 2 with nothing to resist, a mechanism of
  // massless DOFs, though both have stiffness on their diagonal.
  const std::string one_bar = replace(triangle, ", { nodes = [1, 3], EA = 10.0 }]", "]");
  for (const std::string scheme : {"ggl", "index1", "elimination", "penalty", "projection"}) {
    CAPTURE(scheme);
    check_refused(run_scene(one_bar, "--scheme " + scheme),
                  "bad.toml:1: model.masses: 2 DOFs (ux3, uy3) have no mass and no constraint, "
                  "and their stiffness block K_hh is singular");
  }
  // Node 3 at (2, 0) on the bar 2-3 alone: uy3 has no stiffness at all, nothing holds it.
  check_refused(run_scene(replace(one_bar, "[0.0, 1.0]]", "[2.0, 0.0]]")),
                "bad.toml:1: model: DOF 'uy3' has neither mass nor stiffness nor damping nor a "
                "constraint");
  // The same line of nodes with rigid members: they do pass through uy3, but their gradient along
  // it is zero at the straight start, and the message says so rather than 'no constraint'.
  check_refused(run_scene(replace(replace(one_bar, "[0.0, 1.0]]", "[2.0, 0.0]]"), "EA = 10.0",
                                  "rigid = true")),
                "a constraint acting on it at the initial state (a nonlinear constraint through "
                "it, such as straight rigid members, can have a zero gradient there");
  // An all-massless triangle pinned at one node, under gravity: it turns about the pin, and no
  // mass resists (its weight is zero too).
  check_refused(
      run_scene(replace(replace(triangle, "masses = [1.0, 1.0, 0.0]", "masses = [0.0, 0.0, 0.0]"),
                        "supports = [1]", "supports = [1]\ngravity = [0.0, -9.81]")),
      "bad.toml:1: model.masses: 4 DOFs (ux2, uy2, ux3, uy3) have no mass and no constraint, and "
      "their stiffness block K_hh is singular");
  // A massless DOF that a constraint holds is fine (a massless support), under penalty too (its
  // penalty springs hold it).
  const std::string support = replace(kScene, "masses = [1.0, 1.0]", "masses = [0.0, 1.0]");
  CHECK(run_scene(support).code == 0);
  CHECK(run_scene(support, "--scheme penalty").code == 0);
}

TEST_CASE("a full mass matrix singular along a motion no constraint holds: refused, DOFs named") {
  const std::string matrix = R"([model]
type = "matrix"
dofs = ["a", "b"]
mass = [[1.0, 1.0], [1.0, 1.0]]
stiffness = [[2.0, -1.0], [-1.0, 2.0]]

[solve]
t_end = 1.0
output_step = 0.5
)";
  check_refused(run_scene(matrix, "--scheme ggl"),
                "bad.toml:1: model.mass: the mass matrix is singular along a motion of 2 DOFs "
                "(a, b) that no constraint holds");
  // Holding a fixes the motion (1, -1): accepted.
  const Result held = run_scene(matrix + "[[constraint]]\nterms = { a = 1.0 }\n", "--scheme ggl");
  CHECK(held.code == 0);
  // Two such motions, each held by its own row, the rows 1e150 apart in scale: both hold (the
  // rank test on A N unscaled took the small row's pivot for zero and refused the model).
  const std::string two = R"([model]
type = "matrix"
dofs = ["a", "b", "c", "d"]
mass = [[1.0, 1.0, 0.0, 0.0], [1.0, 1.0, 0.0, 0.0], [0.0, 0.0, 1.0, 1.0], [0.0, 0.0, 1.0, 1.0]]
stiffness = [[2.0, -1.0, 0.0, 0.0], [-1.0, 2.0, 0.0, 0.0], [0.0, 0.0, 2.0, -1.0], [0.0, 0.0, -1.0, 2.0]]
[[constraint]]
terms = { a = 1.0 }
[[constraint]]
terms = { c = 1e-150 }
[solve]
t_end = 1.0
output_step = 0.5
)";
  const Result scaled = run_scene(two, "--scheme index3");
  CAPTURE(scaled.err);
  CHECK(scaled.code == 0);
  check_refused(run_scene(replace(two, "terms = { c = 1e-150 }", "terms = { b = 1e-150 }")),
                "the mass matrix is singular along a motion of 2 DOFs (c, d)");
}

TEST_CASE("tolerances that are nan or inf are usage errors naming the flag or key") {
  for (const std::string flag : {"--rtol nan", "--atol nan", "--rtol inf", "--atol -inf"}) {
    CAPTURE(flag);
    const Result r = run_scene(kScene, flag);
    CHECK(r.code == 2);
    CHECK(r.err.find(flag.substr(0, 6)) != std::string::npos);
    CHECK(r.err.find("is not a decimal number") != std::string::npos);
  }
  check_refused(run_scene(replace(kScene, "output_step = 0.5", "output_step = 0.5\nrtol = nan")),
                "bad.toml:18: solve.rtol: must be finite");
  check_refused(run_scene(replace(kScene, "output_step = 0.5", "output_step = 0.5\natol = inf")),
                "bad.toml:18: solve.atol: must be finite");
}

TEST_CASE("an absolute tolerance too small for double-precision error weights is refused") {
  // atol 1e-300 was accepted and failed at the first load step with IDA_ILL_INPUT ("tstop is
  // behind current t") and advice about the load step times: the weights 1/atol overflow.
  for (const std::string flag : {"--atol 1e-300", "--atol 1e-101"}) {
    CAPTURE(flag);
    const Result r = run_scene(kScene, flag);
    CHECK(r.code == 2);
    CHECK(r.err.find("--atol") != std::string::npos);
    CHECK(r.err.find("at least 1e-100") != std::string::npos);
  }
  for (const std::string key : {"atol", "atol_velocity", "atol_multiplier", "atol_mu"}) {
    CAPTURE(key);
    const Result r =
        run_scene(replace(kScene, "output_step = 0.5", "output_step = 0.5\n" + key + " = 1e-300"));
    CHECK(r.code == 2);
    CHECK(r.err.find("bad.toml:18: solve." + key + ": is too small") != std::string::npos);
  }
  CHECK(run_scene(kScene, "--atol 1e-30").code == 0);  // tiny, but weighable: accepted
}

TEST_CASE("a file name with control characters is shown escaped in every message") {
  const Sandbox box;
  // ESC [ 2 J clears a terminal; ESC ] 0 ; ... BEL retitles it; CR hides what came before.
  const std::string clear = "clear\x1b[2J.toml";
  const std::string quoted_clear = "\"$(printf 'clear\\033[2J.toml')\"";
  box.write(clear, "[model\n");
  const auto no_raw_control = [](const std::string& text) {
    for (const char c : text) {
      const auto u = static_cast<unsigned char>(c);
      if ((u < 0x20 && c != '\n' && c != '\t') || u == 0x7f) return false;
    }
    return true;
  };
  const Result syntax = box.run("run " + quoted_clear + " --out o.csv");
  CAPTURE(syntax.err);
  CHECK(syntax.code == 2);
  CHECK(syntax.err.find("clear\\x1b[2J.toml:1") != std::string::npos);
  CHECK(no_raw_control(syntax.err));

  const Result missing = box.run("info \"$(printf 'gone\\033]0;pwned\\007\\r.toml')\"");
  CAPTURE(missing.err);
  CHECK(missing.code == 2);
  CHECK(missing.err.find("gone\\x1b]0;pwned\\x07\\x0d.toml: cannot open") != std::string::npos);
  CHECK(no_raw_control(missing.err));

  // check's report, on standard output, names the scene too (here: it has no [[check]]).
  const std::string fine = "fine\x1b[31m.toml";
  box.write(fine, kScene);
  const Result checked = box.run("check \"$(printf 'fine\\033[31m.toml')\"");
  CAPTURE(checked.out);
  CAPTURE(checked.err);
  CHECK(checked.code == 2);
  CHECK(checked.out.find("fine\\x1b[31m.toml: has no [[check]]") != std::string::npos);
  CHECK(no_raw_control(checked.out));
  CHECK(no_raw_control(checked.err));
}

TEST_CASE("output_step refusals name its own line, not [solve]'s") {
  check_refused(run_scene(replace(kScene, "output_step = 0.5", "output_step = 2.0")),
                "bad.toml:17: solve.output_step: is larger than t_end (2 > 1)");
  check_refused(run_scene(replace(kScene, "output_step = 0.5", "output_step = 0.99999e-7")),
                "bad.toml:17: solve.output_step: would write 10000102 rows (limit 1e+07)");
}

TEST_CASE("a member's rest length or damper out of range: exit 2 naming the key") {
  // Issue 44: `length` and `c` on truss members; a nonlinear bar needs geometry = "nonlinear".
  const std::string nonlinear =
      replace(kScene, "type = \"truss2d\"\n", "type = \"truss2d\"\ngeometry = \"nonlinear\"\n");
  check_refused(run_scene(replace(nonlinear, "EA = 10.0 }", "EA = 10.0, c = -1.0 }")),
                "bad.toml:6: model.members[1].c: must be >= 0 (got -1");
  check_refused(run_scene(replace(nonlinear, "EA = 10.0 }", "EA = 10.0, length = 0.0 }")),
                "bad.toml:6: model.members[1].length: must be > 0 (got 0)");
  check_refused(run_scene(replace(kScene, "EA = 10.0 }", "EA = 10.0, length = 1.5 }")),
                "bad.toml:5: model.members[1].length: a bar's rest length needs geometry");
}

}  // namespace test_cli_bad_input_keys
