// Which DOFs the output shows ([output] dofs): names, or patterns with `*`.
#include <algorithm>
#include <string>
#include <string_view>
#include <unordered_set>
#include <vector>

#include "models/scene/scene_spec.hpp"

namespace condyn {

bool matches_dof_pattern(const std::string& pattern, const std::string& name) {
  // Greedy matching with backtracking to the last `*`: linear in practice, never exponential.
  std::size_t p = 0, n = 0, star = std::string::npos, resume = 0;
  while (n < name.size()) {
    if (p < pattern.size() && pattern[p] == '*') {
      star = p++;
      resume = n;
    } else if (p < pattern.size() && pattern[p] == name[n]) {
      ++p;
      ++n;
    } else if (star != std::string::npos) {
      p = star + 1;
      n = ++resume;
    } else {
      return false;
    }
  }
  while (p < pattern.size() && pattern[p] == '*') ++p;
  return p == pattern.size();
}

std::vector<int> selected_dofs(const OutputSpec& output, const std::vector<std::string>& names) {
  if (output.dofs.empty()) {
    std::vector<int> all(names.size());
    for (std::size_t d = 0; d < names.size(); ++d) all[d] = static_cast<int>(d);
    return all;
  }
  // Names by lookup, patterns by matching: matching every entry against every DOF is quadratic,
  // minutes on large models (docs/benchmarks.md).
  std::unordered_set<std::string_view> exact;
  std::vector<const std::string*> patterns;
  for (const auto& entry : output.dofs) {
    if (entry.find('*') == std::string::npos) {
      exact.insert(entry);
    } else {
      patterns.push_back(&entry);
    }
  }
  std::vector<int> out;
  for (std::size_t d = 0; d < names.size(); ++d) {
    const std::string& name = names[d];
    const bool shown = exact.count(name) != 0 ||
                       std::any_of(patterns.begin(), patterns.end(), [&](const std::string* p) {
                         return matches_dof_pattern(*p, name);
                       });
    if (shown) out.push_back(static_cast<int>(d));
  }
  return out;
}

}  // namespace condyn
