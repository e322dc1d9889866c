// The contract's CSV, a line at a time (src/output/csv_rows.hpp).

#include "src/output/csv_rows.hpp"

#include <array>
#include <charconv>
#include <stdexcept>

namespace condyn {

/// Shortest round-trip form: exact, and much cheaper than a 17-digit printf, whose formatting
/// weighed on a large run's writing (docs/benchmarks.md).
void append_number(std::string& line, double v) {
  std::array<char, 32> buf{};
  const auto end = std::to_chars(buf.data(), buf.data() + buf.size(), v).ptr;
  line.append(buf.data(), end);
}

std::string csv_header(const OutputSpec& output, const OutputColumns& columns) {
  std::string line = "t";
  for (Quantity quantity : output.quantities) {
    switch (quantity) {
      case Quantity::displacement:
      case Quantity::velocity:
      case Quantity::acceleration:
      case Quantity::absolute_acceleration:
      case Quantity::reaction:
        for (int c : columns.shown(quantity)) line.append(",").append(columns.name(quantity, c));
        break;
      case Quantity::multiplier:
        for (const auto& c : columns.model().constraints) line.append(",lambda_").append(c.name);
        break;
      case Quantity::drift:
        line += ",drift_position,drift_velocity";
        break;
      case Quantity::energy:
        for (const auto column : kEnergyColumns) line.append(",").append(column);
        break;
    }
  }
  for (const auto& name : columns.point_columns()) line.append(",").append(name);
  for (const auto& derived : columns.model().derived) line.append(",").append(derived.name);
  if (columns.near_singular()) line += ",near_singular";
  return line;
}

void append_csv_row(std::string& line, const OutputSpec& output, const OutputColumns& columns,
                    const CsvRow& row) {
  append_number(line, row.t);
  const auto value = [&](double v) {
    line += ',';
    append_number(line, v);
  };
  const auto dofs = [&](Quantity q, const Eigen::Ref<const Eigen::VectorXd>& x) {
    for (int d : columns.shown(q)) value(x[d]);
  };
  for (Quantity quantity : output.quantities) {
    switch (quantity) {
      case Quantity::displacement:
        dofs(Quantity::displacement, row.u);
        break;
      case Quantity::velocity:
        dofs(Quantity::velocity, row.v);
        break;
      case Quantity::acceleration:
        dofs(Quantity::acceleration, row.acceleration);
        break;
      case Quantity::absolute_acceleration:
        dofs(Quantity::absolute_acceleration, row.absolute_acceleration);
        break;
      case Quantity::reaction:
        dofs(Quantity::reaction, row.reaction);
        break;
      case Quantity::multiplier:
        for (Eigen::Index i = 0; i < row.multiplier.size(); ++i) value(row.multiplier[i]);
        break;
      case Quantity::drift:
        value(row.drift_position);
        value(row.drift_velocity);
        break;
      case Quantity::energy:  // build_model refuses 'energy' where no balance can be drawn
        if (row.balance == nullptr) throw std::logic_error("an energy column without a balance");
        for (std::size_t k = 0; k < kEnergyColumns.size(); ++k) {
          value(energy_column(*row.balance, k));
        }
        break;
    }
  }
  for (Eigen::Index k = 0; k < row.points.size(); ++k) value(row.points[k]);
  if (!columns.model().derived.empty()) {
    const Eigen::VectorXd derived = columns.model().derived_values(
        row.t, row.u, row.v, row.acceleration, row.reaction, row.absolute_acceleration);
    for (const double d : derived) value(d);
  }
  if (columns.near_singular()) line += row.near_singular ? ",1" : ",0";
}

}  // namespace condyn
