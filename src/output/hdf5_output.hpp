#pragma once
/// HDF5 output (scene-format.md, "Output"): chosen by the `.h5` extension (or `.hdf5`, `.hdf`:
/// src/output/output_format.hpp). One dataset per
/// quantity (`t`; `displacement`, `velocity`, `reaction` as nt x n over the [output] dofs;
/// `multiplier` nt x m; `drift` nt x 2; `energy` nt x 2: energy and its error), the names as string
/// datasets `dof_names` and `constraint_names`, and the scheme, rtol and atol as attributes of the
/// root group. The file is built in memory and written through the caller's stream, so it goes
/// through the same checked, atomic commit as a CSV.

#include <ostream>
#include <string>

#include "dae/run/trajectory.hpp"
#include "models/core/model.hpp"
#include "models/scene/scene_spec.hpp"

namespace condyn {

/// What the HDF5 file says about the run besides its data (root attributes).
struct RunAttributes {
  std::string scheme;
  double rtol = 0.0, atol = 0.0;
  /// "mixed" or "multipliers" (treatment_name); empty: no attribute (not a multiplier scheme).
  std::string constraints;
};

/// The attributes of a run of `model` under `settings`, `resolved` the scheme that ran (the
/// plan's, SolveResult::scheme).
[[nodiscard]] RunAttributes run_attributes(const Model& model, const SolveSpec& settings,
                                           Scheme resolved);

/// Writes the HDF5 file of `traj` to `out`. Throws std::runtime_error when the HDF5 library
/// fails (the message names the call).
void write_hdf5(std::ostream& out, const Model& model, const OutputSpec& output,
                const RunAttributes& run, const Trajectory& traj);

}  // namespace condyn
