// Issue 47, item 9, end to end: `condyn run` and `condyn modes` give the same bytes whether the
// ground motion's influence vector is written DOF by DOF, as a pattern or as a Matrix Market file
// (docs/scenes.md, "Tabulated time functions and ground motion"), and a bad influence file is
// refused with exit 2, its key and file named, nothing written.
#include <doctest/doctest.h>

#include <string>

#include "tests/cli_sandbox.hpp"
#include "tests/scene_text.hpp"
#include "tests/shear_building.hpp"

namespace test_cli_influence {

using condyn::test::Result;
using condyn::test::Sandbox;
using condyn::test::ShearBuilding;

namespace {

bool contains(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

/// A 4-storey building with a constrained base DOF and massless midpoints (9 DOFs, every one
/// moving with the ground), under a harmonic ground acceleration; `influence` replaces its
/// DOF-by-DOF line.
std::string building(const std::string& influence) {
  const ShearBuilding b{.storeys = 4,
                        .mass = 1.0,
                        .stiffness = 40.0,
                        .base_dof = true,
                        .massless_midpoints = true,
                        .ground_motion = true};
  std::string s = condyn::test::shear_building_scene(b);
  const auto from = s.find("influence = {");
  const auto to = s.find("}\n", from) + 2;
  s.replace(from, to - from, influence + "\n");
  return condyn::test::replace(s, "acceleration = 1.0",
                               "acceleration = { type = \"harmonic\", amplitude = 2.0, "
                               "omega = 3.0 }");
}

constexpr int kDofs = 9;

/// r = 1 on all 9 DOFs, as a coordinate file.
std::string ones() {
  std::string s = "%%MatrixMarket matrix coordinate real general\n9 1 9\n";
  for (int i = 1; i <= kDofs; ++i) s += std::to_string(i) + " 1 1.0\n";
  return s;
}

}  // namespace

TEST_CASE("influence: a pattern or a file runs and gives modes as the DOF-by-DOF vector does") {
  const Sandbox box;
  box.write("r.mtx", ones());
  const std::string by_name =
      "influence = { u0 = 1.0, h1 = 1.0, u1 = 1.0, h2 = 1.0, u2 = 1.0, h3 = 1.0, u3 = 1.0, "
      "h4 = 1.0, u4 = 1.0 }";
  box.write("names.toml", building(by_name));
  REQUIRE(box.run("run names.toml --out names.csv").code == 0);
  REQUIRE(box.run("modes names.toml --out names_modes.csv --shapes names_shapes.csv").code == 0);
  const std::string run = condyn::test::slurp(box.path("names.csv"));
  const std::string modes = condyn::test::slurp(box.path("names_modes.csv"));
  REQUIRE(contains(modes, "mass_ratio_cumulative"));
  for (const std::string influence :
       {"influence = { \"*\" = 1.0 }", "influence = { \"u*\" = 1.0, \"h*\" = 1.0 }",
        "influence = { file = \"r.mtx\" }"}) {
    CAPTURE(influence);
    box.write("other.toml", building(influence));
    REQUIRE(box.run("run other.toml --out other.csv").code == 0);
    CHECK(condyn::test::slurp(box.path("other.csv")) == run);
    REQUIRE(box.run("modes other.toml --out other_modes.csv").code == 0);
    CHECK(condyn::test::slurp(box.path("other_modes.csv")) == modes);
  }
}

TEST_CASE("influence: a bad influence file or pattern exits 2, naming the key and the file") {
  const Sandbox box;
  box.write("r.mtx", "%%MatrixMarket matrix coordinate real general\n8 1 1\n1 1 1.0\n");
  box.write("b.toml", building("influence = { file = \"r.mtx\" }"));
  for (const char* command : {"run b.toml --out b.csv", "modes b.toml --out m.csv"}) {
    CAPTURE(command);
    const Result r = box.run(command);
    CAPTURE(r.err);
    CHECK(r.code == 2);
    CHECK(contains(r.err,
                   "b.toml:11: ground_motion.influence.file: r.mtx:2: the size line "
                   "declares 8 x 1 but an influence vector is n x 1 (n = 9 DOFs)"));
  }
  box.write("p.toml", building("influence = { \"x*\" = 1.0 }"));
  const Result p = box.run("run p.toml --out p.csv");
  CHECK(p.code == 2);
  CHECK(contains(p.err, "ground_motion.influence.x*: 'x*' matches no DOF"));
  CHECK(!std::filesystem::exists(box.path("b.csv")));
  CHECK(!std::filesystem::exists(box.path("m.csv")));
  CHECK(!std::filesystem::exists(box.path("p.csv")));
}

}  // namespace test_cli_influence
