#include "src/output/hdf5_modes.hpp"

#include <hdf5.h>

#include <cstdint>

#include "src/output/hdf5_parts.hpp"

namespace condyn {

void write_modes_hdf5(std::ostream& out, const SceneModes& s) {
  const NaturalModes& m = s.modes;
  const hdf5::MemoryFile file;
  const hid_t f = file.id();
  const auto count = static_cast<hsize_t>(m.omega.size());
  // The table's columns, each value computed as the CSV's (write_table in modes_command.cpp).
  const auto column = [&](const char* name, const auto& value) {
    hdf5::put_matrix(f, name, count, 0,
                     [&](hsize_t j, hsize_t) { return value(static_cast<Eigen::Index>(j)); });
  };
  column("mode", [](Eigen::Index j) { return static_cast<std::int64_t>(j + 1); });
  column("omega", [&](Eigen::Index j) { return m.omega[j]; });
  column("frequency", [&](Eigen::Index j) { return mode_frequency(m.omega[j]); });
  column("period", [&](Eigen::Index j) { return mode_period(m.omega[j]); });
  if (s.ground_motion) {
    column("mass_ratio", [&](Eigen::Index j) { return m.mass_ratio[j]; });
    column("mass_ratio_cumulative", [&](Eigen::Index j) { return m.mass_ratio_cumulative[j]; });
  }
  hdf5::put_matrix(f, "shapes", static_cast<hsize_t>(m.shapes.rows()), count,
                   [&](hsize_t i, hsize_t j) {
                     return m.shapes(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j));
                   });
  hdf5::put_strings(f, "dof_names", s.dof_names);
  hdf5::put_attribute(f, "solver", std::string(m.dense ? "dense" : "lanczos"));
  hdf5::put_attribute(f, "available", static_cast<std::int64_t>(m.available));
  if (s.ground_motion) hdf5::put_attribute(f, "total_mass", m.total_mass);
  file.write_to(out);
}

}  // namespace condyn
