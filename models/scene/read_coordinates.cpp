// [model] coordinates of a matrix model (docs/scenes.md, "Node coordinates of a matrix model"):
// the nodes its DOFs move, from a CSV file relative to the scene, checked against the DOFs here
// so that a bad file is refused with the scene's key, the file and its line.

#include <filesystem>
#include <fstream>
#include <string>

#include "models/core/node_map.hpp"
#include "models/scene/scene_readers.hpp"

namespace condyn {

void SceneReader::read_coordinates(const toml::node& node, ModelSpec& model) const {
  const std::string p = "model.coordinates";
  const auto& t = table(node, p);
  check_keys(t, p, {"file", "dofs"});
  const auto& file_node = required(t, p, "file");
  const std::string file = file_name(file_node, join(p, "file"));
  DofTemplates templates;
  if (const auto* d = t.get("dofs")) {
    const std::string dp = join(p, "dofs");
    const auto& dofs = table(*d, dp);
    check_keys(dofs, dp, {"x", "y", "z"});
    if (dofs.empty()) fail(*d, dp, "is empty: give x = \"ux{node}\", y = \"uy{node}\", ...");
    for (std::size_t a = 0; a < 3; ++a) {
      const char* axis = a == 0 ? "x" : a == 1 ? "y" : "z";
      if (const auto* n = dofs.get(axis)) {
        templates[a] = string(*n, join(dp, axis));
        if (templates[a].empty()) fail(*n, join(dp, axis), "is empty");
      }
    }
  }
  // Relative to the scene file's folder (a scene given as text: the working directory).
  const std::filesystem::path resolved =
      std::filesystem::path(file_).parent_path() / std::filesystem::path(file);
  input_files_.push_back(resolved.string());
  const std::string key = join(p, "file");
  std::ifstream in(resolved, std::ios::binary);
  if (!in || std::filesystem::is_directory(resolved)) {
    fail(file_node, key, resolved.string() + ": cannot open the file");
  }
  try {
    model.coordinates = read_node_map(in, model.dofs, templates);
  } catch (const NodeMapError& e) {
    const std::string where =
        resolved.string() + (e.line() > 0 ? ":" + std::to_string(e.line()) : std::string());
    fail(file_node, key, where + ": " + e.what());
  }
}

}  // namespace condyn
