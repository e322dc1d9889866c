#include "models/scene/scene_readers.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace condyn {

void SceneReader::read_truss(const toml::table& t, int dim, ModelSpec& model) const {
  const std::string path = "model";
  check_keys(t, path,
             {"type", "nodes", "masses", "members", "geometry", "gravity", "supports", "damping"});
  if (const auto* d = t.get("damping")) read_rayleigh(*d, "model.damping", model);
  model.type = dim == 3 ? ModelSpec::Type::truss3d : ModelSpec::Type::truss2d;
  model.dimension = dim;
  const auto& nodes = array(required(t, path, "nodes"), "model.nodes");
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const std::string p = index("model.nodes", i);
    const auto xyz = numbers(*nodes.get(i), p);
    if (static_cast<int>(xyz.size()) != dim) {
      fail(*nodes.get(i), p, dim == 3 ? "a node is [x, y, z]" : "a node is [x, y]");
    }
    model.nodes.push_back({xyz[0], xyz[1], dim == 3 ? xyz[2] : 0.0});
  }
  if (model.nodes.empty()) fail(nodes, "model.nodes", "at least one node is needed");
  const auto& masses_node = required(t, path, "masses");
  model.masses = numbers(masses_node, "model.masses");
  if (model.masses.size() != model.nodes.size()) {
    fail(masses_node, "model.masses",
         "has " + std::to_string(model.masses.size()) + " entries for " +
             std::to_string(model.nodes.size()) + " nodes");
  }
  const auto& masses_arr = array(masses_node, "model.masses");
  for (std::size_t i = 0; i < model.masses.size(); ++i) {
    if (model.masses[i] < 0.0) {
      fail(*masses_arr.get(i), index("model.masses", i), "a mass must be >= 0");
    }
  }
  const auto node_number = [&](const toml::node& n, const std::string& p) {
    const long k = integer(n, p);
    if (k < 1 || k > static_cast<long>(model.nodes.size())) {
      fail(n, p,
           "node " + std::to_string(k) + " does not exist (nodes are 1.." +
               std::to_string(model.nodes.size()) + ")");
    }
    return static_cast<int>(k);
  };
  const auto& members = array(required(t, path, "members"), "model.members");
  // The rigid member already joining each pair of nodes (smaller node first): a second one
  // repeats its constraint, dependent everywhere, and took the same row name (two
  // lambda_rigid_1_2 and a "singular configuration" message).
  std::map<std::pair<int, int>, std::size_t> rigid_pairs;
  for (std::size_t i = 0; i < members.size(); ++i) {
    const std::string p = index("model.members", i);
    const auto& m = table(*members.get(i), p);
    check_keys(m, p, {"nodes", "EA", "rigid"});
    MemberSpec member;
    member.where = at(*members.get(i), p);
    const auto& ends_node = required(m, p, "nodes");
    const auto& ends = array(ends_node, join(p, "nodes"));
    if (ends.size() != 2) fail(ends_node, join(p, "nodes"), "a member joins two nodes [i, j]");
    member.node_i = node_number(*ends.get(0), index(join(p, "nodes"), 0));
    member.node_j = node_number(*ends.get(1), index(join(p, "nodes"), 1));
    if (member.node_i == member.node_j)
      fail(ends_node, join(p, "nodes"), "a member must join two different nodes");
    if (const auto* r = m.get("rigid")) {
      const auto* b = r->as_boolean();
      if (b == nullptr) fail(*r, join(p, "rigid"), "expected true or false");
      member.rigid = b->get();
    }
    if (member.rigid) {
      if (const auto* ea = m.get("EA")) {
        fail(*ea, join(p, "EA"), "a rigid member has no stiffness: remove EA or rigid");
      }
      const auto pair = std::minmax(member.node_i, member.node_j);
      if (const auto [it, added] = rigid_pairs.emplace(pair, i); !added) {
        fail(ends_node, join(p, "nodes"),
             "nodes " + std::to_string(pair.first) + " and " + std::to_string(pair.second) +
                 " are already joined rigidly by " + index("model.members", it->second) +
                 ": a second rigid member repeats its constraint; remove one");
      }
    } else {
      member.EA = positive(required(m, p, "EA"), join(p, "EA"));
    }
    model.members.push_back(member);
  }
  if (const auto* g = t.get("geometry")) {
    const std::string s = string(*g, "model.geometry");
    if (s != "linear" && s != "nonlinear") {
      fail(*g, "model.geometry", "expected 'linear' or 'nonlinear' (got '" + s + "')");
    }
    model.geometry = s == "linear" ? ModelSpec::Geometry::linear : ModelSpec::Geometry::nonlinear;
  }
  if (const auto* g = t.get("gravity")) {
    model.gravity = numbers(*g, "model.gravity");
    if (static_cast<int>(model.gravity.size()) != dim) {
      fail(*g, "model.gravity", "needs " + std::to_string(dim) + " components (one per direction)");
    }
  }
  if (const auto* sp = t.get("supports")) {
    const auto& arr = array(*sp, "model.supports");
    std::vector<bool> supported(model.nodes.size(), false);  // linear in the list's length
    for (std::size_t i = 0; i < arr.size(); ++i) {
      const int k = node_number(*arr.get(i), index("model.supports", i));
      if (supported[static_cast<std::size_t>(k - 1)]) {
        fail(*arr.get(i), index("model.supports", i),
             "node " + std::to_string(k) + " is listed twice");
      }
      supported[static_cast<std::size_t>(k - 1)] = true;
      model.supports.push_back(k);
    }
  }
}

void SceneReader::read_model(const toml::node& node, ModelSpec& model) const {
  const std::string path = "model";
  const auto& t = table(node, path);
  model.where = at(node, path);
  const std::string type = string(required(t, path, "type"), "model.type");
  if (type == "truss2d" || type == "truss3d") {
    read_truss(t, type == "truss3d" ? 3 : 2, model);
  } else if (type == "matrix") {
    read_matrix_model(t, model);
  } else if (type == "sleigh") {
    check_keys(t, path, {"type", "mass", "inertia", "contact_offset"});
    model.type = ModelSpec::Type::sleigh;
    model.body_mass = positive(required(t, path, "mass"), "model.mass");
    model.inertia = positive(required(t, path, "inertia"), "model.inertia");
    if (const auto* a = t.get("contact_offset"))
      model.contact_offset = number(*a, "model.contact_offset");
  } else if (type == "andrews" || type == "car_axis" || type == "pendulum") {
    check_keys(t, path, {"type"});  // the published problem fixes every parameter
    model.type = type == "andrews"    ? ModelSpec::Type::andrews
                 : type == "car_axis" ? ModelSpec::Type::car_axis
                                      : ModelSpec::Type::pendulum;
  } else {
    fail(*t.get("type"), "model.type",
         "unknown model type '" + type +
             "' (expected truss2d, truss3d, matrix, sleigh, andrews, car_axis or pendulum)");
  }
}

}  // namespace condyn
