#pragma once
/// "Did you mean": the known names nearest to a name that is not known. One measure for every
/// refusal that suggests names (a check's column, a DOF in a scene key, an [output] dofs entry,
/// an unknown key), so that each suggests what a typo most likely meant, or nothing.

#include <cstddef>
#include <string>
#include <vector>

namespace condyn {

/// The edit distance between `a` and `b` with case ignored: insertions, deletions, substitutions
/// and swaps of two adjacent characters, each counting 1 (optimal string alignment), over bytes.
[[nodiscard]] std::size_t name_distance(const std::string& a, const std::string& b);

/// Up to `most` of `candidates` nearest to `name`, in the candidates' order: of the names near
/// it, those at the smallest distance. Near are the names within name_distance max(1, |name| /
/// 3) that keep a character of either name (a typo or two: `uz3` → `ux3`, `uy3`; `vel_y` →
/// `vel_x`; `tpi` → `tip`; not `q` → `a`), and, ranked as the farthest such typo, the names that
/// contain `name` or that `name` contains, the shorter of the two of 3 characters or more
/// (`drift_pos` → `drift_position`, `displacement_uy3` → `uy3`). Empty when none is near: a list
/// of unrelated names helps nobody.
[[nodiscard]] std::vector<std::string> nearest_names(const std::string& name,
                                                     const std::vector<std::string>& candidates,
                                                     std::size_t most = 5);

/// "a, b, c": the names joined for a message.
[[nodiscard]] std::string joined_names(const std::vector<std::string>& names);

}  // namespace condyn
