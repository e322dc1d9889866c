#pragma once
/// [[derived]] columns (docs/scenes.md, "Derived columns"): a named linear combination of a
/// run's displacement, velocity, acceleration (relative or, under [ground_motion], absolute) and
/// reaction columns, Σ cₖ · columnₖ, written as a
/// column of its own by every output and read by [[check]], plot and sweep like any column. The
/// builder resolves each term's column once (models/assembly/derived_columns.cpp, a term naming
/// an earlier derived column expanded into that column's terms); a row's value is then a few
/// multiply-adds over the row's vectors, computed as the row is written.

#include <Eigen/Dense>
#include <string>
#include <vector>

#include "models/core/output_quantity.hpp"

namespace condyn {

/// coefficient × entry `index` of the row's `quantity` vector (displacement, velocity,
/// acceleration, absolute acceleration or reaction: a DOF, or a mechanism's output-map column).
struct DerivedTerm {
  Quantity quantity = Quantity::displacement;
  int index = 0;
  double coefficient = 0.0;
};

/// One [[derived]] column: its name and its terms, every one on a column of the run (none on
/// another derived column: those are expanded when the column is built).
struct DerivedColumn {
  std::string name;
  std::vector<DerivedTerm> terms;
};

/// One output row's vectors a derived column reads (`acceleration` may be empty when no derived
/// column reads it; `absolute_acceleration`, Model::absolute_acceleration of the row's
/// acceleration, likewise when none reads it: reads_absolute_acceleration).
struct DerivedInputs {
  Eigen::Ref<const Eigen::VectorXd> u, v, acceleration, absolute_acceleration, reaction;
};

/// Σ coefficient · value of the column's terms at the row. Throws std::logic_error when the row
/// lacks a vector a term reads (the run was not asked for it: derived_quantities).
[[nodiscard]] double derived_value(const DerivedColumn& column, const DerivedInputs& row);

/// Whether a term of `derived` reads the absolute acceleration: the row's writer then computes
/// it (Model::absolute_acceleration, as the acc_abs_ columns are) for DerivedInputs.
[[nodiscard]] bool reads_absolute_acceleration(const std::vector<DerivedColumn>& derived);

/// `quantities` and the quantities `derived` read that it lacks: what a run must compute
/// (hooks_for) and what its rows must carry (reads_reactions), whatever [output] shows.
[[nodiscard]] std::vector<Quantity> with_derived_quantities(
    std::vector<Quantity> quantities, const std::vector<DerivedColumn>& derived);

}  // namespace condyn
