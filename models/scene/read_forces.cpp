// [[force]] of a multibody model (docs/scenes.md, "Mechanisms of rigid bodies"): spring-dampers
// between two points, rotational spring-dampers at revolute joints, point forces and torques
// given by time functions (gravity is [model] gravity).

#include <string>
#include <vector>

#include "models/core/nearest_names.hpp"
#include "models/scene/scene_readers.hpp"

namespace condyn {

namespace {

using ForceType = Mechanism::ForceType;

/// A non-negative number (a stiffness or damping coefficient).
double coefficient(const SceneReader& r, const toml::node& node, const std::string& p) {
  const double v = r.number(node, p);
  if (v < 0.0) r.fail(node, p, "must be >= 0 (got " + TomlAccess::fmt(v) + ")");
  return v;
}

/// `count` time functions as a list at `p` (a point force's or a spatial torque's global
/// components).
std::vector<TimeFunction> components(const SceneReader& r, const toml::node& node,
                                     const std::string& p, int count) {
  const auto& arr = r.array(node, p);
  if (static_cast<int>(arr.size()) != count) {
    r.fail(node, p,
           "needs " + std::to_string(count) +
               " components (global; each a number or a time "
               "function), got " +
               std::to_string(arr.size()));
  }
  std::vector<TimeFunction> out;
  for (std::size_t k = 0; k < arr.size(); ++k)
    out.push_back(r.time_function(*arr.get(k), TomlAccess::index(p, k)));
  return out;
}

/// The revolute joint named at `node`.
int revolute_joint(const SceneReader& r, const Mechanism& m, const toml::node& node,
                   const std::string& p) {
  const std::string name = r.string(node, p);
  std::vector<std::string> names;
  for (std::size_t k = 0; k < m.joints.size(); ++k) {
    names.push_back(m.joints[k].name);
    if (m.joints[k].name != name) continue;
    if (m.joints[k].type != Mechanism::JointType::revolute) {
      r.fail(node, p,
             "joint '" + name + "' is " + to_string(m.joints[k].type) +
                 ": a rotational spring-damper acts at a revolute joint");
    }
    return static_cast<int>(k);
  }
  const auto near = nearest_names(name, names, 3);
  r.fail(node, p,
         "unknown joint '" + name + "'" +
             (near.empty() ? std::string() : " (did you mean " + joined_names(near) + "?)"));
}

/// The body at key `key` of `t`, which must not be the ground (a load on the ground does nothing).
int loaded_body(const SceneReader& r, const Mechanism& m, const toml::table& t,
                const std::string& p, const char* key) {
  const auto& node = r.required(t, p, key);
  const int b = r.body_index(m, node, TomlAccess::join(p, key));
  if (b == Mechanism::kGround) {
    r.fail(node, TomlAccess::join(p, key), "the ground does not move: load a body");
  }
  return b;
}

Mechanism::Force read_force(const SceneReader& r, const Mechanism& m, const toml::node& node,
                            const std::string& p) {
  const auto& t = r.table(node, p);
  Mechanism::Force f;
  f.where = r.at(node, p);
  const std::string type = r.string(r.required(t, p, "type"), TomlAccess::join(p, "type"));
  const auto number_or = [&](const char* key, double fallback) {
    const auto* n = t.get(key);
    return n != nullptr ? coefficient(r, *n, TomlAccess::join(p, key)) : fallback;
  };
  if (type == "spring_damper") {
    r.check_keys(t, p, {"type", "bodies", "points", "k", "c", "rest_length"});
    f.type = ForceType::spring_damper;
    const std::string bp = TomlAccess::join(p, "bodies"), pp = TomlAccess::join(p, "points");
    const auto& bodies = r.array(r.required(t, p, "bodies"), bp);
    const auto& points = r.array(r.required(t, p, "points"), pp);
    if (bodies.size() != 2) r.fail(*t.get("bodies"), bp, "a spring-damper joins two bodies");
    if (points.size() != 2) r.fail(*t.get("points"), pp, "a spring-damper joins two points");
    for (std::size_t k = 0; k < 2; ++k) {
      f.bodies[k] = r.body_index(m, *bodies.get(k), TomlAccess::index(bp, k));
      f.points[k] = r.marker_index(m, f.bodies[k], false, *points.get(k), TomlAccess::index(pp, k));
    }
    if (f.bodies[0] == f.bodies[1]) {
      r.fail(*t.get("bodies"), bp, "a spring-damper joins two different bodies");
    }
    f.k = coefficient(r, r.required(t, p, "k"), TomlAccess::join(p, "k"));
    f.c = number_or("c", 0.0);
    if (const auto* l = t.get("rest_length")) {
      f.rest_length = coefficient(r, *l, TomlAccess::join(p, "rest_length"));
    }
  } else if (type == "rotational_spring_damper") {
    r.check_keys(t, p, {"type", "joint", "k", "c", "rest_angle"});
    f.type = ForceType::rotational_spring_damper;
    f.joint = revolute_joint(r, m, r.required(t, p, "joint"), TomlAccess::join(p, "joint"));
    f.bodies = m.joints[static_cast<std::size_t>(f.joint)].bodies;
    f.k = coefficient(r, r.required(t, p, "k"), TomlAccess::join(p, "k"));
    f.c = number_or("c", 0.0);
    if (const auto* a = t.get("rest_angle")) {
      f.rest_angle = r.number(*a, TomlAccess::join(p, "rest_angle"));
    }
  } else if (type == "point_force") {
    r.check_keys(t, p, {"type", "body", "point", "force"});
    f.type = ForceType::point_force;
    f.bodies[0] = loaded_body(r, m, t, p, "body");
    f.points[0] = r.marker_index(m, f.bodies[0], false, r.required(t, p, "point"),
                                 TomlAccess::join(p, "point"));
    f.components =
        components(r, r.required(t, p, "force"), TomlAccess::join(p, "force"), m.dimension);
  } else if (type == "torque") {
    r.check_keys(t, p, {"type", "body", "torque"});
    f.type = ForceType::torque;
    f.bodies[0] = loaded_body(r, m, t, p, "body");
    const auto& tq = r.required(t, p, "torque");
    const std::string tp = TomlAccess::join(p, "torque");
    f.components = m.dimension == 2 ? std::vector<TimeFunction>{r.time_function(tq, tp)}
                                    : components(r, tq, tp, 3);
  } else {
    const std::vector<std::string> names{"spring_damper", "rotational_spring_damper", "point_force",
                                         "torque"};
    const auto near = nearest_names(type, names, 1);
    r.fail(*t.get("type"), TomlAccess::join(p, "type"),
           "unknown force type '" + type + "' (" +
               (near.empty() ? std::string() : "did you mean " + near[0] + "? ") +
               "expected one of: " + joined_names(names) + ")");
  }
  return f;
}

}  // namespace

void SceneReader::read_forces(const toml::node& node, Mechanism& mechanism) const {
  const auto& arr = array(node, "force");
  for (std::size_t i = 0; i < arr.size(); ++i)
    mechanism.forces.push_back(read_force(*this, mechanism, *arr.get(i), index("force", i)));
}

}  // namespace condyn
