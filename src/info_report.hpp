#pragma once
/// `condyn info`: constraint classes, model size, the scheme the scene selects.

#include <ostream>

#include "models/model.hpp"

namespace condyn {

void print_info(std::ostream& out, const Model& model, Scheme requested);

}  // namespace condyn
