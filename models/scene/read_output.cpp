#include "models/scene/scene_readers.hpp"

#include <string>
#include <unordered_map>

namespace condyn {

void SceneReader::read_output(const toml::node& node, OutputSpec& output) const {
  const std::string path = "output";
  const auto& t = table(node, path);
  output.where = at(node, path);
  check_keys(t, path, {"quantities", "file", "dofs", "points"});
  if (const auto* n = t.get("quantities")) {
    output.quantities.clear();
    const auto& arr = array(*n, "output.quantities");
    if (arr.empty()) {
      fail(*n, "output.quantities",
           "is empty: name what to write, or omit the key for displacement and drift");
    }
    for (std::size_t i = 0; i < arr.size(); ++i) {
      const std::string p = index("output.quantities", i);
      const std::string s = string(*arr.get(i), p);
      bool found = false;
      for (Quantity q : {Quantity::displacement, Quantity::velocity, Quantity::acceleration,
                         Quantity::absolute_acceleration, Quantity::reaction, Quantity::multiplier,
                         Quantity::drift, Quantity::energy}) {
        if (s == to_string(q)) {
          for (Quantity seen : output.quantities) {
            if (seen == q) fail(*arr.get(i), p, "'" + s + "' is listed twice");
          }
          output.quantities.push_back(q);
          output.quantities_lines.push_back(at(*arr.get(i), p).line);
          found = true;
        }
      }
      if (!found) {
        fail(*arr.get(i), p,
             "unknown quantity '" + s +
                 "' (expected displacement, velocity, acceleration, absolute_acceleration, "
                 "reaction, multiplier, drift or energy)");
      }
    }
  }
  if (const auto* n = t.get("dofs")) {
    const auto& arr = array(*n, "output.dofs");
    if (arr.empty()) fail(*n, "output.dofs", "is empty: omit the key for every DOF");
    std::unordered_map<std::string, std::size_t> first;  // a column written twice
    for (std::size_t i = 0; i < arr.size(); ++i) {
      const std::string p = index("output.dofs", i);
      const std::string s = string(*arr.get(i), p);
      if (s.empty()) fail(*arr.get(i), p, "must not be empty");
      if (const auto [at, added] = first.emplace(s, i); !added) {
        fail(*arr.get(i), p,
             "'" + s + "' is listed twice (also as " + index("output.dofs", at->second) + ")");
      }
      output.dofs.push_back(s);
      output.dofs_lines.push_back(static_cast<int>(arr.get(i)->source().begin.line));
    }
  }
  if (const auto* n = t.get("points")) {  // checked against the bodies: read_mechanism_names.cpp
    const auto& arr = array(*n, "output.points");
    if (arr.empty()) fail(*n, "output.points", "is empty: omit the key for no point columns");
    for (std::size_t i = 0; i < arr.size(); ++i) {
      output.points.push_back(string(*arr.get(i), index("output.points", i)));
      output.points_lines.push_back(at(*arr.get(i), index("output.points", i)).line);
    }
  }
  if (const auto* n = t.get("file")) {
    output.file = string(*n, "output.file");
    output.file_line = at(*n, "output.file").line;
    if (output.file.empty()) fail(*n, "output.file", "must not be empty");
  }
}

}  // namespace condyn
