#pragma once
/// The HDF5 file of `condyn modes --out FILE.h5` (docs/cli.md, "condyn modes"): the modes table
/// and the mode shapes in one file, laid out as a run's result is (one dataset per quantity, names
/// in string datasets, what describes the computation as root attributes):
///   mode (K, 64-bit integers 1..K), omega, frequency, period (K each; period inf for a
///   zero-frequency mode), and under [ground_motion] mass_ratio and mass_ratio_cumulative (K
///   each): the columns of the CSV table, the same doubles;
///   shapes (n x K, row i the DOF dof_names[i], column j mode j + 1, φᵀMφ = 1) and dof_names (n):
///   the CSV of --shapes;
///   root attributes solver ("dense" or "lanczos"), available (the modes the constrained model
///   has) and, under [ground_motion], total_mass (along the influence vector).

#include <ostream>

#include "validation/studies/scene_modes.hpp"

namespace condyn {

/// Writes the modes file of `modes` to `out` (built in memory, written as one image, as
/// write_hdf5). Throws std::runtime_error when the HDF5 library fails (the message names the call).
void write_modes_hdf5(std::ostream& out, const SceneModes& modes);

}  // namespace condyn
