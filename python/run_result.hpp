#pragma once
/// A finished run (SolveResult) → the dict the Python module returns: numpy arrays over the
/// trajectory's own memory (moved, not copied: an n x nt column-major Eigen matrix is an nt x n
/// row-major array), names and the summary. Needs the GIL.

#include <pybind11/pybind11.h>

#include "dae/run/solve_result.hpp"
#include "models/core/model.hpp"
#include "models/core/solve_spec.hpp"
#include "models/scene/scene_spec.hpp"

namespace condyn::python {

/// Keys t, u, v, reaction, multiplier, drift, a (or None), a_abs (u'' + r a_g(t) when `output`
/// asks for absolute_acceleration, else None), energy and kinetic (or None), dof_names,
/// velocity_names, acceleration_names, reaction_names, points (or None), point_names,
/// constraint_names, derived (nt x k: the [[derived]] columns) and derived_names, summary. A
/// mechanism's u, v, a and reaction hold its output map's columns (dae/run/mapped_rows.hpp) and
/// points its [output] points. `result` is moved from.
[[nodiscard]] pybind11::dict result_dict(SolveResult&& result, const Model& model,
                                         const SolveSpec& settings, const BuildReport& report,
                                         const OutputSpec& output);

}  // namespace condyn::python
