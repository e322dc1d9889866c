#pragma once
/// `condyn info`: constraint classes, model size, the scheme the scene selects.

#include <ostream>

#include "models/core/model.hpp"
#include "models/core/solve_spec.hpp"

namespace condyn {

/// The report on `model`, what its build reported, and the run `settings` (settings.scheme: the
/// scheme asked for). The constraint table lists every row when `every_constraint`, else up to
/// 60 rows, and beyond that the first 40 and a count per class.
void print_info(std::ostream& out, const Model& model, const BuildReport& report,
                const SolveSpec& settings, bool every_constraint = false);

}  // namespace condyn
