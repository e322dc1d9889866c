// Issue 42: what `run` says of a model that runs but may not be what was meant: the DOFs it
// treats as massless (item 2), a ground motion record's peak (item 1), and a drift grown far
// beyond the tolerance, a failed verdict under `check` (item 15).
#include <doctest/doctest.h>

#include <string>

#include "tests/cli_sandbox.hpp"
#include "tests/scene_text.hpp"

namespace test_cli_run_summary {

using namespace condyn::test;

namespace {

bool contains(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

/// A chain of n DOFs u1..un on unit springs, u1 to the ground; mass 1 on the first `heavy` DOFs,
/// none on the rest (a roof whose mass was forgotten: its stiffness holds it).
std::string chain(int n, int heavy) {
  std::string dofs, mass, stiffness;
  for (int i = 0; i < n; ++i) {
    dofs += (i ? ", \"u" : "\"u") + std::to_string(i + 1) + "\"";
    std::string m = "[", k = "[";
    for (int j = 0; j < n; ++j) {
      const double kij = i == j ? (i + 1 < n ? 2.0 : 1.0) : (i - j == 1 || j - i == 1) ? -1.0 : 0.0;
      m += std::string(j ? ", " : "") + (i == j && i < heavy ? "1.0" : "0.0");
      k += std::string(j ? ", " : "") + std::to_string(kij);
    }
    mass += (i ? ", " : "") + m + "]";
    stiffness += (i ? ", " : "") + k + "]";
  }
  return "[model]\ntype = \"matrix\"\ndofs = [" + dofs + "]\nmass = [" + mass + "]\nstiffness = [" +
         stiffness +
         "]\n[[load]]\ndof = \"u1\"\nvalue = { type = \"step\" }\n[solve]\nt_end = 1.0\n"
         "output_step = 0.5\n";
}

}  // namespace

TEST_CASE("run: one line names the DOFs it treats as massless") {
  const Sandbox box;
  // Three storeys, the roof's mass forgotten: it ran without a word.
  box.write("c.toml", chain(3, 2));
  Result r = box.run("run c.toml --out c.csv");
  CAPTURE(r.err);
  REQUIRE(r.code == 0);
  CHECK(contains(r.out,
                 "massless DOFs: 1 of 3 (u3): 1 held by its stiffness alone (algebraic, no "
                 "inertia)\n"));
  // Many: the count and the first ten.
  box.write("c.toml", chain(16, 1));
  r = box.run("run c.toml --out c.csv");
  REQUIRE(r.code == 0);
  CHECK(contains(r.out,
                 "massless DOFs: 15 of 16 (u2, u3, u4, u5, u6, u7, u8, u9, u10, u11 ... and "
                 "5 more): 15 held by their stiffness alone"));
  // A support without mass: in constraints. Every DOF with mass: no line.
  box.write("p.toml", pendulum_scene("t_end = 0.1\noutput_step = 0.1\n"));
  r = box.run("run p.toml --out p.csv");
  REQUIRE(r.code == 0);
  CHECK(contains(r.out, "massless DOFs: 2 of 4 (ux1, uy1): 2 in constraints\n"));
  box.write("c.toml", chain(3, 3));
  r = box.run("run c.toml --out c.csv");
  REQUIRE(r.code == 0);
  CHECK_FALSE(contains(r.out, "massless"));
}

TEST_CASE("run: a ground motion record's peak, and a scale of 981 in an SI scene warned of") {
  const Sandbox box;
  const std::string frame =
      std::string(CONDYN_SOURCE_DIR) + "/models/scenes/shear_frame_el_centro.toml";
  Result r = box.run("run '" + frame + "' --out f.csv");
  CAPTURE(r.err);
  REQUIRE(r.code == 0);
  // The record's header: peak 0.31882 g at t = 2.02 s, times 9.81.
  CHECK(contains(r.out,
                 "ground motion record: table(data/el_centro_1940_ns.csv:acceleration_g, "
                 "1559 samples)*9.81: peak 3.13 m/s^2 (0.319 g) at t = 2.02 s\n"));
  CHECK_FALSE(contains(r.err, "warning"));
  // A slip of units, g to cm/s²: it ran silently to a roof displacement 100 times too large.
  std::string text = slurp(frame);
  text = replace(text, "scale = 9.81", "scale = 981.0");
  text = replace(text, "data/el_centro_1940_ns.csv",
                 std::string(CONDYN_SOURCE_DIR) + "/models/scenes/data/el_centro_1940_ns.csv");
  box.write("f.toml", text);
  r = box.run("run f.toml --out f.csv");
  REQUIRE(r.code == 0);
  CHECK(contains(r.err,
                 "warning: f.toml: ground_motion.acceleration: 'acceleration_g' says the "
                 "record"));
  CHECK(contains(r.err, "its scale 981 is not g in m/s^2"));
  CHECK(contains(r.err, "peaks at 313 m/s^2 (31.9 g) at t = 2.02 s, beyond 5 g"));
}

namespace {

/// The pendulum over 100 s at rtol 1e-6 with a check that holds under every scheme (|ux2| <= 2,
/// the rod's reach 2 and more: index1's rod, drifting, swings to 2.03), index1 or GGL.
std::string drifting_pendulum(const std::string& scheme) {
  return pendulum_scene("t_end = 100.0\noutput_step = 1.0\nrtol = 1e-6\nscheme = \"" + scheme +
                        "\"\n") +
         "[[check]]\nquantity = \"ux2\"\nmax_abs = 2.5\n";
}

}  // namespace

TEST_CASE("run and check: a drift beyond 100 (rtol max|u| + atol) is warned of, and fails check") {
  const Sandbox box;
  // index1 lets the rod's length drift: 0.0437 by t = 100 against a bound of 2.0e-4 (rtol 1e-6
  // times max|u| = 2, plus atol 1e-10, times 100); GGL holds it to 1.9e-6 (observed).
  box.write("i.toml", drifting_pendulum("index1"));
  box.write("g.toml", drifting_pendulum("ggl"));
  const Result i = box.run("run i.toml --out i.csv");
  CAPTURE(i.out);
  CHECK(i.code == 0);  // the result is written; the summary says what it is worth
  CHECK(contains(i.out, "; warning: the constraints drifted by 0.04"));
  CHECK(contains(i.out, "beyond 100 (rtol max|u| + atol) = 0.0002"));
  CHECK(contains(i.out, "index1 lets the drift grow: use ggl or projection"));
  const Result g = box.run("run g.toml --out g.csv");
  CHECK(g.code == 0);
  CHECK_FALSE(contains(g.out, "drifted"));
  // check: the scene fails on the drift though its one check holds.
  const Result c = box.run("check i.toml g.toml --junit report.xml");
  CAPTURE(c.out);
  CHECK(c.code == 1);
  CHECK(contains(c.out, "PASS check[1] ux2 (max_abs)"));
  CHECK(contains(c.out, "  FAIL drift: the constraints drifted by 0.04"));
  CHECK(contains(c.out, "checks: 2 passed, 1 failed (2 scenes)"));
  const std::string xml = slurp(box.path("report.xml"));
  CHECK(contains(xml,
                 "name=\"drift\" time=\"0\">\n      <failure message=\"the constraints "
                 "drifted by 0.04"));
  CHECK(
      contains(xml, "<testsuites name=\"condyn check\" tests=\"3\" failures=\"1\" errors=\"0\">"));
  CHECK(box.run("check g.toml").code == 0);
}

}  // namespace test_cli_run_summary
