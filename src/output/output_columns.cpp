// The columns of a run's result file (src/output/output_columns.hpp).

#include "src/output/output_columns.hpp"

#include <algorithm>
#include <stdexcept>

namespace condyn {

namespace {

/// The CSV prefix of a per-DOF quantity's column without a map.
const char* dof_prefix(Quantity q) {
  switch (q) {
    case Quantity::velocity:
      return "vel_";
    case Quantity::acceleration:
      return "acc_";
    case Quantity::absolute_acceleration:
      return "acc_abs_";
    case Quantity::reaction:
      return "reaction_";
    default:
      return "";
  }
}

/// True for the quantities with a column per DOF (per map column for a mapped model).
bool has_dof_columns(Quantity q) {
  switch (q) {
    case Quantity::displacement:
    case Quantity::velocity:
    case Quantity::acceleration:
    case Quantity::absolute_acceleration:
    case Quantity::reaction:
      return true;
    case Quantity::multiplier:
    case Quantity::drift:
    case Quantity::energy:
      return false;
  }
  return false;
}

}  // namespace

OutputColumns::OutputColumns(const Model& model, const OutputSpec& output)
    : model_(model), map_(model.outputs.get()) {
  // A derived column on reactions or accelerations is as unreliable near a singular
  // configuration as they are: it brings the flag too.
  const std::vector<Quantity> read = with_derived_quantities(output.quantities, model.derived);
  const auto shows = [&read](Quantity q) {
    return std::find(read.begin(), read.end(), q) != read.end();
  };
  near_singular_ = model.nonlinear && model.constraint_count() > 0 &&
                   (shows(Quantity::reaction) || shows(Quantity::multiplier) ||
                    shows(Quantity::acceleration) || shows(Quantity::absolute_acceleration));
  if (map_ == nullptr) {
    if (!output.points.empty()) {
      throw std::invalid_argument("[output] points needs a mechanism ([model] type = multibody)");
    }
    dofs_ = selected_dofs(output, model.dof_names);
    return;
  }
  displacement_ = selected_dofs(output, map_->names(Quantity::displacement));
  velocity_ = selected_dofs(output, map_->names(Quantity::velocity));
  acceleration_ = selected_dofs(output, map_->names(Quantity::acceleration));
  reaction_ = selected_dofs(output, map_->names(Quantity::reaction));
  points_ = point_indices(*map_, output.points);
  point_columns_ = condyn::point_columns(*map_, output.points);
}

const std::vector<int>& OutputColumns::shown(Quantity q) const {
  if (map_ == nullptr) return has_dof_columns(q) ? dofs_ : none_;
  switch (q) {
    case Quantity::displacement:
      return displacement_;
    case Quantity::velocity:
      return velocity_;
    case Quantity::acceleration:
      return acceleration_;
    case Quantity::reaction:
      return reaction_;
    default:  // absolute_acceleration: build_model refuses it for a mapped model
      return none_;
  }
}

std::string OutputColumns::name(Quantity q, int index) const {
  const auto i = static_cast<std::size_t>(index);
  if (map_ == nullptr) return dof_prefix(q) + model_.dof_names[i];
  return map_->names(q)[i];
}

std::vector<std::string> OutputColumns::shown_names(Quantity q) const {
  std::vector<std::string> out;
  const auto& all = map_ == nullptr ? model_.dof_names : map_->names(q);
  for (int c : shown(q)) out.push_back(all[static_cast<std::size_t>(c)]);
  return out;
}

}  // namespace condyn
