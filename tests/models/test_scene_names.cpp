// DOF and constraint names become CSV column names: names that would break the CSV (a comma, a
// quote, a line break) or give a column twice are refused at the line that names them.
#include <doctest/doctest.h>

#include <stdexcept>
#include <string>

#include "models/assembly/build_model.hpp"
#include "models/core/model.hpp"
#include "models/scene/scene_parser.hpp"
#include "tests/scene_errors.hpp"

using namespace condyn;

namespace test_scene_names {

namespace {

/// A matrix scene with the given DOF list and constraint table (TOML text).
std::string scene(const std::string& dofs, const std::string& constraint) {
  return "[model]\ntype = \"matrix\"\ndofs = " + dofs +
         "\nmass = [[1.0, 0.0], [0.0, 1.0]]\nstiffness = [[1.0, 0.0], [0.0, 1.0]]\n" + constraint +
         "[solve]\nt_end = 1.0\noutput_step = 0.5\n";
}

std::string error_of(const std::string& text) { return test::build_error(text, "n.toml"); }

}  // namespace

TEST_CASE("names that would break the CSV are refused with their line") {
  struct Case {
    std::string dofs, constraint, where, what;
  };
  const Case cases[] = {
      {R"(["a,b", "c"])", "", "n.toml:3: model.dofs[1]", "holds ','"},
      {R"(["a\nb", "c"])", "", "n.toml:3: model.dofs[1]", "holds a line break"},
      {R"(["a", " b"])", "", "n.toml:3: model.dofs[2]", "begins with a space"},
      {R"(["a", "b "])", "", "n.toml:3: model.dofs[2]", "ends with a space"},
      {R"(["a", "b\"c"])", "", "n.toml:3: model.dofs[2]", "holds '\"'"},
      {R"(["a", "b\u0001"])", "", "n.toml:3: model.dofs[2]", "the control character \\x01"},
      {R"(["a", "b"])", "[[constraint]]\nname = \"roll,extra\"\nterms = { a = 1.0 }\n",
       "n.toml:7: constraint[1].name", "holds ','"},
      {R"(["a", "b"])", "[[constraint]]\nname = \"r\toll\"\nterms = { a = 1.0 }\n",
       "n.toml:7: constraint[1].name", "holds a tab"},
  };
  for (const auto& c : cases) {
    CAPTURE(c.dofs);
    CAPTURE(c.constraint);
    const std::string e = error_of(scene(c.dofs, c.constraint));
    CHECK(e.find(c.where) != std::string::npos);
    CHECK(e.find(c.what) != std::string::npos);
    CHECK(e.find("CSV column") != std::string::npos);
    CHECK(e.find('\n') == std::string::npos);  // the message itself stays on one line
  }
  // What users write stays valid: indices, dots, colons, signs, brackets, spaces inside,
  // slashes, UTF-8 (names as FE programs export them).
  CHECK(error_of(scene(R"(["node 12 x", "N12/\u00e9l\u00e9ment"])", "")) == "");
  CHECK(error_of(scene(R"(["x[1]", "node.3:y-"])",
                       "[[constraint]]\nname = \"tie\"\nterms = { \"x[1]\" = 1.0 }\n")) == "");
  CHECK(error_of(scene(R"(["a", "b"])",
                       "[[constraint]]\nname = \"pin(1)+roll_2\"\nterms = { a = 1.0 }\n")) == "");
}

TEST_CASE("names that give a CSV column twice are refused, under every quantity") {
  struct Case {
    std::string dofs, constraint, where, what;
  };
  const std::string tie = "[[constraint]]\nname = \"tie\"\nterms = { a = 1.0 }\n";
  const Case cases[] = {
      // The fixed columns.
      {R"(["t", "b"])", "", "n.toml:3: model.dofs[1]", "'t', which is already the time column"},
      {R"(["a", "drift_position"])", "", "n.toml:3: model.dofs[2]", "already a drift column"},
      {R"(["a", "drift_velocity"])", "", "n.toml:3: model.dofs[2]", "already a drift column"},
      {R"(["energy_error", "b"])", "", "n.toml:3: model.dofs[1]", "already an energy column"},
      // Generated columns across quantities, either order.
      {R"(["x", "vel_x"])", "", "n.toml:3: model.dofs[2]",
       "'vel_x', which is already the velocity column of DOF 'x'"},
      {R"(["vel_x", "x"])", "", "n.toml:3: model.dofs[2]",
       "DOF 'x' gives the column 'vel_x', which is already the displacement column of DOF "
       "'vel_x'"},
      {R"(["x", "reaction_x"])", "", "n.toml:3: model.dofs[2]",
       "already the reaction column of DOF 'x'"},
      // A multiplier column against a DOF column.
      {R"(["a", "lambda_tie"])", tie, "n.toml:7: constraint[1].name",
       "constraint[1] 'tie' (line 7) gives the column 'lambda_tie', which is already the "
       "displacement column of DOF 'lambda_tie'"},
  };
  for (const auto& c : cases) {
    CAPTURE(c.dofs);
    const std::string e = error_of(scene(c.dofs, c.constraint));
    CHECK(e.find(c.where) != std::string::npos);
    CHECK(e.find(c.what) != std::string::npos);
  }
  // Prefixes alone are not collisions.
  CHECK(error_of(scene(R"(["vel", "x_vel"])", "")) == "");
}

TEST_CASE("a constraint may not take the name of a row the truss adds") {
  const std::string truss = R"([model]
type = "truss2d"
nodes = [[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]]
masses = [1.0, 1.0, 1.0]
supports = [1]
members = [{ nodes = [1, 2], rigid = true }, { nodes = [2, 3], EA = 10.0 }]
[[constraint]]
name = "NAME"
terms = { ux3 = 1.0 }
[solve]
t_end = 1.0
output_step = 0.5
)";
  const auto named = [&](const std::string& name) {
    std::string text = truss;
    text.replace(text.find("NAME"), 4, name);
    return error_of(text);
  };
  CHECK(named("fix_uy1").find("n.toml:8: constraint[1].name: constraint[1] 'fix_uy1' (line 8) "
                              "gives the "
                              "column 'lambda_fix_uy1', which is already the multiplier column "
                              "of the row 'fix_uy1' that model.supports adds") !=
        std::string::npos);
  CHECK(named("rigid_1_2").find("of the row 'rigid_1_2' that model.members[1] adds") !=
        std::string::npos);
  CHECK(named("rigid_2_3") == "");  // an elastic member adds no row
  CHECK(named("fix_ux2") == "");    // node 2 is not supported
}

TEST_CASE("Model::find_dof and dof_at look a DOF up by its name, in names sorted once") {
  Model m;
  m.dof_names = {"uy2", "ux1", "b", "ux10", "a long DOF name beyond the short-string buffer"};
  m.index_dofs();
  for (int i = 0; i < m.dofs(); ++i) {
    const std::string& name = m.dof_names[static_cast<std::size_t>(i)];
    REQUIRE(m.find_dof(name).has_value());
    CHECK(*m.find_dof(name) == i);
    CHECK(m.dof_at(name) == i);
  }
  for (const char* missing : {"", "ux", "ux100", "uy1", "c", "a"}) {
    CHECK_FALSE(m.find_dof(missing).has_value());
    CHECK_THROWS_AS((void)m.dof_at(missing), std::out_of_range);
  }
  const auto built = build_model(parse_scene_text(scene("[\"p\", \"q\"]", ""), "n.toml"));
  CHECK(built.dof_at("q") == 1);
}

}  // namespace test_scene_names
