#pragma once
/// `condyn info`: constraint classes, model size, the scheme the scene selects.

#include <ostream>

#include "models/model.hpp"

namespace condyn {

/// The report on `model`, what its build reported, and the run `settings` (settings.scheme: the
/// scheme asked for).
void print_info(std::ostream& out, const Model& model, const BuildReport& report,
                const SolveSpec& settings);

}  // namespace condyn
