// Checks of the [solve] and [output] settings against the built model: output rows, energy,
// slaves.

#include <Eigen/Dense>
#include <algorithm>
#include <string>
#include <vector>

#include "models/assembly/model_builder.hpp"
#include "models/core/linear_system.hpp"
#include "models/core/master_slave.hpp"
#include "models/core/nearest_names.hpp"
#include "models/core/singular_values.hpp"

namespace condyn {

namespace {

// Refuse horizons that would write more rows than this (about 1 GB of CSV for a small model).
constexpr double kMaxOutputRows = 1e7;

}  // namespace

/// `[output] quantities` entry of `q` (asked for by the scene), at its line where known.
SourcePoint ModelBuilder::quantity_key(Quantity q) const {
  const auto& quantities = spec_.output.quantities;
  const auto k = static_cast<std::size_t>(std::find(quantities.begin(), quantities.end(), q) -
                                          quantities.begin());
  return {"output.quantities", line_of(spec_.output.quantities_lines, k, spec_.output.where.line)};
}

/// [output] energy needs a conservative system (else the energy is not a first integral).
void ModelBuilder::check_energy_output() const {
  const auto& q = spec_.output.quantities;
  if (std::find(q.begin(), q.end(), Quantity::energy) == q.end()) return;
  if (!evaluator()->energy_parts(0.0, model_.u0, model_.v0)) {
    fail(quantity_key(Quantity::energy),
         "'energy' (the energy balance, docs/energy.md) needs forces that split into "
         "potential, dissipated and applied parts, and this model's do not");
  }
}

void ModelBuilder::check_absolute_acceleration() const {
  const auto& q = spec_.output.quantities;
  if (std::find(q.begin(), q.end(), Quantity::absolute_acceleration) == q.end()) return;
  if (model_.outputs) {
    fail(quantity_key(Quantity::absolute_acceleration),
         "'absolute_acceleration' is not written for a mechanism: its accelerations (crank.ax, "
         "crank.alpha) are absolute (use 'acceleration')");
  }
  if (!model_.ground) {
    fail(quantity_key(Quantity::absolute_acceleration),
         "'absolute_acceleration' needs [ground_motion]: without a moving ground the "
         "accelerations are absolute already (use 'acceleration')");
  }
}

void ModelBuilder::check_output() const {
  const auto rows = static_cast<double>(spec_.solve.output_count());
  if (rows > kMaxOutputRows) {
    fail({"solve.output_step",
          spec_.solve.output_step_line > 0 ? spec_.solve.output_step_line : spec_.solve.where.line},
         "would write " + fmt(rows) + " rows (limit " + fmt(kMaxOutputRows) +
             "): increase output_step");
  }
  check_output_dofs();
  check_output_points();
  check_absolute_acceleration();
  check_slaves();
}

namespace {

/// The column names [output] dofs selects among: the DOFs, or a mechanism's mapped columns of
/// displacement, velocity, acceleration and reaction (src/output/output_columns.hpp).
std::vector<std::string> selectable_names(const Model& model) {
  if (!model.outputs) return model.dof_names;
  std::vector<std::string> out;
  for (Quantity q :
       {Quantity::displacement, Quantity::velocity, Quantity::acceleration, Quantity::reaction}) {
    const auto& names = model.outputs->names(q);
    out.insert(out.end(), names.begin(), names.end());
  }
  return out;
}

}  // namespace

/// [output] dofs: every name or pattern selects some DOF, or some column of a mechanism (a typo
/// would silently drop columns).
void ModelBuilder::check_output_dofs() const {
  const auto& patterns = spec_.output.dofs;
  if (patterns.empty()) return;
  const std::vector<std::string> names = selectable_names(model_);
  const char* what = model_.outputs ? "column" : "DOF";
  for (std::size_t k = 0; k < patterns.size(); ++k) {
    const bool any = patterns[k].find('*') == std::string::npos && !model_.outputs
                         ? model_.find_dof(patterns[k]).has_value()
                         : std::any_of(names.begin(), names.end(), [&](const std::string& name) {
                             return matches_dof_pattern(patterns[k], name);
                           });
    if (any) continue;
    // The names a typo most likely meant (a pattern's `*` left out of the comparison), else the
    // model's first DOFs (columns), said to be that.
    std::string pattern = patterns[k];
    std::erase(pattern, '*');
    const std::vector<std::string> near = nearest_names(pattern, names);
    std::string some;
    if (!near.empty()) {
      some = "the nearest: " + joined_names(near);
    } else {
      some = std::string("the model's ") + what + "s: ";
      for (std::size_t d = 0; d < names.size() && d < 6; ++d) some += (d ? ", " : "") + names[d];
      if (names.size() > 6) some += ", ...";
    }
    const auto& lines = spec_.output.dofs_lines;
    const int line = k < lines.size() && lines[k] > 0 ? lines[k] : spec_.output.where.line;
    fail({"output.dofs[" + std::to_string(k + 1) + "]", line},
         "'" + patterns[k] + "' matches no " + what + " (" + some +
             "; `*` stands for any run of characters)");
  }
}

/// [output] points: a mechanism's named markers, "body.point", each known to its output map.
void ModelBuilder::check_output_points() const {
  const auto& points = spec_.output.points;
  const auto& lines = spec_.output.points_lines;
  for (std::size_t k = 0; k < points.size(); ++k) {
    const int line = k < lines.size() && lines[k] > 0 ? lines[k] : spec_.output.where.line;
    const SourcePoint key{"output.points[" + std::to_string(k + 1) + "]", line};
    if (!model_.outputs) {
      fail(key,
           "names a point of a mechanism, but this model has none ([model] type = "
           "\"multibody\" has bodies with named points)");
    }
    if (model_.outputs->point(points[k])) continue;
    fail(key, "'" + points[k] +
                  "' is no body's point (write \"body.point\", with a point that the body's "
                  "`points` table names)");
  }
}

/// [solve] slaves: one distinct DOF per constraint, each in some constraint (the elimination
/// solves the constraints for them).
void ModelBuilder::check_slaves() const {
  const auto& slaves = spec_.solve.slaves;
  if (slaves.empty()) return;
  const int line = line_of(spec_.solve.slaves_lines, 0, spec_.solve.where.line);  // the key's
  const auto key = [&](std::size_t k) {
    return SourcePoint{"solve.slaves[" + std::to_string(k + 1) + "]",
                       line_of(spec_.solve.slaves_lines, k, spec_.solve.where.line)};
  };
  std::vector<int> touched(static_cast<std::size_t>(model_.dofs()), 0);
  for (int k = 0; k < model_.A.outerSize(); ++k) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(model_.A, k); it; ++it) {
      if (it.value() != 0.0) touched[static_cast<std::size_t>(it.col())] = 1;
    }
  }
  for (std::size_t k = 0; k < slaves.size(); ++k) {
    const int d = dof(slaves[k], key(k));
    for (std::size_t j = 0; j < k; ++j) {
      if (slaves[j] == slaves[k]) {
        fail(key(k), "'" + slaves[k] + "' is named twice (also as solve.slaves[" +
                         std::to_string(j + 1) +
                         "]): each slave is solved from its own constraint");
      }
    }
    if (!touched[static_cast<std::size_t>(d)]) {
      fail(key(k), "'" + slaves[k] +
                       "' appears in no constraint: a slave is a DOF the constraints determine");
    }
  }
  const int m = model_.constraint_count();
  if (static_cast<int>(slaves.size()) != m) {
    fail({"solve.slaves", line},
         "names " + std::to_string(slaves.size()) + " slave" + (slaves.size() == 1 ? "" : "s") +
             " but the scene has " + std::to_string(m) + " constraint" + (m == 1 ? "" : "s") +
             (report_.dropped_constraints.empty() ? "" : " after dropping the redundant ones") +
             ": name exactly one slave per constraint");
  }
  // The elimination solves A_S u_S = g − A_R u_R: the slaves' columns must be well conditioned
  // (the elimination's own limit, 1e12). Dense SVD of m x m; skipped beyond the dense limit.
  if (model_.is_nonlinear() || static_cast<double>(m) * m > kMaxDenseEntries) return;
  // The slaves' columns only: A itself is m x n, and n may be 10⁶.
  Eigen::MatrixXd a_s = Eigen::MatrixXd::Zero(m, m);
  std::string names;
  for (int k = 0; k < m; ++k) {
    const int column = model_.dof_at(slaves[static_cast<std::size_t>(k)]);
    for (Eigen::SparseMatrix<double>::InnerIterator it(model_.A, column); it; ++it)
      a_s(it.row(), k) = it.value();
    names += (k ? ", " : "") + slaves[static_cast<std::size_t>(k)];
  }
  const Eigen::VectorXd sv = singular_values(a_s);
  const double smax = sv(0), smin = sv(m - 1);
  if (!(smin > smax / kMaxSlaveCondition)) {
    fail({"solve.slaves", line}, "the slaves " + names +
                                     " do not determine the constraints (condition number of their "
                                     "columns of the constraint matrix " +
                                     (smin > 0.0 ? fmt(smax / smin) : std::string("infinite")) +
                                     ", limit " + fmt(kMaxSlaveCondition) +
                                     "): choose slaves that the constraints fix independently");
  }
}

}  // namespace condyn
