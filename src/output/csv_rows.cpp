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

std::string csv_header(const Model& model, const OutputSpec& output,
                       const std::vector<int>& shown) {
  std::string line = "t";
  const auto names = [&](const char* prefix) {
    for (int d : shown)
      line.append(",").append(prefix).append(model.dof_names[static_cast<std::size_t>(d)]);
  };
  for (Quantity quantity : output.quantities) {
    switch (quantity) {
      case Quantity::displacement:
        names("");
        break;
      case Quantity::velocity:
        names("vel_");
        break;
      case Quantity::acceleration:
        names("acc_");
        break;
      case Quantity::absolute_acceleration:
        names("acc_abs_");
        break;
      case Quantity::reaction:
        names("reaction_");
        break;
      case Quantity::multiplier:
        for (const auto& c : model.constraints) line.append(",lambda_").append(c.name);
        break;
      case Quantity::drift:
        line += ",drift_position,drift_velocity";
        break;
      case Quantity::energy:
        for (const auto column : kEnergyColumns) line.append(",").append(column);
        break;
    }
  }
  return line;
}

void append_csv_row(std::string& line, const OutputSpec& output, const std::vector<int>& shown,
                    const CsvRow& row) {
  append_number(line, row.t);
  const auto value = [&](double v) {
    line += ',';
    append_number(line, v);
  };
  const auto dofs = [&](const Eigen::Ref<const Eigen::VectorXd>& x) {
    for (int d : shown) value(x[d]);
  };
  for (Quantity quantity : output.quantities) {
    switch (quantity) {
      case Quantity::displacement:
        dofs(row.u);
        break;
      case Quantity::velocity:
        dofs(row.v);
        break;
      case Quantity::acceleration:
        dofs(row.acceleration);
        break;
      case Quantity::absolute_acceleration:
        dofs(row.absolute_acceleration);
        break;
      case Quantity::reaction:
        dofs(row.reaction);
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
}

}  // namespace condyn
