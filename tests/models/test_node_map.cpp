// Issue 47, item 9: a matrix model's [model] coordinates (docs/scenes.md, "Node coordinates of a
// matrix model"), the nodes its DOFs move for `condyn plot --scene`: the file's two ways of naming
// the DOFs, a truss's own nodes, and every refusal with the key, the file and its line.
#include <doctest/doctest.h>

#include <sstream>
#include <string>

#include "models/core/node_map.hpp"
#include "models/scene/scene_node_map.hpp"
#include "models/scene/scene_parser.hpp"
#include "tests/cli_sandbox.hpp"
#include "tests/scene_text.hpp"

using namespace condyn;

namespace test_node_map {

using condyn::test::replace;
using condyn::test::Sandbox;

namespace {

bool has(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

const std::vector<std::string> kDofs = {"u1", "u2", "u3", "u4"};

NodeMap read(const std::string& text, const DofTemplates& templates = {}) {
  std::istringstream in(text);
  return read_node_map(in, kDofs, templates);
}

/// What read() refuses `text` with: "LINE: problem" (line 0: the whole file).
std::string refusal(const std::string& text, const DofTemplates& templates = {}) {
  try {
    (void)read(text, templates);
  } catch (const NodeMapError& e) {
    return std::to_string(e.line()) + ": " + e.what();
  }
  return "accepted";
}

const std::string kMatrix = R"([model]
type = "matrix"
dofs = ["ux2", "uy2", "ux3", "uy3"]
mass = [[1.0, 0.0, 0.0, 0.0], [0.0, 1.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0], [0.0, 0.0, 0.0, 1.0]]
stiffness = [[2.0, 0.0, 0.0, 0.0], [0.0, 2.0, 0.0, 0.0], [0.0, 0.0, 2.0, 0.0], [0.0, 0.0, 0.0, 2.0]]
coordinates = { file = "nodes.csv", dofs = { x = "ux{node}", y = "uy{node}" } }
[solve]
t_end = 1.0
output_step = 0.5
)";

}  // namespace

TEST_CASE("node map: dof_ columns, in any order, comments and blanks skipped") {
  const NodeMap m = read(
      "# an FE export\nnode, y, x, dof_x, dof_y\n\n10, 0.0, 1.5, u1, u2\n20, 3.0, 1.5, u3,\r\n");
  CHECK(m.dimension == 2);
  CHECK(m.nodes == std::vector<std::string>{"10", "20"});
  CHECK(m.position[0] == std::array<double, 3>{1.5, 0.0, 0.0});
  CHECK(m.position[1] == std::array<double, 3>{1.5, 3.0, 0.0});
  CHECK(m.dofs[0] == std::array<std::string, 3>{"u1", "u2", ""});
  CHECK(m.dofs[1] == std::array<std::string, 3>{"u3", "", ""});  // empty: no DOF along y
  CHECK(m.edges.empty());
  // 3D, with a z column.
  const NodeMap z = read("node,x,y,z,dof_z\n1,0,0,2,u4\n");
  CHECK(z.dimension == 3);
  CHECK(z.dofs[0] == std::array<std::string, 3>{"", "", "u4"});
}

TEST_CASE("node map: DOF names from the node ids, a node without its DOF a support") {
  const NodeMap m = read("node,x,y\n1,0,0\n2,0,3\n3,0,6\n", {"u{node}", "", ""});
  CHECK(m.dofs[0] == std::array<std::string, 3>{"u1", "", ""});
  CHECK(m.dofs[2] == std::array<std::string, 3>{"u3", "", ""});
  // Node 5's u5 is no DOF: none along x, as a support condensed out of the matrices.
  CHECK(read("node,x,y\n5,0,0\n4,0,3\n", {"u{node}", "", ""}).dofs[0][0].empty());
}

TEST_CASE("node map: refusals name the line and what is wrong") {
  CHECK(refusal("node,x\n1,0\n") ==
        "1: the header has no column 'y' (expected node, x, y and "
        "optionally z, dof_x, dof_y, dof_z)");
  CHECK(refusal("node,x,y,w\n") ==
        "1: unknown column 'w' (expected node, x, y and optionally z, "
        "dof_x, dof_y, dof_z)");
  CHECK(refusal("node,x,y,x\n") == "1: the column 'x' is named twice");
  CHECK(refusal("node,x,y,dof_z\n") == "1: a column dof_z needs a column z");
  CHECK(has(refusal("node,x,y\n1,0,0\n"),
            "1: no dof_x, dof_y columns, and the scene gives no "
            "dofs"));
  CHECK(refusal("node,x,y,dof_x\n", {"u{node}", "", ""}) ==
        "1: the file has dof_ columns and the scene gives dofs: give one");
  CHECK(refusal("node,x,y,dof_x\n1,0,0\n") == "2: has 3 cells, the header 4");
  CHECK(refusal("node,x,y,dof_x\n,0,0,u1\n") == "2: the node id is empty");
  CHECK(refusal("node,x,y,dof_x\n1,0,0,u1\n1,0,1,u2\n") ==
        "3: node '1' is listed twice (also on line 2)");
  CHECK(refusal("node,x,y,dof_x\n1,0,north,u1\n") == "2: y 'north' is not a number");
  CHECK(refusal("node,x,y,dof_x\n1,inf,0,u1\n") == "2: x 'inf' is not finite");
  CHECK(refusal("node,x,y,dof_x\n1,1e999,0,u1\n") ==
        "2: x '1e999' is out of the double range (beyond about 1.8e308, or nonzero below "
        "4.9e-324)");
  CHECK(refusal("node,x,y,dof_x\n1,0,0,u9\n") ==
        "2: no such DOF 'u9' (the nearest: u1, u2, u3, "
        "u4)");
  CHECK(refusal("node,x,y,dof_x,dof_y\n1,0,0,u1,u1\n") ==
        "2: DOF 'u1' moves node 1 along x already; node 1 along y needs a DOF of its own");
  CHECK(refusal("node,x,y\n1,0,0\n", {"u{node}", "u{node}", ""}) ==
        "2: DOF 'u1' moves node 1 along x already; node 1 along y needs a DOF of its own");
  CHECK(refusal("node,x,y\n1,0,0\n", {"ux", "", ""}) ==
        "0: the DOF name for x, 'ux', holds no {node} (where the node's id goes)");
  CHECK(refusal("node,x,y\n1,0,0\n", {"ux{node}", "", ""}) ==
        "0: the DOF name for x, 'ux{node}', names no DOF of any node (node 1 gives 'ux1')");
  CHECK(refusal("node,x,y\n1,0,0\n", {"u{node}", "", "w{node}"}) ==
        "1: the scene gives a DOF name for z but the file has no column z");
  CHECK(refusal("node,x,y,dof_x\n") == "0: no nodes (a header, then one row per node)");
  CHECK(refusal("node,x,y,dof_x\n1,0,0,\n") == "0: no node has a DOF: nothing would move");
}

TEST_CASE("node map: [model] coordinates in a scene, and a truss's own nodes") {
  Sandbox box;
  box.write("nodes.csv", "node,x,y\n1,0,0\n2,0,3\n3,4,3\n");
  const SceneSpec spec = parse_scene_file(box.write("scene.toml", kMatrix).string());
  const NodeMap m = scene_node_map(spec);
  REQUIRE(m.nodes.size() == 3);
  CHECK(m.dofs[0] == std::array<std::string, 3>{"", "", ""});  // node 1: a support, no DOF
  CHECK(m.dofs[2] == std::array<std::string, 3>{"ux3", "uy3", ""});
  CHECK(spec.input_files.back() == box.path("nodes.csv").string());
  // Without coordinates: none.
  const std::string bare = replace(kMatrix,
                                   "coordinates = { file = \"nodes.csv\", dofs = { x = "
                                   "\"ux{node}\", y = \"uy{node}\" } }\n",
                                   "");
  CHECK(scene_node_map(parse_scene_file(box.write("bare.toml", bare).string())).empty());
  // A truss: its nodes, DOFs ux<k>, uy<k>, and its members as edges.
  const SceneSpec truss = parse_scene_file(box.write("truss.toml", R"([model]
type = "truss2d"
nodes = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0]]
masses = [0.0, 1.0, 1.0]
supports = [1]
members = [{ nodes = [1, 2], EA = 1.0 }, { nodes = [2, 3], EA = 1.0 }]
[solve]
t_end = 1.0
output_step = 0.5
)")
                                               .string());
  const NodeMap t = scene_node_map(truss);
  CHECK(t.nodes == std::vector<std::string>{"1", "2", "3"});
  CHECK(t.dofs[1] == std::array<std::string, 3>{"ux2", "uy2", ""});
  CHECK(t.edges == std::vector<std::array<int, 2>>{{0, 1}, {1, 2}});
}

TEST_CASE("node map: a bad coordinates file or key is refused with the scene's key") {
  Sandbox box;
  const auto error = [&](const std::string& scene) {
    try {
      (void)parse_scene_file(box.write("scene.toml", scene).string());
    } catch (const SceneError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  box.write("nodes.csv", "node,x,y\n2,0,0\n3,0,north\n");
  CHECK(has(error(kMatrix), "scene.toml:6: model.coordinates.file: " +
                                box.path("nodes.csv").string() + ":3: y 'north' is not a number"));
  CHECK(has(error(replace(kMatrix, "nodes.csv", "gone.csv")),
            "model.coordinates.file: " + box.path("gone.csv").string() + ": cannot open the file"));
  CHECK(has(error(replace(kMatrix, "dofs = {", "nodes = 1, dofs = {")),
            "model.coordinates.nodes: unknown key"));
  CHECK(has(error(replace(kMatrix, "x = \"ux{node}\", y = \"uy{node}\"", "")),
            "model.coordinates.dofs: is empty"));
  CHECK(has(error(replace(kMatrix, "x = \"ux{node}\"", "x = 1")), "model.coordinates.dofs.x: "));
  CHECK(has(error(replace(kMatrix, "\"matrix\"", "\"matrix\"\ncoordinates_ = 1")),
            "model.coordinates_: unknown key"));
}

}  // namespace test_node_map
