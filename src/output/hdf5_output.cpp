#include "src/output/hdf5_output.hpp"

#include <hdf5.h>

#include "dae/run/scheme_choice.hpp"
#include "src/output/hdf5_parts.hpp"

#include <optional>
#include <stdexcept>
#include <vector>

namespace condyn {

namespace {

using hdf5::put_matrix;
using hdf5::put_strings;

/// The [[derived]] columns: `derived` (nt x k) and their names `derived_names`.
void put_derived(hid_t file, const Model& model, const Trajectory& traj) {
  const Eigen::VectorXd none;
  // k x nt, a row's values computed together (its absolute acceleration once).
  Eigen::MatrixXd values(static_cast<Eigen::Index>(model.derived.size()),
                         static_cast<Eigen::Index>(traj.t.size()));
  for (Eigen::Index k = 0; k < values.cols(); ++k) {
    const Eigen::Ref<const Eigen::VectorXd> a =
        traj.acceleration.cols() > k ? Eigen::Ref<const Eigen::VectorXd>(traj.acceleration.col(k))
                                     : Eigen::Ref<const Eigen::VectorXd>(none);
    values.col(k) = model.derived_values(traj.t[static_cast<std::size_t>(k)], traj.u.col(k),
                                         traj.v.col(k), a, traj.reaction.col(k));
  }
  put_matrix(file, "derived", traj.t.size(), model.derived.size(), [&](hsize_t r, hsize_t c) {
    return values(static_cast<Eigen::Index>(c), static_cast<Eigen::Index>(r));
  });
  std::vector<std::string> names;
  for (const auto& d : model.derived) names.push_back(d.name);
  put_strings(file, "derived_names", names);
}

}  // namespace

RunAttributes run_attributes(const Model& model, const SolveSpec& settings, Scheme resolved) {
  const char* treatment = treatment_name(model, resolved, settings);
  return {to_string(resolved), settings.rtol, settings.atol, treatment != nullptr ? treatment : ""};
}

void write_hdf5(std::ostream& out, const Model& model, const OutputSpec& output,
                const RunAttributes& run, const Trajectory& whole) {
  const hdf5::MemoryFile file;
  const hid_t f = file.id();
  const OutputColumns columns(model, output);
  // A mechanism's rows in its output map's columns (a copy: the caller's trajectory stays).
  std::optional<Trajectory> mapped;
  if (columns.mapped())
    mapped = mapped_trajectory(
        model, whole, columns.points(),
        reads_reactions(with_derived_quantities(output.quantities, model.derived)));
  const Trajectory& traj = mapped ? *mapped : whole;
  const auto nt = static_cast<hsize_t>(traj.t.size());
  put_matrix(f, "t", nt, 0, [&](hsize_t r, hsize_t) { return traj.t[r]; });
  const auto dofs = [&](const char* name, Quantity q, const Eigen::MatrixXd& m) {
    const std::vector<int>& shown = columns.shown(q);
    put_matrix(f, name, nt, shown.size(),
               [&](hsize_t r, hsize_t c) { return m(shown[c], static_cast<Eigen::Index>(r)); });
  };
  for (Quantity q : output.quantities) {
    switch (q) {
      case Quantity::displacement:
        dofs("displacement", Quantity::displacement, traj.u);
        break;
      case Quantity::velocity:
        dofs("velocity", Quantity::velocity, traj.v);
        break;
      case Quantity::acceleration:
        dofs("acceleration", Quantity::acceleration, traj.acceleration);
        break;
      case Quantity::absolute_acceleration: {
        Eigen::MatrixXd absolute(traj.acceleration.rows(), traj.acceleration.cols());
        for (Eigen::Index k = 0; k < absolute.cols(); ++k) {
          absolute.col(k) = model.absolute_acceleration(traj.t[static_cast<std::size_t>(k)],
                                                        traj.acceleration.col(k));
        }
        dofs("absolute_acceleration", Quantity::absolute_acceleration, absolute);
        break;
      }
      case Quantity::reaction:
        dofs("reaction", Quantity::reaction, traj.reaction);
        break;
      case Quantity::multiplier:
        put_matrix(f, "multiplier", nt, static_cast<hsize_t>(traj.multiplier.rows()),
                   [&](hsize_t r, hsize_t c) {
                     return traj.multiplier(static_cast<Eigen::Index>(c),
                                            static_cast<Eigen::Index>(r));
                   });
        break;
      case Quantity::drift:
        put_matrix(f, "drift", nt, 2, [&](hsize_t r, hsize_t c) {
          const auto k = static_cast<Eigen::Index>(r);
          return c == 0 ? traj.drift_position[k] : traj.drift_velocity[k];
        });
        break;
      case Quantity::energy:  // build_model refuses 'energy' where no balance can be drawn
        if (traj.balance.size() != nt) throw std::logic_error("energy rows without a balance");
        put_matrix(f, "energy", nt, kEnergyColumns.size(),
                   [&](hsize_t r, hsize_t c) { return energy_column(traj.balance[r], c); });
        put_strings(f, "energy_columns", energy_column_names());
        break;
    }
  }
  if (!columns.points().empty()) {
    put_matrix(f, "points", nt, static_cast<hsize_t>(traj.points.rows()),
               [&](hsize_t r, hsize_t c) {
                 return traj.points(static_cast<Eigen::Index>(c), static_cast<Eigen::Index>(r));
               });
  }
  if (!model.derived.empty()) {
    put_derived(f, model, traj);
  }
  if (columns.near_singular()) {
    put_matrix(f, "near_singular", nt, 0, [&](hsize_t r, hsize_t) {
      return traj.near_singular.size() > r && traj.near_singular[r] ? 1.0 : 0.0;
    });
  }
  hdf5::put_column_names(f, columns);
  hdf5::put_run_attributes(f, run);
  file.write_to(out);
}

}  // namespace condyn
