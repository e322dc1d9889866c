#pragma once
/// Where a model's DOFs sit and which way they move, for drawing deformed and mode shapes
/// (`condyn plot --scene`, docs/plots.md): a truss's nodes and members, or a matrix model's
/// `[model] coordinates` file (docs/scenes.md, "Node coordinates of a matrix model").

#include <array>
#include <istream>
#include <stdexcept>
#include <string>
#include <vector>

namespace condyn {

struct NodeMap {
  int dimension = 2;                            ///< 2: x, y; 3: x, y, z
  std::vector<std::string> nodes;               ///< node ids, as the file (or the truss) names them
  std::vector<std::array<double, 3>> position;  ///< x, y, z of each node (z = 0 in 2D)
  std::vector<std::array<std::string, 3>> dofs;  ///< the DOF moving it along x, y, z ("": none)
  std::vector<std::array<int, 2>> edges;         ///< pairs of node indices drawn as lines
  [[nodiscard]] bool empty() const { return nodes.empty(); }
};

/// A malformed coordinates file: `line` its 1-based line (0: the whole file), what() the problem.
class NodeMapError : public std::runtime_error {
 public:
  NodeMapError(int line, const std::string& what) : std::runtime_error(what), line_(line) {}
  [[nodiscard]] int line() const { return line_; }

 private:
  int line_;
};

/// Names of the DOFs moving each node along x, y, z from templates holding `{node}` (the node's
/// id put in its place: "ux{node}"); an empty template: no DOF along that axis.
using DofTemplates = std::array<std::string, 3>;

/// Reads a coordinates file: comma-separated, `#` lines and blank lines skipped, a header naming
/// `node`, `x`, `y`, optionally `z` and `dof_x`, `dof_y`, `dof_z` (a cell each: the DOF moving the
/// node along that axis, empty for none), one node a row. `dof_names` are the model's DOFs;
/// `templates` (any non-empty) name them instead of the dof_ columns, a node whose name is no DOF
/// having none along that axis. Throws NodeMapError for a missing or unknown column, a row of the
/// wrong length, an empty or repeated node id, a coordinate that is not a finite number, an
/// unknown DOF, a DOF given twice, a template without `{node}` or naming no DOF of any node, and
/// a map that moves no node.
[[nodiscard]] NodeMap read_node_map(std::istream& in, const std::vector<std::string>& dof_names,
                                    const DofTemplates& templates = {});

}  // namespace condyn
