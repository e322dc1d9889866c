#pragma once
/// A finished run (SolveResult) → the dict the Python module returns: numpy arrays over the
/// trajectory's own memory (moved, not copied: an n x nt column-major Eigen matrix is an nt x n
/// row-major array), names and the summary. Needs the GIL.

#include <pybind11/pybind11.h>

#include "dae/run/solve_result.hpp"
#include "models/core/model.hpp"
#include "models/core/solve_spec.hpp"

namespace condyn::python {

/// Keys t, u, v, reaction, multiplier, drift, a (or None), a_abs (u'' + r a_g(t) when
/// `absolute_acceleration`, else None), energy and kinetic (or None), dof_names,
/// constraint_names, summary. `result` is moved from.
[[nodiscard]] pybind11::dict result_dict(SolveResult&& result, const Model& model,
                                         const SolveSpec& settings, const BuildReport& report,
                                         bool absolute_acceleration);

}  // namespace condyn::python
