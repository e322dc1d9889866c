#pragma once
/// A scene's natural modes (validation/studies/scene_modes.hpp) → the dict condyn.modes returns:
/// numpy arrays (copies) and names. Needs the GIL.

#include <pybind11/pybind11.h>

#include "validation/studies/scene_modes.hpp"

namespace condyn::python {

/// Keys omega, frequency, period (count each), mass_ratio and mass_ratio_cumulative (count each,
/// or None without [ground_motion]), total_mass (or None), shapes (n x count, φᵀMφ = 1),
/// dof_names, available (the modes the constrained model has), solver ("dense" or "lanczos").
[[nodiscard]] pybind11::dict modes_dict(const SceneModes& modes);

}  // namespace condyn::python
