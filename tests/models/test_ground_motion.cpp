// Issue 13, item 2: [ground_motion] (scene-format.md, "Ground motion"): one pattern load −M r
// a_g(t) for trusses (r along a direction) and matrix models (r by DOF), and the refusals, each
// naming its key.
#include <doctest/doctest.h>

#include <string>

#include "models/assembly/build_model.hpp"
#include "models/core/model.hpp"
#include "models/scene/scene_parser.hpp"
#include "tests/cli_sandbox.hpp"
#include "tests/scene_text.hpp"

using namespace condyn;

namespace test_ground_motion {

using condyn::test::replace;
using condyn::test::Sandbox;

namespace {

bool has(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

const std::string kRecord = "t,a\n0,0\n0.5,1\n1,-0.5\n";

/// Three nodes in a row, the first supported; masses 0 (the support), 2 and 3.
const std::string kTruss = R"([model]
type = "truss2d"
nodes = [[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]]
masses = [0.0, 2.0, 3.0]
supports = [1]
members = [{ nodes = [1, 2], EA = 10.0 }, { nodes = [2, 3], EA = 10.0 }]
[[constraint]]
terms = { uy2 = 1.0 }
[[constraint]]
terms = { uy3 = 1.0 }
[ground_motion]
direction = "x"
acceleration = { type = "table", file = "rec.csv", scale = 9.81 }
[solve]
t_end = 1.0
output_step = 0.5
)";

const std::string kMatrix = R"([model]
type = "matrix"
dofs = ["a", "b", "c"]
mass = [[1.0, 0.5, 0.0], [0.5, 2.0, 0.0], [0.0, 0.0, 4.0]]
stiffness = [[2.0, -1.0, 0.0], [-1.0, 2.0, -1.0], [0.0, -1.0, 1.0]]
[ground_motion]
influence = { a = 1.0, b = 1.0 }
acceleration = { type = "harmonic", amplitude = 2.0, omega = 3.0 }
[solve]
t_end = 1.0
output_step = 0.5
)";

struct Built {
  std::string error;
  Model model;
};

Built build(const Sandbox& box, const std::string& scene) {
  box.write("rec.csv", kRecord);
  try {
    return {"", build_model(parse_scene_file(box.write("scene.toml", scene).string()))};
  } catch (const SceneError& e) {
    return {e.what(), {}};
  }
}

/// The build's warnings for `scene` (written to the sandbox; its tables are the test's own).
std::vector<std::string> build_warnings(const Sandbox& box, const std::string& scene) {
  BuildReport report;
  (void)build_model(parse_scene_file(box.write("scene.toml", scene).string()), report);
  return report.warnings;
}

}  // namespace

TEST_CASE("ground motion: a truss gets one pattern load −M r a_g along its direction") {
  Sandbox box;
  const Built b = build(box, kTruss);
  REQUIRE(b.error.empty());
  const Model& model = b.model;
  REQUIRE(model.loads.size() == 1);
  const Load& load = model.loads[0];
  CHECK(load.dof == -1);
  // ux2 and ux3 only: the support has no mass, the y DOFs are not along r.
  REQUIRE(load.pattern.nonZeros() == 2);
  CHECK(load.pattern.coeff(model.dof_at("ux2")) == -2.0);
  CHECK(load.pattern.coeff(model.dof_at("ux3")) == -3.0);
  CHECK(load.value.describe() == "table(rec.csv:a, 3 samples)*9.81");
  // f(t) = −M r a_g(t): a_g(0.25) = 0.5 g, a_g(0.75) = 0.25 g.
  for (const auto& [t, ag] : {std::pair{0.25, 0.5 * 9.81}, std::pair{0.75, 0.25 * 9.81}}) {
    const Eigen::VectorXd f = model.applied_forces(t);
    CHECK(f[model.dof_at("ux2")] == doctest::Approx(-2.0 * ag).epsilon(1e-15));
    CHECK(f[model.dof_at("ux3")] == doctest::Approx(-3.0 * ag).epsilon(1e-15));
    CHECK(f[model.dof_at("uy3")] == 0.0);
  }
  // y: the y DOFs instead; a 3D truss has z.
  const Built y = build(box, replace(kTruss, "direction = \"x\"", "direction = \"y\""));
  REQUIRE(y.error.empty());
  CHECK(y.model.loads[0].pattern.coeff(y.model.dof_at("uy3")) == -3.0);
  CHECK(y.model.loads[0].pattern.coeff(y.model.dof_at("ux3")) == 0.0);
}

TEST_CASE("ground motion: a matrix model's influence vector, unnamed DOFs 0") {
  Sandbox box;
  const Built b = build(box, kMatrix);
  REQUIRE(b.error.empty());
  REQUIRE(b.model.loads.size() == 1);
  // −M r with r = (1, 1, 0): −(1.5, 2.5, 0); c carries no load.
  const auto& p = b.model.loads[0].pattern;
  CHECK(p.nonZeros() == 2);
  CHECK(p.coeff(0) == -1.5);
  CHECK(p.coeff(1) == -2.5);
  CHECK(p.coeff(2) == 0.0);
  // Added after the scene's own loads.
  const Built with_load = build(
      box,
      replace(kMatrix, "[ground_motion]", "[[load]]\ndof = \"c\"\nvalue = 1.0\n[ground_motion]"));
  REQUIRE(with_load.error.empty());
  CHECK(with_load.model.loads.size() == 2);
  CHECK(with_load.model.applied_forces(0.0)[2] == 1.0);
}

TEST_CASE("ground motion: refusals name the key") {
  Sandbox box;
  const auto error = [&](const std::string& scene) { return build(box, scene).error; };
  CHECK(has(error(replace(kTruss, "direction = \"x\"", "direction = \"z\"")),
            "scene.toml:12: ground_motion.direction: no direction 'z' in a 2D truss (expected x "
            "or y)"));
  CHECK(has(error(replace(kTruss, "direction = \"x\"", "direction = \"north\"")),
            "ground_motion.direction: no direction 'north'"));
  CHECK(has(error(replace(kTruss, "direction = \"x\"\n", "")),
            "ground_motion.direction: missing required key"));
  CHECK(has(error(replace(kTruss, "direction = \"x\"", "influence = { ux2 = 1.0 }")),
            "ground_motion.influence: is for matrix models; a truss gives direction"));
  CHECK(has(error(replace(kTruss, "direction = \"x\"", "direction = \"x\"\ndamping = 0.05")),
            "ground_motion.damping: unknown key (expected one of: acceleration, direction, "
            "influence)"));
  CHECK(has(error(replace(kTruss, "acceleration = ", "acceleraton = ")),
            "ground_motion.acceleraton: unknown key"));
  CHECK(has(error(replace(kTruss, "file = \"rec.csv\"", "file = \"gone.csv\"")),
            "ground_motion.acceleration.file: " + box.path("gone.csv").string() +
                ": cannot open the file"));
  CHECK(has(error(replace(kMatrix, "a = 1.0, b = 1.0", "a = 1.0, q = 1.0")),
            "ground_motion.influence.q: no such DOF 'q' (DOFs are: a, b, c)"));
  CHECK(has(error(replace(kMatrix, "a = 1.0, b = 1.0", "a = 0.0")),
            "ground_motion.influence: is zero: no DOF moves with the ground"));
  CHECK(has(error(replace(kMatrix, "influence", "direction = \"x\"\ninfluence")),
            "ground_motion.direction: is for truss models"));
  CHECK(has(error(replace(kMatrix, "influence = { a = 1.0, b = 1.0 }\n", "")),
            "ground_motion.influence: missing required key"));
  CHECK(has(error(replace(kMatrix,
                          "acceleration = { type = \"harmonic\", amplitude = 2.0, "
                          "omega = 3.0 }\n",
                          "")),
            "ground_motion.acceleration: missing required key"));
  // Mass only on DOFs r does not move.
  CHECK(has(error(replace(kTruss, "masses = [0.0, 2.0, 3.0]", "masses = [0.0, 0.0, 0.0]")),
            "ground_motion: M r is zero"));
  // A model with no M r a_g form.
  CHECK(has(error("[model]\ntype = \"pendulum\"\n[ground_motion]\ndirection = \"x\"\n"
                  "acceleration = 1.0\n[solve]\nt_end = 1.0\noutput_step = 0.5\n"),
            "ground_motion: ground motion applies to truss and matrix models"));
}

TEST_CASE("a record that ends before t_end on a nonzero value is warned about, by key") {
  // The contract holds a table constant after its last sample: a record cut short would go on
  // shaking the ground at its last value, without a word.
  Sandbox box;
  box.write("rec.csv", kRecord);  // ends at t = 1 on -0.5
  const auto warnings = [&box](const std::string& scene) { return build_warnings(box, scene); };
  // Ground motion, t_end 2: held at 9.81 * -0.5.
  auto w = warnings(replace(kTruss, "t_end = 1.0", "t_end = 2.0"));
  REQUIRE(w.size() == 1);
  CHECK(w[0] ==
        "ground_motion.acceleration: rec.csv ends at t = 1, before t_end = 2, on a nonzero value: "
        "-4.905 is held from there on (a table is constant after its last sample); add a sample "
        "to say what follows");
  // At t_end itself, or ending on zero: nothing to say.
  CHECK(warnings(kTruss).empty());
  box.write("zero.csv", "t,a\n0,0\n0.5,1\n1,0\n");
  CHECK(warnings(replace(replace(kTruss, "t_end = 1.0", "t_end = 2.0"), "rec.csv", "zero.csv"))
            .empty());
  // A load's table, by the load's key.
  const std::string load = replace(kMatrix, "[ground_motion]",
                                   "[[load]]\ndof = \"c\"\nvalue = { type = \"table\", file = "
                                   "\"rec.csv\" }\n[ground_motion]");
  w = warnings(replace(load, "t_end = 1.0", "t_end = 3.0"));
  REQUIRE(w.size() == 1);
  CHECK(has(w[0],
            "load[1].value: rec.csv ends at t = 1, before t_end = 3, on a nonzero value: "
            "-0.5 is held"));
}

TEST_CASE("a record that starts after t = 0 on a nonzero value is warned about, by key") {
  // A table is constant before its first sample: a time-shifted accelerogram acted from t = 0
  // at its first value, without a word, even when it began after t_end.
  Sandbox box;
  const auto warnings = [&box](const std::string& scene) { return build_warnings(box, scene); };
  box.write("late.csv", "t,a\n0.25,0.5\n0.5,1\n1,0\n");
  auto w = warnings(replace(kTruss, "rec.csv", "late.csv"));
  REQUIRE(w.size() == 1);
  CHECK(w[0] ==
        "ground_motion.acceleration: late.csv starts at t = 0.25 on a nonzero value: 4.905 acts "
        "from t = 0 (a table is constant before its first sample); add a sample at t = 0 to say "
        "what precedes");
  box.write("after.csv", "t,a\n5,0.5\n6,0\n");
  w = warnings(replace(kTruss, "rec.csv", "after.csv"));
  REQUIRE(w.size() == 1);
  CHECK(has(w[0], "after.csv starts at t = 5, after t_end = 1, on a nonzero value: 4.905 acts"));
  // Starting on zero, or at t = 0: nothing to say.
  box.write("quiet.csv", "t,a\n0.25,0\n0.5,1\n1,0\n");
  CHECK(warnings(replace(kTruss, "rec.csv", "quiet.csv")).empty());
  box.write("rec.csv", kRecord);
  CHECK(warnings(kTruss).empty());
}

}  // namespace test_ground_motion
