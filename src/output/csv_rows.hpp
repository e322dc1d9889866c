#pragma once
/// The CSV of the contract (scene-format.md, "Output"), one line at a time: the header, and a data
/// row from one output time's values. Used by the whole-trajectory writer and by the row writer
/// of a streamed run alike, so both write the same bytes.

#include <Eigen/Dense>
#include <string>
#include <vector>

#include "dae/run/energy_balance.hpp"
#include "models/core/model.hpp"
#include "models/scene/scene_spec.hpp"
#include "src/output/output_columns.hpp"

namespace condyn {

/// One output time's values, viewed (columns of a trajectory or a streamed row).
struct CsvRow {
  double t = 0.0;
  /// `acceleration` may be empty when the output does not ask for it.
  /// `absolute_acceleration` (u'' + r a_g under ground motion) may be empty when not asked for.
  Eigen::Ref<const Eigen::VectorXd> u, v, acceleration, absolute_acceleration, reaction, multiplier;
  double drift_position = 0.0, drift_velocity = 0.0;
  /// The energy balance (docs/energy.md) when the output asks for `energy`.
  const EnergyBalance* balance = nullptr;
  /// A mapped row's named points (OutputColumns::point_columns), written after every quantity.
  Eigen::Ref<const Eigen::VectorXd> points;
  /// Inside a passage near a singular configuration: the last column, where
  /// OutputColumns::near_singular.
  bool near_singular = false;
};

/// "t,..." for the [output] quantities over the columns shown, then the named points' columns, the
/// [[derived]] columns (Model::derived) and the `near_singular` flag
/// (OutputColumns::near_singular), without the newline.
[[nodiscard]] std::string csv_header(const OutputSpec& output, const OutputColumns& columns);

/// Appends the data row (without newline) to `line`; numbers in the shortest form that reads back
/// as the same double. A mapped model's row holds the map's columns (MappedRows). The derived
/// columns are computed here from the row's vectors, which must then hold what they read
/// (with_derived_quantities), whether [output] shows it or not.
void append_csv_row(std::string& line, const OutputSpec& output, const OutputColumns& columns,
                    const CsvRow& row);

/// Appends v in the shortest round-trip form (std::to_chars).
void append_number(std::string& line, double v);

}  // namespace condyn
