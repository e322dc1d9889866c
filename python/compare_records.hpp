#pragma once
/// `condyn compare`'s sweep (validation/studies/compare.hpp) → one Python dict per (scheme, rtol)
/// run.

#include <pybind11/pybind11.h>

#include "validation/studies/compare.hpp"

namespace condyn::python {

/// Each run's scheme, rtol, atol, ok, message, errors (error_u, error_v, error_reaction, against
/// `reference`), drifts, costs, wall times, mescd_u/v and energy_error (None where not defined);
/// a scheme that cannot treat the scene gives one dict with skipped = True and the reason.
[[nodiscard]] pybind11::list compare_records(const CompareResult& result);

}  // namespace condyn::python
