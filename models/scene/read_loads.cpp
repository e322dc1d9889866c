#include "models/scene/scene_readers.hpp"

#include <string>
#include <utility>
#include <vector>

namespace condyn {

void SceneReader::read_loads(const toml::node& node, std::vector<LoadSpec>& out) const {
  const auto& loads = array(node, "load");
  for (std::size_t i = 0; i < loads.size(); ++i) {
    const std::string p = index("load", i);
    const auto& t = table(*loads.get(i), p);
    check_keys(t, p, {"dof", "pattern", "value"});
    LoadSpec load;
    load.where = at(*loads.get(i), p);
    if (const auto* pat = t.get("pattern")) {
      if (t.contains("dof")) fail(*pat, join(p, "pattern"), "give either dof or pattern, not both");
      load.pattern = matrix_file(*pat, join(p, "pattern"), pattern_size());
    } else {
      load.dof = string(required(t, p, "dof"), join(p, "dof"));
    }
    load.value = time_function(required(t, p, "value"), join(p, "value"));
    out.push_back(std::move(load));
  }
}

}  // namespace condyn
