// [ground_motion] (scene-format.md, "Ground motion"): the ground's acceleration and the influence
// vector r, by direction for trusses and by DOF for matrix models. The load −M r a_g(t) is made
// by the builder (models/assembly/ground_motion.cpp), which knows M and the DOF names.

#include <string>

#include "models/scene/scene_readers.hpp"

namespace condyn {

void SceneReader::read_ground_motion(const toml::node& node, const ModelSpec& model,
                                     std::optional<GroundMotionSpec>& out) const {
  const std::string p = "ground_motion";
  const auto& t = table(node, p);
  check_keys(t, p, {"acceleration", "direction", "influence"});
  GroundMotionSpec g;
  g.where = at(node, p);
  const bool truss =
      model.type == ModelSpec::Type::truss2d || model.type == ModelSpec::Type::truss3d;
  if (!truss && model.type != ModelSpec::Type::matrix) {
    fail(node, p, "ground motion applies to truss and matrix models (loads −M r a_g)");
  }
  if (truss) {
    if (const auto* i = t.get("influence")) {
      fail(*i, join(p, "influence"),
           "is for matrix models; a truss gives direction = \"x\" or \"y\"" +
               std::string(model.dimension == 3 ? " or \"z\"" : ""));
    }
    const auto& d = required(t, p, "direction");
    const std::string dir = string(d, join(p, "direction"));
    const std::string axes = model.dimension == 3 ? "x, y or z" : "x or y";
    g.direction = dir == "x" ? 0 : dir == "y" ? 1 : dir == "z" ? 2 : -1;
    if (g.direction < 0 || g.direction >= model.dimension) {
      fail(d, join(p, "direction"),
           "no direction '" + dir + "' in a " + std::to_string(model.dimension) +
               "D truss (expected " + axes + ")");
    }
  } else {
    if (const auto* d = t.get("direction")) {
      fail(*d, join(p, "direction"),
           "is for truss models; a matrix model gives influence = { dof = r, ... }");
    }
    const auto& i = required(t, p, "influence");
    g.influence = dof_values(i, join(p, "influence"), &g.influence_lines);
    bool any = false;
    for (const auto& [name, r] : g.influence) any = any || r != 0.0;
    if (!any) fail(i, join(p, "influence"), "is zero: no DOF moves with the ground");
  }
  g.acceleration = time_function(required(t, p, "acceleration"), join(p, "acceleration"));
  out = std::move(g);
}

}  // namespace condyn
