#include "models/scene_readers.hpp"

namespace condyn {

void SceneReader::read_initial(const toml::node& node, InitialSpec& initial) const {
  const auto& t = table(node, "initial");
  initial.where = at(node, "initial");
  check_keys(t, "initial", {"displacement", "velocity", "project"});
  if (const auto* pr = t.get("project")) {
    const auto* b = pr->as_boolean();
    if (b == nullptr) fail(*pr, "initial.project", "expected true or false");
    initial.project = b->get();
  }
  if (const auto* d = t.get("displacement")) {
    initial.displacement = dof_values(*d, "initial.displacement");
  }
  if (const auto* v = t.get("velocity")) initial.velocity = dof_values(*v, "initial.velocity");
}

}  // namespace condyn
