#include "models/scene/scene_readers.hpp"

namespace condyn {

void SceneReader::read_initial(const toml::node& node, InitialSpec& initial) const {
  const auto& t = table(node, "initial");
  initial.where = at(node, "initial");
  check_keys(t, "initial", {"displacement", "velocity", "project", "static", "keep"});
  if (const auto* pr = t.get("project")) {
    const auto* b = pr->as_boolean();
    if (b == nullptr) fail(*pr, "initial.project", "expected true or false");
    initial.project = b->get();
  }
  if (const auto* st = t.get("static")) {
    const auto* b = st->as_boolean();
    if (b == nullptr) fail(*st, "initial.static", "expected true or false");
    initial.static_start = b->get();
    if (initial.static_start && initial.project) {
      fail(*st, "initial.static",
           "static = true and project = true cannot be combined: the static equilibrium already "
           "meets the position constraints; give velocities that meet the velocity constraints");
    }
    if (initial.static_start && t.contains("displacement")) {
      fail(*st, "initial.static",
           "static = true computes every initial displacement; remove [initial] displacement "
           "(or static = true)");
    }
  }
  if (const auto* d = t.get("displacement")) {
    initial.displacement = dof_values(*d, "initial.displacement", &initial.displacement_lines);
  }
  if (const auto* k = t.get("keep")) {  // checked against the bodies: read_mechanism_names.cpp
    const auto& arr = array(*k, "initial.keep");
    for (std::size_t i = 0; i < arr.size(); ++i) {
      initial.keep.push_back(string(*arr.get(i), index("initial.keep", i)));
      initial.keep_lines.push_back(at(*arr.get(i), index("initial.keep", i)).line);
    }
  }
  if (const auto* v = t.get("velocity")) {
    initial.velocity = dof_values(*v, "initial.velocity", &initial.velocity_lines);
  }
}

}  // namespace condyn
