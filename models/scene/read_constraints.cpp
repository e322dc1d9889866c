#include "models/scene/scene_readers.hpp"

#include <map>
#include <string>
#include <utility>
#include <vector>

namespace condyn {

void SceneReader::read_constraints(const toml::node& node, std::vector<ConstraintSpec>& out) const {
  const auto& cons = array(node, "constraint");
  std::map<std::string, std::pair<std::size_t, bool>> names;  // name: index, whether given
  for (std::size_t i = 0; i < cons.size(); ++i) {
    const std::string p = index("constraint", i);
    const auto& t = table(*cons.get(i), p);
    check_keys(t, p, {"name", "terms", "level", "value"});
    ConstraintSpec c;
    c.where = at(*cons.get(i), p);
    c.name = "c" + std::to_string(i + 1);
    if (const auto* nm = t.get("name")) {
      c.name = string(*nm, join(p, "name"));
      if (c.name.empty()) fail(*nm, join(p, "name"), "must not be empty");
      check_name(*nm, join(p, "name"), c.name, "constraint");
    }
    const bool given = t.contains("name");
    if (const auto [first, fresh] = names.try_emplace(c.name, i, given); !fresh) {
      const auto [j, first_given] = first->second;
      const auto by_default = [&](std::size_t k, bool named) {
        return named ? std::string()
                     : " (the default name of unnamed " + index("constraint", k) + ")";
      };
      fail(*cons.get(i), p,
           "duplicate constraint name '" + c.name + "'" + by_default(i, given) + ": " +
               index("constraint", j) + " is named so too" + by_default(j, first_given) +
               "; give the constraints distinct names");
    }
    const auto& terms_node = required(t, p, "terms");
    c.terms = dof_values(terms_node, join(p, "terms"), &c.term_lines);
    if (c.terms.empty()) fail(terms_node, join(p, "terms"), "a constraint needs at least one term");
    if (const auto* lv = t.get("level")) {
      const std::string s = string(*lv, join(p, "level"));
      if (s == "position") {
        c.level = ConstraintSpec::Level::position;
      } else if (s == "velocity") {
        c.level = ConstraintSpec::Level::velocity;
      } else {
        fail(*lv, join(p, "level"), "expected 'position' or 'velocity'");
      }
    }
    if (const auto* v = t.get("value")) c.value = time_function(*v, join(p, "value"));
    out.push_back(std::move(c));
  }
}

}  // namespace condyn
