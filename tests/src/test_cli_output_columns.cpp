// [output] dofs selects the DOF columns; CSV numbers read back as the doubles computed.

#include <doctest/doctest.h>

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "models/scene_parser.hpp"
#include "models/scene_spec.hpp"
#include "tests/cli_sandbox.hpp"
#include "tests/scene_text.hpp"

using namespace condyn;
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

TEST_CASE("[output] dofs: a pattern that matches no DOF is refused, naming it") {
  test::Sandbox box;
  box.write("s.toml", replace(kChain, "[output]\n", "[output]\ndofs = [\"ux3\", \"uz*\"]\n"));
  const test::Result r = box.run("run s.toml --out out.csv");
  CHECK(r.code == 2);
  CHECK(r.err.find("output.dofs[2]") != std::string::npos);
  CHECK(r.err.find("'uz*' matches no DOF") != std::string::npos);
  box.write("e.toml", replace(kChain, "[output]\n", "[output]\ndofs = []\n"));
  CHECK(box.run("run e.toml --out out.csv").err.find("output.dofs") != std::string::npos);
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
