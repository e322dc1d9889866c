// [model] type = "multibody" (docs/scenes.md, "Mechanisms of rigid bodies"): the model table's
// keys, the [[body]], [[joint]] and [[force]] sections in that order (each refers to the ones
// before it), the sections a mechanism has no use for, and the helpers the three readers share.

#include <cmath>
#include <string>
#include <vector>

#include "models/core/nearest_names.hpp"
#include "models/scene/scene_readers.hpp"

namespace condyn {

namespace {

/// The name the ground goes by in [[joint]] and [[force]] bodies.
constexpr std::string_view kGroundName = "ground";

}  // namespace

Mechanism::Vec3 SceneReader::mechanism_vector(const toml::node& node, const std::string& path,
                                              int dim) const {
  const auto v = numbers(node, path);
  if (static_cast<int>(v.size()) != dim) {
    fail(node, path,
         "has " + std::to_string(v.size()) + " components; a vector of a " + std::to_string(dim) +
             "D mechanism (dimension = " + std::to_string(dim) + ") has " + std::to_string(dim));
  }
  return {v[0], v[1], dim == 3 ? v[2] : 0.0};
}

std::string SceneReader::mechanism_name(const toml::node& node, const std::string& path,
                                        const char* what) const {
  std::string name = string(node, path);
  if (name.empty()) fail(node, path, std::string("a ") + what + " name must not be empty");
  check_name(node, path, name, what);
  if (name.find('.') != std::string::npos) {
    fail(node, path,
         std::string("the ") + what + " name '" + name +
             "' holds a '.', which joins the names of output columns (crank.B.x): use '_'");
  }
  return name;
}

std::vector<Mechanism::Marker> SceneReader::read_markers(const toml::node& node,
                                                         const std::string& path, int dim,
                                                         bool axes) const {
  std::vector<Mechanism::Marker> out;
  for (const auto& [key, value] : table(node, path)) {
    const std::string p = join(path, std::string(key.str()));
    Mechanism::Marker m;
    m.name = std::string(key.str());
    if (m.name.empty()) fail(value, p, "a marker name must not be empty");
    if (m.name.find('.') != std::string::npos) {
      fail(value, p,
           "the name '" + m.name +
               "' holds a '.', which joins the names of output columns: "
               "use '_'");
    }
    m.at = mechanism_vector(value, p, dim);
    if (axes) {
      const double norm = std::hypot(m.at[0], m.at[1], m.at[2]);
      // Negated: a NaN norm (entries overflowing when squared are finite) is refused too.
      if (!(norm > 0.0) || !std::isfinite(norm)) {
        fail(value, p, "an axis needs a nonzero direction (its length is " + fmt(norm) + ")");
      }
      for (double& c : m.at) c /= norm;  // a direction: any nonzero length, normalized
    }
    out.push_back(m);
  }
  return out;
}

int SceneReader::find_body(const Mechanism& mechanism, const std::string& name) const {
  // Built again when the bodies are not those it holds (they are read once, before any lookup).
  if (body_at_of_ != &mechanism || body_at_.size() != mechanism.bodies.size()) {
    body_at_.clear();
    for (std::size_t b = 0; b < mechanism.bodies.size(); ++b)
      body_at_.emplace(mechanism.bodies[b].name, static_cast<int>(b));
    body_at_of_ = &mechanism;
  }
  const auto at = body_at_.find(name);
  return at == body_at_.end() ? -1 : at->second;
}

int SceneReader::body_index(const Mechanism& mechanism, const toml::node& node,
                            const std::string& path, const std::string* given) const {
  const std::string name = given != nullptr ? *given : string(node, path);
  if (name == kGroundName) return Mechanism::kGround;
  if (const int b = find_body(mechanism, name); b >= 0) return b;
  std::vector<std::string> names{std::string(kGroundName)};
  for (const auto& body : mechanism.bodies) names.push_back(body.name);
  const auto near = nearest_names(name, names, 3);
  fail(node, path,
       "unknown body '" + name + "' (" +
           (near.empty() ? std::string() : "did you mean " + joined_names(near) + "? ") +
           "the bodies are the ground and the [[body]] tables written above)");
}

int SceneReader::marker_index(const Mechanism& mechanism, int body, bool axis,
                              const toml::node& node, const std::string& path,
                              const std::string* given) const {
  const std::string name = given != nullptr ? *given : string(node, path);
  const bool ground = body == Mechanism::kGround;
  const auto& markers = ground ? (axis ? mechanism.ground_axes : mechanism.ground_points)
                               : (axis ? mechanism.bodies[static_cast<std::size_t>(body)].axes
                                       : mechanism.bodies[static_cast<std::size_t>(body)].points);
  std::vector<std::string> names;
  for (std::size_t k = 0; k < markers.size(); ++k) {
    if (markers[k].name == name) return static_cast<int>(k);
    names.push_back(markers[k].name);
  }
  const std::string owner =
      ground ? "the ground"
             : "body '" + mechanism.bodies[static_cast<std::size_t>(body)].name + "'";
  const std::string where =
      ground ? (axis ? "model.ground_axes" : "model.ground") : (axis ? "its axes" : "its points");
  const auto near = nearest_names(name, names, 3);
  fail(node, path,
       std::string(axis ? "unknown axis '" : "unknown point '") + name + "' of " + owner + " (" +
           (near.empty() ? std::string() : "did you mean " + joined_names(near) + "? ") +
           (names.empty() ? where + " name none" : "known: " + joined_names(names)) + ")");
}

void SceneReader::read_mechanism_model(const toml::table& t, ModelSpec& model) const {
  const std::string path = "model";
  check_keys(t, path, {"type", "dimension", "gravity", "ground", "ground_axes"});
  model.type = ModelSpec::Type::multibody;
  Mechanism m;
  m.where = model.where;
  if (const auto* d = t.get("dimension")) {
    const long dim = integer(*d, "model.dimension");
    if (dim != 2 && dim != 3) {
      fail(*d, "model.dimension", "must be 2 (planar) or 3 (spatial), not " + std::to_string(dim));
    }
    m.dimension = static_cast<int>(dim);
  }
  model.dimension = m.dimension;
  if (const auto* g = t.get("gravity"))
    m.gravity = mechanism_vector(*g, "model.gravity", m.dimension);
  if (const auto* g = t.get("ground")) {
    m.ground_points = read_markers(*g, "model.ground", m.dimension, false);
  }
  if (const auto* g = t.get("ground_axes")) {
    m.ground_axes = read_markers(*g, "model.ground_axes", m.dimension, true);
  }
  model.mechanism = std::move(m);
}

void SceneReader::read_mechanism_sections(const toml::table& root, ModelSpec& model) const {
  const char* sections[] = {"body", "joint", "force"};
  if (!model.mechanism) {
    for (const char* s : sections) {
      if (const auto* n = root.get(s)) {
        fail(*n, s,
             std::string("[[") + s +
                 "]] belongs to a mechanism: it needs [model] type = "
                 "\"multibody\"");
      }
    }
    return;
  }
  // What a mechanism takes from its own tables: loads as [[force]], rows as [[joint]], the start
  // from [[body]]; a key of another model silently ignored would be a model not run.
  for (const auto& [key, why] :
       {std::pair<const char*, const char*>{"load",
                                            "apply forces with [[force]] point_force or torque"},
        {"constraint", "connect bodies with [[joint]]"},
        {"constraint_block", "connect bodies with [[joint]]"},
        {"ground_motion", "a mechanism has no ground motion yet: drive a joint instead"}}) {
    if (const auto* n = root.get(key)) {
      fail(*n, key, std::string("not part of a multibody model: ") + why);
    }
  }
  Mechanism& m = *model.mechanism;
  const auto* bodies = root.get("body");
  if (bodies == nullptr) {
    fail(*root.get("model"), "model", "a multibody model needs at least one [[body]]");
  }
  read_bodies(*bodies, m);
  if (const auto* n = root.get("joint")) read_joints(*n, m);
  if (const auto* n = root.get("force")) read_forces(*n, m);
}

}  // namespace condyn
