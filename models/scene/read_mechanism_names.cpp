// The keys outside [model] that name parts of a mechanism: [initial] keep (values the projection
// keeps) and [output] points (markers whose positions get columns), checked against the bodies;
// and the [initial] keys a mechanism takes from its [[body]] tables instead.

#include <string>
#include <unordered_map>

#include "models/core/mechanism_keep.hpp"
#include "models/core/nearest_names.hpp"
#include "models/scene/scene_readers.hpp"

namespace condyn {

namespace {

/// The node of the k-th entry of `section`.`key` (an array the section readers accepted).
const toml::node& entry(const toml::table& root, const char* section, const char* key,
                        std::size_t k) {
  return *root.get_as<toml::table>(section)->get_as<toml::array>(key)->get(k);
}

}  // namespace

void SceneReader::check_mechanism_names(const toml::table& root, const SceneSpec& spec) const {
  const auto* initial = root.get_as<toml::table>("initial");
  const auto* output = root.get_as<toml::table>("output");
  if (!spec.model.mechanism) {
    if (initial != nullptr && initial->contains("keep")) {
      fail(*initial->get("keep"), "initial.keep",
           "names values of a mechanism's bodies ([model] type = \"multibody\"); other models "
           "keep the values given in [initial] displacement and velocity");
    }
    if (output != nullptr && output->contains("points")) {
      fail(*output->get("points"), "output.points",
           "names points of a mechanism's bodies ([model] type = \"multibody\")");
    }
    return;
  }
  const Mechanism& m = *spec.model.mechanism;
  if (initial != nullptr) {
    for (const char* key : {"displacement", "velocity", "static"}) {
      if (const auto* n = initial->get(key)) {
        fail(*n, join("initial", key),
             "a mechanism's initial poses and velocities are its [[body]] tables' position, "
             "angle or orientation, velocity and angular_velocity");
      }
    }
    if (!spec.initial.keep.empty() && !spec.initial.project) {
      fail(*initial->get("keep"), "initial.keep",
           "keeps values while [initial] project = true moves the others: set project = true");
    }
  }
  std::unordered_map<std::string, std::size_t> seen;
  for (std::size_t k = 0; k < spec.initial.keep.size(); ++k) {
    const auto& name = spec.initial.keep[k];
    const toml::node& node = entry(root, "initial", "keep", k);
    std::string problem;
    if (kept_values(m, name, problem).empty()) fail(node, index("initial.keep", k), problem);
    if (const auto [at, fresh] = seen.emplace(name, k); !fresh) {
      fail(node, index("initial.keep", k),
           "'" + name + "' is listed twice (also as " + index("initial.keep", at->second) + ")");
    }
  }
  seen.clear();
  for (std::size_t k = 0; k < spec.output.points.size(); ++k) {
    const auto& name = spec.output.points[k];
    const toml::node& node = entry(root, "output", "points", k);
    const std::string p = index("output.points", k);
    const auto dot = name.find('.');
    if (dot == std::string::npos) fail(node, p, "'" + name + "' is not body.point (e.g. crank.B)");
    // Resolved as a joint's body and point are, with the same suggestions.
    const std::string body = name.substr(0, dot), point = name.substr(dot + 1);
    const int b = body_index(m, node, p, &body);
    if (b == Mechanism::kGround) fail(node, p, "the ground's points do not move");
    (void)marker_index(m, b, false, node, p, &point);
    if (const auto [at, fresh] = seen.emplace(name, k); !fresh) {
      fail(node, p,
           "'" + name + "' is listed twice (also as " + index("output.points", at->second) + ")");
    }
  }
}

}  // namespace condyn
