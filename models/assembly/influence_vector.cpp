// The influence vector r of [ground_motion] (scene-format.md, "Ground motion"; docs/scenes.md,
// "Tabulated time functions and ground motion"): a truss's direction, a matrix model's n x 1
// file, or its DOF names and `*` patterns (the glob of [output] dofs). A key that is a DOF's
// name sets that DOF and wins over every pattern, so `{ "ux*" = 1.0, ux1 = 0.0 }` moves every
// ux but ux1; two patterns may both match a DOF only with the same value (which of two
// different values was meant cannot be told).

#include <string>
#include <vector>

#include "models/assembly/model_builder.hpp"
#include "models/core/nearest_names.hpp"

namespace condyn {

namespace {

/// "the nearest: ..." for a pattern that matches nothing (its `*` left out of the comparison),
/// else the model's first DOFs.
std::string pattern_hint(std::string pattern, const std::vector<std::string>& names) {
  std::erase(pattern, '*');
  if (const auto near = nearest_names(pattern, names); !near.empty()) {
    return "the nearest: " + joined_names(near);
  }
  std::string some = "the model's DOFs: ";
  for (std::size_t d = 0; d < names.size() && d < 6; ++d) some += (d ? ", " : "") + names[d];
  return some + (names.size() > 6 ? ", ..." : "");
}

}  // namespace

Eigen::VectorXd ModelBuilder::influence_vector() const {
  const GroundMotionSpec& g = *spec_.ground_motion;
  const int n = model_.dofs();
  Eigen::VectorXd r = Eigen::VectorXd::Zero(n);
  if (g.direction >= 0) {
    for (int i = g.direction; i < n; i += spec_.model.dimension) r[i] = 1.0;
    return r;
  }
  if (g.influence_file.given()) {
    const auto& f = g.influence_file.matrix;  // its size checked by the reader, as read
    if (f.cols() != 1 || f.rows() != n) {
      fail(g.influence_file.where, g.influence_file.file + " is " + std::to_string(f.rows()) +
                                       " x " + std::to_string(f.cols()) +
                                       ": an influence vector is n x 1 (n = " + std::to_string(n) +
                                       " DOFs)");
    }
    for (Eigen::SparseMatrix<double>::InnerIterator it(f, 0); it; ++it) r[it.row()] = it.value();
    return r;
  }
  // Which entry set each DOF (-1: none) and whether it named the DOF itself.
  std::vector<int> set_by(static_cast<std::size_t>(n), -1);
  std::vector<bool> exact(g.influence.size(), false);
  const auto key = [&](std::size_t k) {
    return SourcePoint{"ground_motion.influence." + g.influence[k].first,
                       line_of(g.influence_lines, k, g.where.line)};
  };
  for (std::size_t k = 0; k < g.influence.size(); ++k) {
    const auto& [name, value] = g.influence[k];
    // A DOF's own name (even one holding a `*`) is that DOF; any other name without `*` is
    // refused as no such DOF.
    if (model_.find_dof(name) || name.find('*') == std::string::npos) {
      const int d = dof(name, key(k));
      r[d] = value;
      set_by[static_cast<std::size_t>(d)] = static_cast<int>(k);
      exact[k] = true;
    }
  }
  for (std::size_t k = 0; k < g.influence.size(); ++k) {
    if (exact[k]) continue;
    const auto& [pattern, value] = g.influence[k];
    bool matched = false;
    for (int d = 0; d < n; ++d) {
      const auto& name = model_.dof_names[static_cast<std::size_t>(d)];
      if (!matches_dof_pattern(pattern, name)) continue;
      matched = true;
      const int other = set_by[static_cast<std::size_t>(d)];
      if (other >= 0 && exact[static_cast<std::size_t>(other)]) continue;  // its name wins
      if (other >= 0 && r[d] != value) {
        fail(key(k), "'" + pattern + "' = " + fmt(value) + " and '" +
                         g.influence[static_cast<std::size_t>(other)].first + "' = " + fmt(r[d]) +
                         " both match DOF '" + name +
                         "': give it by its name, which wins over any pattern");
      }
      r[d] = value;
      set_by[static_cast<std::size_t>(d)] = static_cast<int>(k);
    }
    if (!matched) {
      fail(key(k), "'" + pattern + "' matches no DOF (" + pattern_hint(pattern, model_.dof_names) +
                       "; `*` stands for any run of characters)");
    }
  }
  if ((r.array() == 0.0).all()) {
    fail({"ground_motion.influence", g.where.line},
         "gives every DOF 0: no DOF moves with the ground");
  }
  return r;
}

}  // namespace condyn
