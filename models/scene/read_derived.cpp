// [[derived]] tables (docs/scenes.md, "Derived columns"): each a name and its terms. Read here
// with what the text alone decides (a CSV-safe name, given once; a non-empty table of finite
// coefficients; a term on another derived column only on one above it); which column each term
// names is resolved against the built model by models/assembly/derived_columns.cpp.

#include <cmath>
#include <cstdint>
#include <optional>
#include <unordered_map>

#include "models/scene/scene_readers.hpp"

namespace condyn {

void SceneReader::read_derived(const toml::node& node, std::vector<DerivedSpec>& out) const {
  const auto& arr = array(node, "derived");
  if (arr.empty()) fail(node, "derived", "is empty: give [[derived]] tables or omit them");
  std::unordered_map<std::string, std::size_t> first;  // each name's entry
  // Each name's first entry as written, to tell a term on a later derived column (below).
  std::unordered_map<std::string, std::size_t> entry_of;
  for (std::size_t j = 0; j < arr.size(); ++j) {
    const auto* t = arr.get(j)->as_table();
    const auto* name = t != nullptr ? t->get("name") : nullptr;
    if (const auto text = name != nullptr ? name->value<std::string>() : std::nullopt) {
      entry_of.emplace(*text, j);
    }
  }
  for (std::size_t i = 0; i < arr.size(); ++i) {
    const std::string path = index("derived", i);
    const auto& t = table(*arr.get(i), path);
    check_keys(t, path, {"name", "terms"});
    DerivedSpec d;
    const toml::node& name_node = required(t, path, "name");
    d.where = at(name_node, path);  // the name's line: the builder's refusals name the entry
    d.name = string(name_node, join(path, "name"));
    if (d.name.empty()) fail(name_node, join(path, "name"), "must not be empty");
    check_name(name_node, join(path, "name"), d.name, "derived column");
    if (const auto [seen, added] = first.emplace(d.name, i); !added) {
      fail(name_node, join(path, "name"),
           "derived column '" + d.name + "' is defined twice (also by " +
               index("derived", seen->second) + ")");
    }
    const std::string who = "derived column '" + d.name + "'";
    const std::string terms_path = join(path, "terms");
    const toml::node& terms_node = required(t, path, "terms");
    if (!terms_node.is_table()) {
      fail(terms_node, terms_path,
           who +
               ": expected a table of columns and coefficients, as terms = { u2 = 1.0, "
               "u1 = -1.0 }");
    }
    const auto& terms = *terms_node.as_table();
    if (terms.empty()) fail(terms_node, terms_path, who + ": has no terms");
    for (const auto& [key, value] : terms) {
      const std::string column(key.str());
      const std::string term_path = join(terms_path, column);
      if (!value.is_number()) fail(value, term_path, who + ": expected a number (the coefficient)");
      const double c = value.is_integer() ? static_cast<double>(*value.value<std::int64_t>())
                                          : *value.value<double>();
      if (!std::isfinite(c)) {
        fail(value, term_path, who + ": the coefficient " + fmt(c) + " is not finite");
      }
      // A name further down is a later column: only those above are known by then, and the
      // order rules out cycles.
      if (const auto later = entry_of.find(column); later != entry_of.end() && later->second > i) {
        fail(value, term_path,
             who + ": names derived column '" + column + "' of " + index("derived", later->second) +
                 ", which comes after it: a derived column may use only those above it");
      }
      d.terms.push_back({column, c + 0.0, static_cast<int>(value.source().begin.line)});
    }
    out.push_back(std::move(d));
  }
}

}  // namespace condyn
