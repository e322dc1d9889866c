#pragma once
/// The columns a run's result file shows, for the CSV and HDF5 writers. A model without an
/// OutputMap shows a column per DOF (`ux1`, `vel_ux1`, `acc_ux1`, `acc_abs_ux1`,
/// `reaction_ux1`); a model with one (a mechanism: models/core/output_map.hpp) shows the map's
/// columns instead (`crank.x`, `crank.vx`, `crank.ax`, `hinge.fx`) and, for [output] points, the
/// named points' positions (`crank.B.x`) after every quantity's columns. [output] dofs selects
/// among each quantity's columns by name; the multipliers, drift and energy columns are the same
/// for both. A run that watches for singular configurations and writes reactions, multipliers or
/// accelerations ends each row with the flag `near_singular` (1 inside a passage, else 0).

#include <string>
#include <vector>

#include "dae/run/mapped_rows.hpp"
#include "models/core/model.hpp"
#include "models/scene/scene_spec.hpp"

namespace condyn {

/// Which columns of each quantity a run of `model` shows under `output`, and their names.
class OutputColumns {
 public:
  /// `output.dofs` selects per quantity: without a map, the DOFs whose names match (the same
  /// for every quantity); with one, the columns of each quantity whose own names match (so
  /// `crank.*` selects crank's pose, velocity and acceleration, `hinge.*` that joint's
  /// reaction). `output.points` names the map's points (build_model refuses unknown ones):
  /// std::invalid_argument for one the map does not have, or for points without a map.
  OutputColumns(const Model& model, const OutputSpec& output);

  /// True when the model's OutputMap gives the columns.
  [[nodiscard]] bool mapped() const { return map_ != nullptr; }
  /// The shown columns of q (displacement, velocity, acceleration, absolute_acceleration,
  /// reaction; none for another quantity): ascending indices into its row vector (the DOFs,
  /// or the map's columns).
  [[nodiscard]] const std::vector<int>& shown(Quantity q) const;
  /// Column `index` of q's as the CSV header writes it: the DOF name with q's prefix (`vel_ux1`),
  /// or the map's name (`crank.vx`).
  [[nodiscard]] std::string name(Quantity q, int index) const;
  /// The names of q's shown columns (HDF5's name datasets): without the CSV prefix.
  [[nodiscard]] std::vector<std::string> shown_names(Quantity q) const;
  /// The map's indices of the [output] points, in order.
  [[nodiscard]] const std::vector<int>& points() const { return points_; }
  /// Their columns' names, `body.point.x`, `.y` (`.z`): dimension() per point.
  [[nodiscard]] const std::vector<std::string>& point_columns() const { return point_columns_; }
  [[nodiscard]] const Model& model() const { return model_; }
  /// The model's map, or null.
  [[nodiscard]] const OutputMap* map() const { return map_; }
  /// True when the rows end with the `near_singular` flag: the model's constraint Jacobian
  /// depends on the state (its runs watch for singular configurations,
  /// dae/run/singular_passages.hpp) and the output shows a quantity that is unreliable there
  /// (reaction, multiplier, acceleration), itself or through a [[derived]] column.
  [[nodiscard]] bool near_singular() const { return near_singular_; }

 private:
  const Model& model_;
  const OutputMap* map_ = nullptr;
  std::vector<int> dofs_;  ///< without a map: the DOFs shown, for every quantity
  /// With a map: displacement, velocity, acceleration, reaction.
  std::vector<int> displacement_, velocity_, acceleration_, reaction_, none_;
  std::vector<int> points_;
  std::vector<std::string> point_columns_;
  bool near_singular_ = false;
};

}  // namespace condyn
