#include "models/scene/scene_node_map.hpp"

#include <string>

namespace condyn {

NodeMap scene_node_map(const SceneSpec& spec) {
  const ModelSpec& m = spec.model;
  if (m.type == ModelSpec::Type::matrix) return m.coordinates;
  NodeMap map;
  if (m.type != ModelSpec::Type::truss2d && m.type != ModelSpec::Type::truss3d) return map;
  // The truss builder's DOF names (models/assembly/truss_assembly.cpp).
  static constexpr std::array<const char*, 3> kTrussAxes = {"ux", "uy", "uz"};
  map.dimension = m.dimension;
  for (std::size_t k = 0; k < m.nodes.size(); ++k) {
    const std::string id = std::to_string(k + 1);
    map.nodes.push_back(id);
    map.position.push_back(m.nodes[k]);
    std::array<std::string, 3> dofs;
    for (std::size_t a = 0; a < static_cast<std::size_t>(m.dimension); ++a)
      dofs[a] = kTrussAxes[a] + id;
    map.dofs.push_back(dofs);
  }
  for (const auto& member : m.members) map.edges.push_back({member.node_i - 1, member.node_j - 1});
  return map;
}

}  // namespace condyn
