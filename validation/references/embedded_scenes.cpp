#include "validation/references/embedded_scenes.hpp"

#include <stdexcept>

namespace condyn {

const EmbeddedScene& embedded_scene(const std::string& name) {
  for (const auto& s : embedded_scenes()) {
    if (s.name == name) return s;
  }
  throw std::out_of_range("no embedded scene named '" + name + "'");
}

}  // namespace condyn
