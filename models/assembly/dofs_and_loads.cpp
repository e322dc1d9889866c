// DOF names and their lookup, refusals naming the scene's key, and the scene's loads.

#include <cmath>

#include "models/assembly/model_builder.hpp"
#include "models/core/nearest_names.hpp"
#include "models/scene/scene_parser.hpp"

namespace condyn {

void ModelBuilder::fail(const SourcePoint& where, const std::string& problem) const {
  throw SceneError(scene_message(spec_.file, where, problem));
}

int ModelBuilder::dof(const std::string& name, const SourcePoint& where) const {
  const auto index = model_.find_dof(name);
  if (!index) {
    // The names a typo most likely meant; a small model's every DOF when none is near.
    std::string hint;
    if (const auto near = nearest_names(name, model_.dof_names); !near.empty()) {
      hint = " (the nearest: " + joined_names(near) + ")";
    } else if (model_.dofs() <= 12) {
      hint = " (DOFs are: " + joined_names(model_.dof_names) + ")";
    }
    fail(where, "no such DOF '" + name + "'" + hint);
  }
  return *index;
}

void ModelBuilder::set_dofs(std::vector<std::string> names) {
  model_.dof_names = std::move(names);
  model_.index_dofs();
}

void ModelBuilder::build_loads() {
  // Gravity loads come first; several loads on one DOF add up, and so must stay finite.
  std::vector<double> total(static_cast<std::size_t>(model_.dofs()), 0.0);
  for (const auto& l : model_.loads) {
    total[static_cast<std::size_t>(l.dof)] += magnitude_bound(l.value, spec_.solve.t_end);
  }
  for (const auto& l : spec_.loads) {
    const SourcePoint value_at{l.where.path + ".value", l.where.line};
    check_time_function(l.value, value_at);
    const TimeFunction value = acting_in_run(l.value, value_at);
    const double bound = magnitude_bound(value, spec_.solve.t_end);
    if (l.pattern.given()) {
      add_pattern_load(l, value, bound, total);
      continue;
    }
    const int d = dof(l.dof, {l.where.path + ".dof", l.where.line});
    auto& sum = total[static_cast<std::size_t>(d)];
    sum += bound;
    if (!std::isfinite(sum)) {
      fail(value_at,
           "the loads on DOF '" + l.dof + "' add up to more than the double range (about 1.8e308)");
    }
    model_.loads.push_back(Load{d, value, {}});
  }
  add_ground_motion(total);
}

/// pattern = { file = "f.mtx" }: one Load holding the pattern as a sparse vector.
void ModelBuilder::add_pattern_load(const LoadSpec& l, const TimeFunction& value, double bound,
                                    std::vector<double>& total) {
  const auto& p = l.pattern.matrix;
  if (p.cols() != 1 || p.rows() != model_.dofs()) {
    fail(l.pattern.where,
         l.pattern.file + " is " + std::to_string(p.rows()) + " x " + std::to_string(p.cols()) +
             ": a load pattern is n x 1 (n = " + std::to_string(model_.dofs()) + " DOFs)");
  }
  Load load{-1, value, Eigen::SparseVector<double>(p.rows())};
  for (Eigen::SparseMatrix<double>::InnerIterator it(p, 0); it; ++it) {
    if (it.value() == 0.0) continue;
    const auto d = static_cast<int>(it.row());
    auto& sum = total[static_cast<std::size_t>(d)];
    sum += std::abs(it.value()) * bound;
    if (!std::isfinite(sum)) {
      fail({l.where.path + ".value", l.where.line},
           "the loads on DOF '" + model_.dof_names[static_cast<std::size_t>(d)] +
               "' add up to more than the double range (about 1.8e308)");
    }
    load.pattern.insertBack(d) = it.value();
  }
  if (load.pattern.nonZeros() > 0) {
    model_.loads.push_back(std::move(load));
  } else {
    // Most likely an export that lost its values: said, since the run would go on unloaded.
    // A pattern handed over in memory (Python) is named by its own key.
    report_.warnings.push_back((l.pattern.in_memory()
                                    ? l.where.path + ".pattern: the array"
                                    : l.pattern.where.path + ": " + l.pattern.file) +
                               " has no nonzero entry: this load applies no force");
  }
}

}  // namespace condyn
