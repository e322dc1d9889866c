#include "models/scene_readers.hpp"

#include <string>
#include <utility>
#include <vector>

namespace condyn {

TimeTerm SceneReader::term(const toml::node& node, const std::string& path) const {
  const auto& t = table(node, path);
  const std::string type = string(required(t, path, "type"), join(path, "type"));
  TimeTerm term;
  auto opt = [&](std::string_view key, double dflt) {
    const auto* n = t.get(key);
    return n ? number(*n, join(path, std::string(key))) : dflt;
  };
  if (type == "step") {
    check_keys(t, path, {"type", "amplitude", "start"});
    term.kind = TimeTerm::Kind::step;
    term.amplitude = opt("amplitude", 1.0);
    term.start = opt("start", 0.0);
  } else if (type == "polynomial") {
    check_keys(t, path, {"type", "coefficients"});
    term.kind = TimeTerm::Kind::polynomial;
    term.coefficients = numbers(required(t, path, "coefficients"), join(path, "coefficients"));
    if (term.coefficients.empty()) fail(node, join(path, "coefficients"), "must not be empty");
  } else if (type == "harmonic") {
    check_keys(t, path, {"type", "amplitude", "omega", "phase"});
    term.kind = TimeTerm::Kind::harmonic;
    term.amplitude = opt("amplitude", 1.0);
    term.omega = number(required(t, path, "omega"), join(path, "omega"));
    term.phase = opt("phase", 0.0);
  } else if (type == "exponential") {
    check_keys(t, path, {"type", "amplitude", "rate"});
    term.kind = TimeTerm::Kind::exponential;
    term.amplitude = opt("amplitude", 1.0);
    term.rate = number(required(t, path, "rate"), join(path, "rate"));
  } else {
    fail(*t.get("type"), join(path, "type"),
         "unknown time function '" + type +
             "' (expected step, polynomial, harmonic or exponential)");
  }
  return term;
}

TimeFunction SceneReader::time_function(const toml::node& node, const std::string& path) const {
  if (node.is_number()) return TimeFunction::constant(number(node, path));
  if (node.is_table()) return TimeFunction({term(node, path)});
  if (const auto* arr = node.as_array()) {
    std::vector<TimeTerm> terms;
    for (std::size_t i = 0; i < arr->size(); ++i)
      terms.push_back(term(*arr->get(i), index(path, i)));
    if (terms.empty()) fail(node, path, "an empty list is not a time function (write 0)");
    return TimeFunction(std::move(terms));
  }
  fail(node, path, "expected a number, a time-function table or a list of them");
}

}  // namespace condyn
