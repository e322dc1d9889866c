#include "models/scene/scene_readers.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace condyn {

namespace {

/// The 1-based node number at `n` (key path `p`), one of the `nodes` nodes.
int node_number(const TomlAccess& r, std::size_t nodes, const toml::node& n, const std::string& p) {
  const long k = r.integer(n, p);
  if (k < 1 || k > static_cast<long>(nodes)) {
    r.fail(n, p,
           "node " + std::to_string(k) + " does not exist (nodes are 1.." + std::to_string(nodes) +
               ")");
  }
  return static_cast<int>(k);
}

/// model.nodes ([x, y] or [x, y, z] by `dim`) and their masses (>= 0, one per node).
void read_nodes(const TomlAccess& r, const toml::table& t, const std::string& path, int dim,
                ModelSpec& model) {
  const auto& nodes = r.array(r.required(t, path, "nodes"), "model.nodes");
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const std::string p = TomlAccess::index("model.nodes", i);
    const auto xyz = r.numbers(*nodes.get(i), p);
    if (static_cast<int>(xyz.size()) != dim) {
      r.fail(*nodes.get(i), p, dim == 3 ? "a node is [x, y, z]" : "a node is [x, y]");
    }
    model.nodes.push_back({xyz[0], xyz[1], dim == 3 ? xyz[2] : 0.0});
  }
  if (model.nodes.empty()) r.fail(nodes, "model.nodes", "at least one node is needed");
  const auto& masses_node = r.required(t, path, "masses");
  model.masses = r.numbers(masses_node, "model.masses");
  if (model.masses.size() != model.nodes.size()) {
    r.fail(masses_node, "model.masses",
           "has " + std::to_string(model.masses.size()) + " entries for " +
               std::to_string(model.nodes.size()) + " nodes");
  }
  const auto& masses_arr = r.array(masses_node, "model.masses");
  for (std::size_t i = 0; i < model.masses.size(); ++i) {
    if (model.masses[i] < 0.0) {
      r.fail(*masses_arr.get(i), TomlAccess::index("model.masses", i), "a mass must be >= 0");
    }
  }
}

/// A member's optional `length` (> 0) and dashpot `c` (>= 0, bars only). A bar's rest length
/// other than its nodes' distance is a pre-stress, which only the large-displacement bar carries
/// (the small-displacement bar's force is K u, zero at u = 0).
void read_member_extras(const TomlAccess& r, const toml::table& m, const std::string& p,
                        ModelSpec::Geometry geometry, MemberSpec& member) {
  if (const auto* length = m.get("length")) {
    member.length = r.positive(*length, TomlAccess::join(p, "length"));
    if (!member.rigid && geometry != ModelSpec::Geometry::nonlinear) {
      r.fail(*length, TomlAccess::join(p, "length"),
             "a bar's rest length needs geometry = \"nonlinear\" (a small-displacement bar has "
             "no pre-stress: its length is its nodes' distance)");
    }
  }
  if (const auto* c = m.get("c")) {
    if (member.rigid) {
      r.fail(*c, TomlAccess::join(p, "c"),
             "a rigid member keeps its length, so a damper along it does nothing: remove c or "
             "rigid");
    }
    member.c = r.number(*c, TomlAccess::join(p, "c"));
    if (member.c < 0.0) {
      r.fail(
          *c, TomlAccess::join(p, "c"),
          "must be >= 0 (got " + TomlAccess::fmt(member.c) + "; a negative one feeds energy in)");
    }
  }
}

/// model.members: two different nodes each, elastic (EA) or rigid, no two rigid members on one
/// pair of nodes.
void read_members(const TomlAccess& r, const toml::table& t, const std::string& path,
                  ModelSpec& model) {
  const auto& members = r.array(r.required(t, path, "members"), "model.members");
  // The rigid member already joining each pair of nodes (smaller node first): a second one
  // repeats its constraint, dependent everywhere, and took the same row name (two
  // lambda_rigid_1_2 and a "singular configuration" message).
  std::map<std::pair<int, int>, std::size_t> rigid_pairs;
  for (std::size_t i = 0; i < members.size(); ++i) {
    const std::string p = TomlAccess::index("model.members", i);
    const auto& m = r.table(*members.get(i), p);
    r.check_keys(m, p, {"nodes", "EA", "rigid", "length", "c"});
    MemberSpec member;
    member.where = r.at(*members.get(i), p);
    const auto& ends_node = r.required(m, p, "nodes");
    const auto& ends = r.array(ends_node, TomlAccess::join(p, "nodes"));
    if (ends.size() != 2)
      r.fail(ends_node, TomlAccess::join(p, "nodes"), "a member joins two nodes [i, j]");
    member.node_i = node_number(r, model.nodes.size(), *ends.get(0),
                                TomlAccess::index(TomlAccess::join(p, "nodes"), 0));
    member.node_j = node_number(r, model.nodes.size(), *ends.get(1),
                                TomlAccess::index(TomlAccess::join(p, "nodes"), 1));
    if (member.node_i == member.node_j)
      r.fail(ends_node, TomlAccess::join(p, "nodes"), "a member must join two different nodes");
    if (const auto* rigid = m.get("rigid")) {
      const auto* b = rigid->as_boolean();
      if (b == nullptr) r.fail(*rigid, TomlAccess::join(p, "rigid"), "expected true or false");
      member.rigid = b->get();
    }
    if (member.rigid) {
      if (const auto* ea = m.get("EA")) {
        r.fail(*ea, TomlAccess::join(p, "EA"),
               "a rigid member has no stiffness: remove EA or rigid");
      }
      const auto pair = std::minmax(member.node_i, member.node_j);
      if (const auto [it, added] = rigid_pairs.emplace(pair, i); !added) {
        r.fail(ends_node, TomlAccess::join(p, "nodes"),
               "nodes " + std::to_string(pair.first) + " and " + std::to_string(pair.second) +
                   " are already joined rigidly by " +
                   TomlAccess::index("model.members", it->second) +
                   ": a second rigid member repeats its constraint; remove one");
      }
    } else {
      member.EA = r.positive(r.required(m, p, "EA"), TomlAccess::join(p, "EA"));
    }
    read_member_extras(r, m, p, model.geometry, member);
    model.members.push_back(member);
  }
}

}  // namespace

void SceneReader::read_truss(const toml::table& t, int dim, ModelSpec& model) const {
  const std::string path = "model";
  check_keys(t, path,
             {"type", "nodes", "masses", "members", "geometry", "gravity", "supports", "damping"});
  if (const auto* d = t.get("damping")) read_rayleigh(*d, "model.damping", model);
  model.type = dim == 3 ? ModelSpec::Type::truss3d : ModelSpec::Type::truss2d;
  model.dimension = dim;
  read_nodes(*this, t, path, dim, model);
  if (const auto* g = t.get("geometry")) {  // before the members: a bar's rest length needs it
    const std::string s = string(*g, "model.geometry");
    if (s != "linear" && s != "nonlinear") {
      fail(*g, "model.geometry", "expected 'linear' or 'nonlinear' (got '" + s + "')");
    }
    model.geometry = s == "linear" ? ModelSpec::Geometry::linear : ModelSpec::Geometry::nonlinear;
  }
  read_members(*this, t, path, model);
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
      const int k = node_number(*this, model.nodes.size(), *arr.get(i), index("model.supports", i));
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
  } else if (type == "multibody") {
    read_mechanism_model(t, model);
  } else if (type == "andrews" || type == "car_axis" || type == "pendulum") {
    check_keys(t, path, {"type"});  // the published problem fixes every parameter
    model.type = type == "andrews"    ? ModelSpec::Type::andrews
                 : type == "car_axis" ? ModelSpec::Type::car_axis
                                      : ModelSpec::Type::pendulum;
  } else {
    fail(*t.get("type"), "model.type",
         "unknown model type '" + type +
             "' (expected truss2d, truss3d, matrix, multibody, sleigh, andrews, car_axis or "
             "pendulum)");
  }
}

}  // namespace condyn
