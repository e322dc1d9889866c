// A run's columns by name (models/core/result_columns.hpp).

#include "models/core/result_columns.hpp"

#include <algorithm>
#include <stdexcept>
#include <string_view>
#include <utility>

#include "models/core/nearest_names.hpp"

namespace condyn {

namespace {

/// The quantities whose columns a mechanism's output map names.
constexpr Quantity kMappedQuantities[] = {Quantity::displacement, Quantity::velocity,
                                          Quantity::acceleration, Quantity::reaction};

/// A mechanism's column `name`: one of its output map's, or a named point's `body.point.x`.
std::optional<ResultColumn> find_mapped_column(const OutputMap& map, const std::string& name) {
  for (Quantity q : kMappedQuantities) {
    const auto& names = map.names(q);
    const auto it = std::find(names.begin(), names.end(), name);
    if (it != names.end()) return ResultColumn{q, static_cast<int>(it - names.begin())};
  }
  const std::size_t dot = name.rfind('.');
  if (dot == std::string::npos) return std::nullopt;
  const std::string axis = name.substr(dot);
  for (int k = 0; k < map.dimension(); ++k) {
    if (axis != std::string(".") + static_cast<char>('x' + k)) continue;
    if (const auto point = map.point(std::string_view(name).substr(0, dot))) {
      return ResultColumn{Quantity::displacement, k, *point};
    }
  }
  return std::nullopt;
}

}  // namespace

std::string column_name(const Model& model, Quantity quantity, int index) {
  const auto i = static_cast<std::size_t>(index);
  if (model.outputs) return model.outputs->names(quantity).at(i);
  const std::string& dof = model.dof_names.at(i);
  switch (quantity) {
    case Quantity::displacement:
      return dof;
    case Quantity::velocity:
      return "vel_" + dof;
    case Quantity::acceleration:
      return "acc_" + dof;
    case Quantity::absolute_acceleration:
      return "acc_abs_" + dof;
    case Quantity::reaction:
      return "reaction_" + dof;
    default:
      break;
  }
  throw std::logic_error("column_name: not a quantity of one column per DOF");
}

std::vector<std::string> all_columns(const Model& model) {
  std::vector<std::string> out = {"drift_position", "drift_velocity"};
  for (const auto column : kEnergyColumns) out.emplace_back(column);
  if (model.outputs) {
    for (Quantity q : kMappedQuantities) {
      const auto& names = model.outputs->names(q);
      out.insert(out.end(), names.begin(), names.end());
    }
  } else {
    for (const auto& d : model.dof_names) {
      for (const char* prefix : {"", "vel_", "acc_", "acc_abs_", "reaction_"}) {
        if (std::string_view(prefix) == "acc_abs_" && !model.ground) continue;
        out.push_back(prefix + d);
      }
    }
  }
  for (const auto& c : model.constraints) out.push_back("lambda_" + c.name);
  for (const auto& d : model.derived) out.push_back(d.name);
  return out;
}

std::string unknown_column(const Model& model, const std::string& name,
                           const std::vector<std::string>& candidates) {
  for (const auto& c : model.dropped_constraints) {
    if (name == "lambda_" + c) {
      return "constraint '" + c +
             "' was dropped as redundant ([solve] redundant = \"drop\"): it has no multiplier, "
             "and its reaction is carried by the constraints it combines";
    }
  }
  const std::vector<std::string> near = nearest_names(name, candidates);
  return "no output column is named '" + name +
         (model.outputs ? std::string("' (columns are a mechanism's body and joint columns "
                                      "such as crank.x, crank.vx, crank.ax, hinge.fx, a named "
                                      "point's crank.B.x, lambda_ and a constraint, ")
                        : std::string("' (columns are a DOF's name, vel_, acc_, acc_abs_ or "
                                      "reaction_ and a DOF, lambda_ and a constraint, ")) +
         "drift_position, drift_velocity, energy, energy_error and the other energy columns, "
         "and the [[derived]] columns); " +
         (near.empty() ? std::string("no column's name is near it")
                       : "the nearest: " + joined_names(near));
}

std::optional<ResultColumn> find_column(const Model& model, const std::string& name) {
  if (name == "drift_position") return ResultColumn{Quantity::drift, 0};
  if (name == "drift_velocity") return ResultColumn{Quantity::drift, 1};
  for (std::size_t k = 0; k < kEnergyColumns.size(); ++k) {
    if (name == kEnergyColumns[k]) return ResultColumn{Quantity::energy, static_cast<int>(k)};
  }
  for (std::size_t k = 0; k < model.derived.size(); ++k) {
    if (name == model.derived[k].name) {
      return ResultColumn{Quantity::displacement, 0, -1, static_cast<int>(k)};
    }
  }
  if (name.rfind("lambda_", 0) == 0) {
    const std::string c = name.substr(7);
    for (std::size_t i = 0; i < model.constraints.size(); ++i) {
      if (model.constraints[i].name == c) {
        return ResultColumn{Quantity::multiplier, static_cast<int>(i)};
      }
    }
  }
  if (model.outputs) return find_mapped_column(*model.outputs, name);
  const auto dof = [&](const std::string& d) -> int {
    const auto it = std::find(model.dof_names.begin(), model.dof_names.end(), d);
    return it == model.dof_names.end() ? -1 : static_cast<int>(it - model.dof_names.begin());
  };
  if (const int d = dof(name); d >= 0) return ResultColumn{Quantity::displacement, d};
  for (const auto& [prefix, quantity] :
       {std::pair<std::string, Quantity>{"vel_", Quantity::velocity},
        {"acc_abs_", Quantity::absolute_acceleration},
        {"acc_", Quantity::acceleration},
        {"reaction_", Quantity::reaction}}) {
    if (name.rfind(prefix, 0) == 0) {
      if (const int d = dof(name.substr(prefix.size())); d >= 0) return ResultColumn{quantity, d};
    }
  }
  return std::nullopt;
}

}  // namespace condyn
