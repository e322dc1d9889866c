#pragma once
/// A run's columns by name, as its CSV writes them: which quantity and entry a name is, every
/// name a run of a model can write, and the refusal of a name it cannot (with the nearest names).
/// What [[check]] (validation/studies/user_checks.hpp) and [[derived]]
/// (models/assembly/derived_columns.cpp) resolve their column names with.

#include <optional>
#include <string>
#include <vector>

#include "models/core/model.hpp"

namespace condyn {

/// Where a named column comes from in a row.
struct ResultColumn {
  Quantity quantity = Quantity::displacement;
  /// The DOF (a mechanism's column of the quantity), the constraint, drift position/velocity
  /// (0/1), kEnergyColumns; for a named point, its axis (0, 1, 2 for .x, .y, .z).
  int index = 0;
  int point = -1;    ///< a named point's index in the model's OutputMap, else −1
  int derived = -1;  ///< a [[derived]] column's index in Model::derived, else −1
};

/// The column `name` of a run of `model`, or nothing when no quantity gives it. Column names as
/// the CSV writes them: a DOF's name, vel_, acc_, acc_abs_, reaction_ + DOF (a mechanism's: its
/// output map's columns `crank.x`, `crank.vx`, `crank.ax`, `hinge.fx`, and any named point's
/// `crank.B.x`, listed in [output] points or not), lambda_ + constraint, drift_position,
/// drift_velocity, the energy columns (kEnergyColumns) and the model's [[derived]] columns.
[[nodiscard]] std::optional<ResultColumn> find_column(const Model& model, const std::string& name);

/// The name of entry `index` of `quantity`'s columns (displacement, velocity, acceleration,
/// absolute acceleration or reaction), as the CSV writes it: "vel_u3", a mechanism's "crank.vx".
[[nodiscard]] std::string column_name(const Model& model, Quantity quantity, int index);

/// Every column a run of the model can write (under some quantity; a mechanism's named points
/// are not listed: its map does not enumerate them), [[derived]] columns included.
[[nodiscard]] std::vector<std::string> all_columns(const Model& model);

/// "no output column is named 'uz3' (...); the nearest: ux3, uy3": why `name` is no column of
/// the model, with the names a typo most likely meant among `candidates` (nearest_names).
[[nodiscard]] std::string unknown_column(const Model& model, const std::string& name,
                                         const std::vector<std::string>& candidates);

}  // namespace condyn
