// [ground_motion] (scene-format.md, "Ground motion"): the ground's acceleration and the influence
// vector r, by direction for trusses and by DOF for matrix models. The load −M r a_g(t) is made
// by the builder (models/assembly/ground_motion.cpp), which knows M and the DOF names.

#include <algorithm>
#include <string>

#include "models/scene/scene_readers.hpp"

namespace condyn {

/// influence = { file = "r.mtx" } (an n x 1 Matrix Market vector; a string `file`: a DOF named
/// "file" keeps its number), or { dof-or-pattern = r, ... }, resolved against the DOFs by the
/// builder (models/assembly/influence_vector.cpp).
void SceneReader::read_influence(const toml::node& node, const std::string& path,
                                 GroundMotionSpec& g) const {
  const auto& t = table(node, path);
  if (const auto* f = t.get("file"); f != nullptr && f->is_string()) {
    if (t.size() > 1) {
      fail(node, path,
           "give either file = \"r.mtx\" or DOF names and patterns (dof = r, \"ux*\" = r), "
           "not both");
    }
    MarketExpectation size = pattern_size();
    size.because = "an influence vector is n x 1 (n = " + std::to_string(size.rows) + " DOFs)";
    g.influence_file = matrix_file(node, path, size);
    const auto& r = g.influence_file.matrix;
    if (std::all_of(r.valuePtr(), r.valuePtr() + r.nonZeros(), [](double v) { return v == 0.0; })) {
      // An array handed over by Python is named by its own key (python/scene_from_python.cpp).
      const bool array = g.influence_file.in_memory();
      fail(
          *f, array ? path : join(path, "file"),
          (array ? "the array" : g.influence_file.file) + " is zero: no DOF moves with the ground");
    }
    return;
  }
  g.influence = dof_values(node, path, &g.influence_lines);
  bool any = false;
  for (const auto& [name, r] : g.influence) any = any || r != 0.0;
  if (!any) fail(node, path, "is zero: no DOF moves with the ground");
}

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
    read_influence(required(t, p, "influence"), join(p, "influence"), g);
  }
  g.acceleration = time_function(required(t, p, "acceleration"), join(p, "acceleration"));
  out = std::move(g);
}

}  // namespace condyn
