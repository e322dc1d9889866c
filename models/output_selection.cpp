// Which DOFs the output shows ([output] dofs): names, or patterns with `*`.
#include <string>
#include <vector>

#include "models/scene_spec.hpp"

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
  std::vector<int> out;
  for (std::size_t d = 0; d < names.size(); ++d) {
    bool shown = output.dofs.empty();
    for (const auto& pattern : output.dofs) shown = shown || matches_dof_pattern(pattern, names[d]);
    if (shown) out.push_back(static_cast<int>(d));
  }
  return out;
}

}  // namespace condyn
