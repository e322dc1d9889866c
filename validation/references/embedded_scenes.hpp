#pragma once
/// Scene files from validation/scenes/, compiled into the program.

#include <string>
#include <vector>

namespace condyn {

struct EmbeddedScene {
  std::string name;  ///< file stem, e.g. "chapter_5_5_1"
  std::string text;  ///< the TOML text
};

[[nodiscard]] const std::vector<EmbeddedScene>& embedded_scenes();
/// The scene with this stem; throws std::out_of_range naming it.
[[nodiscard]] const EmbeddedScene& embedded_scene(const std::string& name);

}  // namespace condyn
