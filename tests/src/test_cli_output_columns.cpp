// [output] dofs selects the DOF columns; CSV numbers read back as the doubles computed.

#include <doctest/doctest.h>
#include <filesystem>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "models/scene/scene_parser.hpp"
#include "models/scene/scene_spec.hpp"
#include "tests/cli_sandbox.hpp"
#include "tests/scene_text.hpp"

using namespace condyn;

namespace test_cli_output_columns {

using condyn::test::replace;

namespace {

std::string first_line(const std::string& text) { return text.substr(0, text.find('\n')); }

const std::string kChain = R"([model]
type = "truss2d"
nodes = [[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]]
masses = [1.0, 1.0, 1.0]
members = [{ nodes = [1, 2], EA = 10.0 }, { nodes = [2, 3], EA = 10.0 }]
supports = [1]
[[load]]
dof = "ux3"
value = 1.0
[[constraint]]
name = "roll"
terms = { uy2 = 1.0 }
[[constraint]]
name = "roll3"
terms = { uy3 = 1.0 }
[solve]
t_end = 1.0
output_step = 0.25
[output]
quantities = ["displacement", "velocity", "reaction", "multiplier"]
)";

}  // namespace

TEST_CASE("dof patterns: * stands for any run of characters") {
  CHECK(matches_dof_pattern("ux2", "ux2"));
  CHECK_FALSE(matches_dof_pattern("ux2", "ux20"));
  CHECK(matches_dof_pattern("ux*", "ux20"));
  CHECK(matches_dof_pattern("*", "anything"));
  CHECK(matches_dof_pattern("*2", "uy2"));
  CHECK_FALSE(matches_dof_pattern("*2", "uy3"));
  CHECK(matches_dof_pattern("u*2*", "uy12x"));
  CHECK(matches_dof_pattern("a*b*c", "aXbYbZc"));
  CHECK_FALSE(matches_dof_pattern("a*b*c", "aXbYbZ"));
  OutputSpec out;
  out.dofs = {"uy*", "ux1"};
  CHECK(selected_dofs(out, {"ux1", "uy1", "ux2", "uy2"}) == std::vector<int>{0, 1, 3});
  CHECK(selected_dofs(OutputSpec{}, {"a", "b"}) == std::vector<int>{0, 1});
}

TEST_CASE("[output] dofs selects the DOF columns of every DOF quantity, not the multipliers") {
  test::Sandbox box;
  box.write("s.toml", replace(kChain, "[output]\n", "[output]\ndofs = [\"ux3\", \"uy*\"]\n"));
  const test::Result r = box.run("run s.toml --out out.csv");
  CAPTURE(r.err);
  REQUIRE(r.code == 0);
  // The selected DOFs in the model's order; every constraint keeps its multiplier column.
  CHECK(first_line(test::slurp(box.path("out.csv"))) ==
        "t,uy1,uy2,ux3,uy3,vel_uy1,vel_uy2,vel_ux3,vel_uy3,reaction_uy1,reaction_uy2,"
        "reaction_ux3,reaction_uy3,lambda_fix_ux1,lambda_fix_uy1,lambda_roll,lambda_roll3");
}

TEST_CASE("acceleration columns acc_<dof> come where the quantity is listed, over [output] dofs") {
  test::Sandbox box;
  box.write("s.toml",
            replace(kChain,
                    "quantities = [\"displacement\", \"velocity\", \"reaction\", \"multiplier\"]\n",
                    "quantities = [\"velocity\", \"acceleration\", \"displacement\"]\n"
                    "dofs = [\"ux*\"]\n"));
  const test::Result r = box.run("run s.toml --out out.csv");
  CAPTURE(r.err);
  REQUIRE(r.code == 0);
  const std::string text = test::slurp(box.path("out.csv"));
  CHECK(first_line(text) == "t,vel_ux1,vel_ux2,vel_ux3,acc_ux1,acc_ux2,acc_ux3,ux1,ux2,ux3");
  // ux1 is supported, so it does not accelerate; ux3 is pulled by its load at t = 0: a = f/m = 1.
  std::istringstream in(text);
  std::string line;
  std::getline(in, line);
  std::getline(in, line);
  std::vector<double> row;
  std::istringstream cells(line);
  for (std::string cell; std::getline(cells, cell, ',');) row.push_back(std::stod(cell));
  REQUIRE(row.size() == 10);
  for (std::size_t c : {4, 5}) CHECK(std::abs(row[c]) <= 1e-9);
  CHECK(row[6] == doctest::Approx(1.0).epsilon(1e-9));
}

TEST_CASE("a DOF whose acceleration column would repeat another column is refused") {
  CHECK_THROWS_WITH_AS((void)parse_scene_text(R"([model]
type = "matrix"
dofs = ["x", "acc_x"]
mass = [[1.0, 0.0], [0.0, 1.0]]
stiffness = [[1.0, 0.0], [0.0, 1.0]]
[solve]
t_end = 1.0
output_step = 0.5
)",
                                              "s.toml"),
                       doctest::Contains("acc_x"), SceneError);
}

TEST_CASE("[output] dofs: a pattern that matches no DOF is refused, naming it") {
  test::Sandbox box;
  // The entry on its own line: the message gives that line, not the [output] header's.
  const std::string scene =
      replace(kChain, "[output]\n", "[output]\ndofs = [\n  \"ux3\",\n  \"uz*\",\n]\n");
  box.write("s.toml", scene);
  const test::Result r = box.run("run s.toml --out out.csv");
  CHECK(r.code == 2);
  const auto line_of = [&](const std::string& text) {
    return 1 + std::count(scene.begin(), scene.begin() + static_cast<long>(scene.find(text)), '\n');
  };
  CHECK(r.err.find("s.toml:" + std::to_string(line_of("\"uz*\"")) + ": output.dofs[2]") !=
        std::string::npos);
  CHECK(r.err.find("'uz*' matches no DOF") != std::string::npos);
  box.write("e.toml", replace(kChain, "[output]\n", "[output]\ndofs = []\n"));
  CHECK(box.run("run e.toml --out out.csv").err.find("output.dofs") != std::string::npos);
  // A name given twice (a column written twice) and an empty list of quantities (a CSV of
  // times alone) are refused as a quantity given twice and an empty list of DOFs are.
  box.write("d.toml", replace(kChain, "[output]\n", "[output]\ndofs = [\"ux3\", \"ux3\"]\n"));
  const test::Result twice = box.run("run d.toml --out out.csv");
  CHECK(twice.code == 2);
  CHECK_MESSAGE(twice.err.find("output.dofs[2]: 'ux3' is listed twice (also as output.dofs[1])") !=
                    std::string::npos,
                twice.err);
  box.write("q.toml", replace(kChain,
                              "quantities = [\"displacement\", \"velocity\", \"reaction\", "
                              "\"multiplier\"]",
                              "quantities = []"));
  const test::Result none = box.run("run q.toml --out out.csv");
  CHECK(none.code == 2);
  CHECK_MESSAGE(none.err.find("output.quantities: is empty") != std::string::npos, none.err);
  CHECK_FALSE(std::filesystem::exists(box.path("out.csv")));
}

TEST_CASE("CSV numbers read back as the same doubles (shortest round-trip form)") {
  // 3 x 0.1 is not 0.3: the shortest form of each double still tells them apart.
  test::Sandbox box;
  box.write("s.toml", replace(kChain, "output_step = 0.25", "output_step = 0.1"));
  const test::Result r = box.run("run s.toml --out out.csv");
  REQUIRE(r.code == 0);
  std::istringstream csv(test::slurp(box.path("out.csv")));
  std::string line;
  std::getline(csv, line);  // header
  std::vector<double> times;
  while (std::getline(csv, line)) times.push_back(std::stod(line.substr(0, line.find(','))));
  REQUIRE(times.size() == 11);
  for (std::size_t k = 0; k + 1 < times.size(); ++k) {
    CHECK(times[k] == static_cast<double>(k) * 0.1);  // the loop's output times, bit for bit
  }
  CHECK(times.back() == 1.0);
}

}  // namespace test_cli_output_columns
