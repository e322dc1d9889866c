#include "models/core/mechanism_keep.hpp"

#include <array>
#include <string_view>

#include "models/core/nearest_names.hpp"

namespace condyn {

namespace {

struct KeyMeaning {
  std::string_view key;
  KeptValue::Kind kind;
  int component;  ///< -1: every component of the dimension
  int dimension;  ///< 0: both
};

constexpr std::array<KeyMeaning, 19> kKeys = {{
    {"x", KeptValue::Kind::position, 0, 0},
    {"y", KeptValue::Kind::position, 1, 0},
    {"z", KeptValue::Kind::position, 2, 3},
    {"position", KeptValue::Kind::position, -1, 0},
    {"angle", KeptValue::Kind::orientation, 0, 2},
    {"orientation", KeptValue::Kind::orientation, 0, 3},
    {"vx", KeptValue::Kind::velocity, 0, 0},
    {"vy", KeptValue::Kind::velocity, 1, 0},
    {"vz", KeptValue::Kind::velocity, 2, 3},
    {"velocity", KeptValue::Kind::velocity, -1, 0},
    {"omega", KeptValue::Kind::angular_velocity, 2, 2},
    {"wx", KeptValue::Kind::angular_velocity, 0, 3},
    {"wy", KeptValue::Kind::angular_velocity, 1, 3},
    {"wz", KeptValue::Kind::angular_velocity, 2, 3},
    {"angular_velocity", KeptValue::Kind::angular_velocity, -1, 0},
    // The quaternion's columns: one component alone is no value a pose keeps (the others would
    // move to keep it unit); refused below, with the key that keeps the whole orientation.
    {"qw", KeptValue::Kind::orientation, -2, 3},
    {"qx", KeptValue::Kind::orientation, -2, 3},
    {"qy", KeptValue::Kind::orientation, -2, 3},
    {"qz", KeptValue::Kind::orientation, -2, 3},
}};

}  // namespace

std::vector<KeptValue> kept_values(const Mechanism& mechanism, const std::string& name,
                                   std::string& problem) {
  const auto dot = name.find('.');
  const std::string body = name.substr(0, dot);
  std::vector<std::string> bodies;
  int b = -1;
  for (std::size_t k = 0; k < mechanism.bodies.size(); ++k) {
    bodies.push_back(mechanism.bodies[k].name);
    if (mechanism.bodies[k].name == body) b = static_cast<int>(k);
  }
  if (dot == std::string::npos) {
    problem = "'" + name + "' names no value: write body.key, e.g. " + bodies.front() + ".x";
    return {};
  }
  if (b < 0) {
    const auto near = nearest_names(body, bodies, 3);
    problem = "unknown body '" + body + "'" +
              (near.empty() ? std::string() : " (did you mean " + joined_names(near) + "?)") +
              (body == "ground" ? ": the ground does not move" : "");
    return {};
  }
  const std::string key = name.substr(dot + 1);
  const int dim = mechanism.dimension;
  std::vector<std::string> keys;
  for (const auto& k : kKeys) {
    if (k.dimension != 0 && k.dimension != dim) continue;
    if (k.component != -2) keys.emplace_back(k.key);
    if (key != k.key) continue;
    if (k.component == -2) {
      problem = "'" + name +
                "' is one component of a quaternion, which cannot be kept alone: "
                "keep the whole orientation, " +
                body + ".orientation";
      return {};
    }
    std::vector<KeptValue> out;
    if (k.component >= 0) {
      out.push_back({b, k.kind, k.component});
    } else {  // every component: 2D angular velocity is about z alone
      const bool about_z = dim == 2 && k.kind == KeptValue::Kind::angular_velocity;
      for (int c = about_z ? 2 : 0; c < (about_z ? 3 : dim); ++c) out.push_back({b, k.kind, c});
    }
    return out;
  }
  const auto near = nearest_names(key, keys, 3);
  problem = "'" + key + "' is no value of body '" + body + "' that can be kept (" +
            (near.empty() ? std::string() : "did you mean " + joined_names(near) + "? ") +
            "expected one of: " + joined_names(keys) + ")";
  return {};
}

}  // namespace condyn
