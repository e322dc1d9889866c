// [[joint]] of a multibody model (docs/scenes.md, "Mechanisms of rigid bodies"): its type, the
// two bodies and their markers, and a drive. What each type needs is checked here, where the
// key has a line; whether the poses meet the joint at t = 0 is the builder's
// (models/assembly/multibody_model.cpp), which evaluates the rows.

#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <unordered_map>
#include <vector>

#include "models/core/nearest_names.hpp"
#include "models/scene/scene_readers.hpp"

namespace condyn {

namespace {

using JointType = Mechanism::JointType;

// A drive's value at t = 0 counts as 0 within this roundoff of its terms' size (a harmonic
// written with phase π is sin(π) = 1.2e-16 of its amplitude there).
constexpr double kDriveRoundoff = 64 * std::numeric_limits<double>::epsilon();

constexpr std::array<JointType, 9> kTypes = {
    JointType::revolute,  JointType::prismatic,     JointType::fixed,
    JointType::distance,  JointType::point_on_line, JointType::spherical,
    JointType::universal, JointType::cylindrical,   JointType::point_on_plane};

bool spatial_only(JointType type) {
  return type == JointType::spherical || type == JointType::universal ||
         type == JointType::cylindrical || type == JointType::point_on_plane;
}

/// Whether the type needs an axis of each body in this dimension (docs/scenes.md).
bool needs_axes(JointType type, int dim) {
  if (type == JointType::prismatic || type == JointType::point_on_line) return true;
  return dim == 3 && (type == JointType::revolute || type == JointType::cylindrical ||
                      type == JointType::universal || type == JointType::point_on_plane);
}

/// The marker `which` of body `body` in global coordinates at t = 0.
Eigen::Vector3d global_point(const Mechanism& m, int body, int point) {
  if (body == Mechanism::kGround) {
    const auto& at = m.ground_points[static_cast<std::size_t>(point)].at;
    return {at[0], at[1], at[2]};
  }
  const auto& b = m.bodies[static_cast<std::size_t>(body)];
  const auto& s = b.points[static_cast<std::size_t>(point)].at;
  return Eigen::Vector3d(b.position[0], b.position[1], b.position[2]) +
         b.orientation * Eigen::Vector3d(s[0], s[1], s[2]);
}

}  // namespace

namespace {

JointType joint_type(const SceneReader& r, const toml::node& node, const std::string& p, int dim) {
  const std::string s = r.string(node, p);
  std::vector<std::string> names;
  for (JointType type : kTypes) {
    names.emplace_back(to_string(type));
    if (s != to_string(type)) continue;
    if (spatial_only(type) && dim == 2) {
      r.fail(node, p,
             "a " + s +
                 " joint is spatial: it needs [model] dimension = 3 (planar joints: "
                 "revolute, prismatic, fixed, distance, point_on_line)");
    }
    return type;
  }
  const auto near = nearest_names(s, names, 1);
  r.fail(node, p,
         "unknown joint type '" + s + "' (" +
             (near.empty() ? std::string() : "did you mean " + near[0] + "? ") +
             "expected one of: " + joined_names(names) + ")");
}

/// A list of two names at `p` (`what`: "bodies", "points", "axes").
std::array<const toml::node*, 2> pair_of(const SceneReader& r, const toml::node& node,
                                         const std::string& p, const char* what) {
  const auto& arr = r.array(node, p);
  if (arr.size() != 2) {
    r.fail(node, p,
           std::string("a joint names two ") + what +
               ", one of each body, in the order of "
               "bodies (got " +
               std::to_string(arr.size()) + ")");
  }
  return {arr.get(0), arr.get(1)};
}

/// drive: revolute or prismatic, 0 at t = 0, no step after t = 0.
TimeFunction read_drive(const SceneReader& r, const toml::node& node, const std::string& p,
                        JointType type) {
  if (type != JointType::revolute && type != JointType::prismatic) {
    r.fail(node, p,
           std::string("a ") + to_string(type) +
               " joint has no coordinate to drive (drives prescribe a revolute joint's angle or "
               "a prismatic joint's slide)");
  }
  TimeFunction f = r.time_function(node, p);
  const double f0 = f.value(0.0);
  if (!(std::abs(f0) <= kDriveRoundoff * f.magnitude(0, 0.0))) {
    r.fail(node, p,
           "is " + TomlAccess::fmt(f0) +
               " at t = 0, but a drive counts the joint's coordinate from its value at t = 0: "
               "it must start at 0 (pose the bodies instead)");
  }
  for (double b : f.breakpoints()) {
    r.fail(node, p,
           "a step at t = " + TomlAccess::fmt(b) +
               " would make the driven coordinate jump (an infinite velocity): use a smooth "
               "function");
  }
  return f;
}

/// One [[joint]] table at `p`.
Mechanism::Joint read_joint(const SceneReader& r, const Mechanism& m, const toml::node& node,
                            const std::string& p, std::size_t i) {
  const auto& t = r.table(node, p);
  r.check_keys(t, p, {"name", "type", "bodies", "points", "axes", "length", "drive"});
  Mechanism::Joint j;
  j.where = r.at(node, p);
  j.name = t.contains("name")
               ? r.mechanism_name(*t.get("name"), TomlAccess::join(p, "name"), "joint")
               : "joint" + std::to_string(i + 1);
  j.type = joint_type(r, r.required(t, p, "type"), TomlAccess::join(p, "type"), m.dimension);
  const std::string bp = TomlAccess::join(p, "bodies");
  const auto bodies = pair_of(r, r.required(t, p, "bodies"), bp, "bodies");
  for (int k = 0; k < 2; ++k) j.bodies[k] = r.body_index(m, *bodies[k], TomlAccess::index(bp, k));
  if (j.bodies[0] == j.bodies[1]) {
    r.fail(r.required(t, p, "bodies"), bp, "a joint connects two different bodies");
  }
  const std::string pp = TomlAccess::join(p, "points");
  const auto points = pair_of(r, r.required(t, p, "points"), pp, "points");
  for (int k = 0; k < 2; ++k)
    j.points[k] = r.marker_index(m, j.bodies[k], false, *points[k], TomlAccess::index(pp, k));
  const std::string ap = TomlAccess::join(p, "axes");
  if (needs_axes(j.type, m.dimension)) {
    if (!t.contains("axes")) {
      r.fail(node, p,
             std::string("a ") + (m.dimension == 3 ? "spatial " : "planar ") + to_string(j.type) +
                 " joint needs axes = [axis of " +
                 (j.bodies[0] == Mechanism::kGround ? "the ground" : "body 1") +
                 ", axis of body 2] (named in [model] ground_axes or the bodies' axes)");
    }
    const auto axes = pair_of(r, *t.get("axes"), ap, "axes");
    for (int k = 0; k < 2; ++k)
      j.axes[k] = r.marker_index(m, j.bodies[k], true, *axes[k], TomlAccess::index(ap, k));
  } else if (const auto* a = t.get("axes")) {
    r.fail(*a, ap,
           std::string("a ") + (m.dimension == 3 ? "spatial " : "planar ") + to_string(j.type) +
               " joint takes no axes" +
               (m.dimension == 2 && j.type == JointType::revolute ? " (it turns about z)" : "") +
               ": remove the key");
  }
  if (const auto* l = t.get("length")) {
    if (j.type != JointType::distance) {
      r.fail(*l, TomlAccess::join(p, "length"), "only a distance joint has a length");
    }
    j.length = r.positive(*l, TomlAccess::join(p, "length"));
  } else if (j.type == JointType::distance) {
    const double d =
        (global_point(m, j.bodies[0], j.points[0]) - global_point(m, j.bodies[1], j.points[1]))
            .norm();
    if (!(d > 0.0)) {
      r.fail(node, p,
             "the distance joint's points coincide at t = 0, so the length it keeps would be 0: "
             "give length, or use a revolute (2D) or spherical (3D) joint");
    }
  }
  if (const auto* d = t.get("drive"))
    j.drive = read_drive(r, *d, TomlAccess::join(p, "drive"), j.type);
  return j;
}

}  // namespace

void SceneReader::read_joints(const toml::node& node, Mechanism& mechanism) const {
  const auto& arr = array(node, "joint");
  std::unordered_map<std::string, std::size_t> seen;
  for (std::size_t i = 0; i < arr.size(); ++i) {
    const std::string p = index("joint", i);
    Mechanism::Joint j = read_joint(*this, mechanism, *arr.get(i), p, i);
    const auto* name_node = arr.get(i)->as_table()->get("name");
    const toml::node& at_node = name_node != nullptr ? *name_node : *arr.get(i);
    if (find_body(mechanism, j.name) >= 0) {
      fail(at_node, join(p, "name"),
           "'" + j.name +
               "' is also a body's name: joints and bodies name output columns "
               "alike (" +
               j.name + ".x, " + j.name + ".fx), so their names must be distinct");
    }
    if (const auto [at, fresh] = seen.emplace(j.name, i); !fresh) {
      fail(at_node, join(p, "name"),
           "joint '" + j.name + "' is already " + index("joint", at->second) +
               ": joint names must be distinct");
    }
    mechanism.joints.push_back(std::move(j));
  }
}

}  // namespace condyn
