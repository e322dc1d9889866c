// Issue 47, item 9: a matrix model's ground-motion influence vector from an n x 1 Matrix Market
// file or from `*` patterns over DOF names (docs/scenes.md, "Tabulated time functions and ground
// motion"): the same r, load and participating masses as the vector written DOF by DOF, bit for
// bit; a DOF's own name before any pattern; and the refusals, each naming its key.
#include <doctest/doctest.h>

#include <string>

#include "models/assembly/build_model.hpp"
#include "models/core/model.hpp"
#include "models/scene/scene_parser.hpp"
#include "tests/cli_sandbox.hpp"
#include "tests/scene_text.hpp"
#include "validation/studies/scene_modes.hpp"

using namespace condyn;

namespace test_influence_vector {

using condyn::test::replace;
using condyn::test::Sandbox;

namespace {

bool has(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

/// Three nodes of two DOFs each in a chain of springs that couples x and y, so that every mode
/// has some mass along x: influence 1 on the x DOFs.
const std::string kChain = R"([model]
type = "matrix"
dofs = ["ux1", "uy1", "ux2", "uy2", "ux3", "uy3"]
mass = [[1.0, 0.0, 0.0, 0.0, 0.0, 0.0], [0.0, 2.0, 0.0, 0.0, 0.0, 0.0],
        [0.0, 0.0, 1.0, 0.0, 0.0, 0.0], [0.0, 0.0, 0.0, 2.0, 0.0, 0.0],
        [0.0, 0.0, 0.0, 0.0, 1.0, 0.0], [0.0, 0.0, 0.0, 0.0, 0.0, 2.0]]
stiffness = [[2.0, -1.0, 0.0, 0.0, 0.0, 0.0], [-1.0, 2.0, -1.0, 0.0, 0.0, 0.0],
             [0.0, -1.0, 2.0, -1.0, 0.0, 0.0], [0.0, 0.0, -1.0, 2.0, -1.0, 0.0],
             [0.0, 0.0, 0.0, -1.0, 2.0, -1.0], [0.0, 0.0, 0.0, 0.0, -1.0, 1.0]]
[ground_motion]
influence = { ux1 = 1.0, ux2 = 1.0, ux3 = 1.0 }
acceleration = { type = "harmonic", amplitude = 2.0, omega = 3.0 }
[solve]
t_end = 1.0
output_step = 0.5
)";

const std::string kByName = "influence = { ux1 = 1.0, ux2 = 1.0, ux3 = 1.0 }";

/// r = (1, 0, 1, 0, 1, 0) as scipy.io.mmwrite writes a numpy column (format `array`).
const std::string kColumn = "%%MatrixMarket matrix array real general\n6 1\n1\n0\n1\n0\n1\n0\n";

struct Built {
  std::string error;
  Model model;
};

Built build(const Sandbox& box, const std::string& scene) {
  box.write("r.mtx", kColumn);
  try {
    return {"", build_model(parse_scene_file(box.write("scene.toml", scene).string()))};
  } catch (const SceneError& e) {
    return {e.what(), {}};
  }
}

Eigen::VectorXd r_of(const Sandbox& box, const std::string& influence) {
  const Built b = build(box, replace(kChain, kByName, influence));
  REQUIRE_MESSAGE(b.error.empty(), b.error);
  REQUIRE(b.model.ground);
  return b.model.ground->r;
}

}  // namespace

TEST_CASE("influence: a file and a pattern give the vector written DOF by DOF, bit for bit") {
  Sandbox box;
  const Built by_name = build(box, kChain);
  REQUIRE(by_name.error.empty());
  const Eigen::VectorXd r = by_name.model.ground->r;
  CHECK(r == (Eigen::VectorXd(6) << 1, 0, 1, 0, 1, 0).finished());
  const SceneModes modes = scene_modes(parse_scene_file(box.path("scene.toml").string()), {}, "");
  for (const std::string influence :
       {"influence = { file = \"r.mtx\" }", "influence = { \"ux*\" = 1.0 }",
        "influence = { \"ux*\" = 1.0, \"uy*\" = 0.0 }",
        // A DOF's name before a pattern; two patterns agreeing on a DOF.
        "influence = { \"*\" = 1.0, uy1 = 0.0, uy2 = 0.0, uy3 = 0.0 }",
        "influence = { \"ux*\" = 1.0, \"*1\" = 1.0, uy1 = 0.0 }"}) {
    CAPTURE(influence);
    const Built b = build(box, replace(kChain, kByName, influence));
    REQUIRE_MESSAGE(b.error.empty(), b.error);
    CHECK(b.model.ground->r == r);
    // The load −M r a_g(t), and so the run, is the same sparse vector.
    REQUIRE(b.model.loads.size() == 1);
    CHECK(Eigen::VectorXd(b.model.loads[0].pattern) ==
          Eigen::VectorXd(by_name.model.loads[0].pattern));
    // condyn modes' participation reads the model's r: the same ratios, bit for bit.
    const SceneModes m = scene_modes(parse_scene_file(box.path("scene.toml").string()), {}, "");
    CHECK(m.modes.mass_ratio == modes.modes.mass_ratio);
    CHECK(m.modes.total_mass == modes.modes.total_mass);
  }
  CHECK(modes.modes.total_mass == 3.0);  // rᵀ M r: three unit masses along x, no constraint
}

TEST_CASE("influence: a DOF's own name wins over every pattern") {
  Sandbox box;
  // ux1 by name, the other x DOFs by the pattern.
  CHECK(r_of(box, "influence = { \"ux*\" = 1.0, ux1 = 0.5 }") ==
        (Eigen::VectorXd(6) << 0.5, 0, 1, 0, 1, 0).finished());
  // A DOF named with a `*` is that DOF (a scene written before patterns keeps its meaning).
  const std::string star =
      replace(kChain, "\"ux1\", \"uy1\"", "\"u*\", \"uy1\"");  // the first DOF is named u*
  const Built b = build(box, replace(star, kByName, "influence = { \"u*\" = 1.0 }"));
  REQUIRE_MESSAGE(b.error.empty(), b.error);
  CHECK(b.model.ground->r == (Eigen::VectorXd(6) << 1, 0, 0, 0, 0, 0).finished());
  // A DOF named `file` with a number is that DOF, not a file.
  const std::string file_dof = replace(kChain, "\"ux1\", \"uy1\"", "\"file\", \"uy1\"");
  const Built f = build(box, replace(file_dof, kByName, "influence = { file = 2.0 }"));
  REQUIRE_MESSAGE(f.error.empty(), f.error);
  CHECK(f.model.ground->r == (Eigen::VectorXd(6) << 2, 0, 0, 0, 0, 0).finished());
}

TEST_CASE("influence: refusals name the key, the file and what is wrong") {
  Sandbox box;
  const auto error = [&](const std::string& influence) {
    return build(box, replace(kChain, kByName, influence)).error;
  };
  const auto with_file = [&](const std::string& text) {
    box.write("v.mtx", text);
    return build(box, replace(kChain, kByName, "influence = { file = \"v.mtx\" }")).error;
  };
  CHECK(has(error("influence = { \"uz*\" = 1.0 }"),
            "scene.toml:11: ground_motion.influence.uz*: 'uz*' matches no DOF ("));
  CHECK(has(error("influence = { \"uz*\" = 1.0 }"), "`*` stands for any run of characters)"));
  CHECK(has(error("influence = { \"ux*\" = 1.0, \"*1\" = 2.0 }"),
            "ground_motion.influence.ux*: 'ux*' = 1 and '*1' = 2 both match DOF 'ux1': give it "
            "by its name, which wins over any pattern"));
  CHECK(has(error("influence = { ux4 = 1.0 }"), "ground_motion.influence.ux4: no such DOF 'ux4'"));
  CHECK(has(error("influence = { \"ux*\" = nan }"), "ground_motion.influence.ux*: must be finite"));
  CHECK(has(error("influence = { \"ux*\" = 1.0, ux1 = 0.0, ux2 = 0.0, ux3 = 0.0 }"),
            "ground_motion.influence: gives every DOF 0: no DOF moves with the ground"));
  CHECK(has(error("influence = { file = \"r.mtx\", ux1 = 1.0 }"),
            "ground_motion.influence: give either file = \"r.mtx\" or DOF names and patterns"));
  CHECK(has(
      error("influence = { file = \"gone.mtx\" }"),
      "ground_motion.influence.file: " + box.path("gone.mtx").string() + ": cannot open the file"));
  // Wrong size, not a vector, not finite, zero: the file and its line named.
  CHECK(has(with_file("%%MatrixMarket matrix array real general\n5 1\n1\n0\n1\n0\n1\n"),
            "ground_motion.influence.file: " + box.path("v.mtx").string() + ":2: "));
  CHECK(has(with_file("%%MatrixMarket matrix array real general\n5 1\n1\n0\n1\n0\n1\n"),
            "an influence vector is n x 1 (n = 6 DOFs)"));
  CHECK(has(with_file("%%MatrixMarket matrix coordinate real general\n6 2 1\n1 2 1.0\n"),
            "an influence vector is n x 1 (n = 6 DOFs)"));
  CHECK(has(with_file("%%MatrixMarket matrix coordinate real general\n6 1 1\n1 1 inf\n"),
            box.path("v.mtx").string() + ":3: the value 'inf' is not finite"));
  CHECK(has(with_file("%%MatrixMarket matrix coordinate real general\n6 1 1\n1 1 0.0\n"),
            "ground_motion.influence.file: v.mtx is zero: no DOF moves with the ground"));
}

}  // namespace test_influence_vector
